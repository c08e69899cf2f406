#pragma once
// The collision kernel's recorded traversal (robocore/collision/
// tree_collision.h: CollisionBatch, one NodeVisit per node fetch) as the
// KernelRecord every backend prices, for the shipped SACT program
// programs/sact_obb_aabb.asm (StepProgramKind::kSactTest).
//
// The mapping is the one tree_collision.h documents:
//   region   the flat node array {base_address, node_bytes, node_count}
//   query i  its visits in order; address = batch.Address(visit)
//   exit     visit.exit when an axis separated (0..14: the program's
//            RETURN_IF #k follows the k-th axis test in sact.h's stage
//            order, A0..A2, B0..B2, then the nine edge axes), kNoExit when
//            the node overlapped (the program runs every axis, then PUSH).
// Visits decided by a sphere pre-test ran no SACT stage and the shipped
// program has no sphere section, so a batch with sphere pre-tests is
// rejected rather than priced wrongly.
#include <cstdint>
#include <memory>

#include "robocore/collision/tree_collision.h"
#include "robocore/kernel_record.h"

namespace rc {

// Throws std::invalid_argument if the batch used sphere pre-tests.
KernelRecord SactKernelRecord(const CollisionBatch& batch);

// The same fetches with another step program and every node exit passed
// through `remap` (an exit of the shipped program, or kNoExit, to an exit of
// `program`): how a SACT datapath variant is priced on the same traversal
// (sact_datapath_variants.h).
template <typename Remap>
KernelRecord WithProgram(const KernelRecord& record, std::shared_ptr<const MicroProgram> program, Remap&& remap) {
  KernelRecord out = record;
  out.program = std::move(program);
  for (std::uint8_t& exit : out.node_exits) exit = remap(exit);
  out.Validate();
  return out;
}

}  // namespace rc
