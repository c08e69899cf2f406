#pragma once
// The collision kernel's recorded traversal (tree_collision.h:
// CollisionBatch, one NodeVisit per node fetch) as the KernelRecord every
// backend prices: for the OBB robot, the SACT program
// (programs/sact_obb_aabb.asm, StepProgramKind::kSactTest); for the sphere
// robot, the sphere program (programs/sphere_aabb.asm,
// StepProgramKind::kSphereTest).
//
// The mapping is the one tree_collision.h documents:
//   region   the flat node array {base_address, node_bytes, node_count},
//            FetchKind::kTreeNode
//   query i  its visits in order; address = batch.Address(visit)
//   exit     SACT: visit.exit when an axis separated (0..14: the program's
//            RETURN_IF #k follows the k-th axis test in sact.h's stage
//            order, A0..A2, B0..B2, then the nine edge axes), kNoExit when
//            the node overlapped (the program runs every axis, then PUSH).
//            Sphere: RETURN_IF #0 when the sphere misses the node's box,
//            kNoExit when it meets it.
// Visits decided by a SACT sphere pre-test ran no SACT stage and the SACT
// program has no sphere pre-test section, so a batch with sphere pre-tests
// is rejected rather than priced wrongly.
//
// Compiled into rc_robocore (it needs kernel_record.h's builder and the
// shipped programs); rc_collision itself never links rc_robocore.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "robocore/address_sample.h"
#include "robocore/collision/tree_collision.h"
#include "robocore/kernel_record.h"

namespace rc {

// The node array the batch fetched from, as a record region.
MemoryRegion TreeNodeRegion(const CollisionBatch& batch);
MemoryRegion TreeNodeRegion(std::uint64_t base_address, std::uint32_t node_bytes, std::uint64_t node_count);

// True if `program` keeps the SACT exit contract: a loop whose RETURN_IF #k
// (k = 0..14) comes after the micro-op that tests axis k (BOX k for
// k < 6, EDGE k-6 after), with one PRE before the first axis. Otherwise
// false, with the reason in `why`.
bool KeepsSactExitContract(const MicroProgram& program, std::string* why);

// How a record built from a batch keeps its exits: a byte per fetch
// (node_exits; what the calibration and ExitAt read), or tallied per query
// (tallied_exits, equal to ProfileExits of the per-fetch record, so every
// backend prices the two alike): less to store and no profiling pass when
// the record is priced.
enum class RecordedExits { kPerFetch, kTallied };

// Node counts and exits are kept for every query; `sample` says whose
// addresses are kept (robocore/address_sample.h; the default keeps every
// query's). A sampled record also counts the sectors the whole batch
// touched (every sector of every fetched node), as the memory replay's
// estimate of the unsampled SMs needs (backends/memory_replay.h).
//
// Throws std::invalid_argument if the batch is not an OBB batch, used
// sphere pre-tests, or `program` (default: the shipped SACT program) does
// not keep the SACT exit contract.
KernelRecord SactKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program = nullptr,
                              const AddressSample& sample = AddressSample{},
                              RecordedExits exits = RecordedExits::kPerFetch);

// CollideBatch and SactKernelRecord in one pass, without keeping the visits
// (8 bytes each): the same outcomes, and, when `record` is given, the record
// SactKernelRecord(CollideBatch(tree, obbs, options, base_address), nullptr,
// sample) returns, array for array, except that its exits are tallied per
// query as the traversal runs (KernelRecord::tallied_exits, equal to
// ProfileExits of that record) instead of kept a byte per visit. Parallel
// with OpenMP over blocks of the sample's placement (warp_size x
// warps_per_block queries); each block's tallies and kept addresses go to a
// buffer of its own, joined in launch order, so neither the outcomes nor
// the record depend on the thread count.
// Without `record`, only the outcomes (and their node counts) are computed.
// Buffers in `outcomes` and `record` are reused. Throws
// std::invalid_argument for invalid SACT options or sphere pre-tests (the
// SACT program has no sphere section).
template <typename Scalar>
void CollideBatchRecorded(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                          const CollisionOptions<Scalar>& options, const AddressSample& sample,
                          std::vector<TraversalOutcome>* outcomes, KernelRecord* record,
                          std::uint64_t base_address = kDefaultTreeBase);

// True if `program` keeps the sphere exit contract: a loop with exactly one
// RETURN_IF (#0: the sphere misses the node) and no SACT micro-op.
bool KeepsSphereExitContract(const MicroProgram& program, std::string* why);

// Throws std::invalid_argument if the batch is not a sphere batch
// (CollideSphereBatch) or `program` (default: the shipped sphere program)
// does not keep the sphere exit contract.
KernelRecord SphereKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program = nullptr,
                                const AddressSample& sample = AddressSample{});

// The same fetches with another step program and every node exit passed
// through `remap` (an exit of the shipped program, or kNoExit, to an exit of
// `program`): how a SACT datapath variant is priced on the same traversal
// (backends/calibration/sact_datapath_variants.h).
template <typename Remap>
KernelRecord WithProgram(const KernelRecord& record, std::shared_ptr<const MicroProgram> program, Remap&& remap) {
  if (record.exits_tallied())
    throw std::invalid_argument("WithProgram: a record with tallied exits (CollideBatchRecorded) keeps no pass's own "
                                "exit to remap; price the variant on SactKernelRecord's record");
  KernelRecord out = record;
  out.program = std::move(program);
  for (std::uint8_t& exit : out.node_exits) exit = remap(exit);
  out.Validate();
  return out;
}

}  // namespace rc
