#pragma once
// The recorded work of one kernel batch: what every query did, in a form
// every backend's cost model can price without re-running the kernel
// (DESIGN.md, "run once, price many times").
//
// Per query, in launch order: the nodes it fetched, as device byte
// addresses (base of the structure + index * element size), and for every
// node which RETURN_IF of the step program's loop fired in that node's pass
// (kNoExit when none did). Stored compactly as CSR: fetch_offsets has one
// entry per query plus one; query i's fetches are
// [fetch_offsets[i], fetch_offsets[i+1]).
//
// Addresses may be kept for a sample of the queries only (address_sample,
// robocore/address_sample.h): node counts and exits are always kept for
// every query, which is all the cost models need besides the memory replay.
//
// Memory: 1 byte per fetch (its exit; none with exits per query or tallied)
// + 8 bytes per kept address + 8 bytes per query (+ 8 per block of queries
// with a sample). A Wean-sized DeliBot update (90,000 rays, about 26 nodes
// each) records about 21 MB with every address, 5 MB with one SM of eight
// sampled.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "robocore/address_sample.h"
#include "robocore/exit_profile.h"
#include "robocore/micro_program.h"
#include "robocore/ray_cast.h"
#include "robocore/section_timing.h"

namespace rc {

// The kernel's step program.
enum class StepProgramKind : std::uint8_t {
  kGridMarch,         // march: programs/grid_march.asm
  kDdaStep,           // dda:   programs/dda_step.asm
  kRmStep,            // rm:    programs/rm_step.asm
  kSactTest,          // one OBB-vs-AABB SACT per node: programs/sact_obb_aabb.asm
  kSphereTest,        // one sphere-vs-AABB test per node (sphere robot): programs/sphere_aabb.asm
  kBallQueryPRay,     // ball query, point probe vs state spheres: programs/ball_query_pray.asm
  kBallQueryPSphere,  // ball query, query sphere vs state boxes: programs/ball_query_psphere.asm
};
const char* ToString(StepProgramKind kind);
StepProgramKind StepProgramFor(RayCastMethod method);

enum class LeafProgramKind : std::uint8_t {
  kNone,
  kBeamModel,  // programs/beam_leaf.asm, once per ray after the traversal
  kCustom,     // a leaf given to ConfigRoboCore
};

// Exit contract of the ray-cast step programs: in the last node's loop
// pass, RETURN_IF #0 fires when the cell stops the ray, and RETURN_IF #1
// when the next cell or sample is out of range or off the map.
inline constexpr std::uint8_t kRayHitReturn = 0;
inline constexpr std::uint8_t kRayEndReturn = 1;

// A structure the kernel fetches from, placed in the modelled device's
// address space.
struct MemoryRegion {
  std::string name;
  FetchKind kind = FetchKind::kGridCell;
  std::uint64_t base = 0;           // bytes
  std::uint32_t element_bytes = 0;  // bytes per fetched element
  std::uint64_t elements = 0;
  std::uint64_t bytes() const { return element_bytes * elements; }
};

// Where CastRayBatchRecorded places the structures. The values only have to
// be distinct and aligned; they are not costs. Regions are laid out one
// after another from first_base, each aligned to `alignment`, so the
// footprint is contiguous (which lets a cache model tell from the total size
// whether it fits).
//
// grid_cell_bytes is how the device stores one occupancy cell, which is a
// cost (it sets how many cells share a sector): 1, our CellState byte; 8,
// the RoboGPU artifact's grid of doubles (docs/artifact_preset.md). The
// functional answer does not depend on it.
struct DeviceLayout {
  std::uint64_t first_base = std::uint64_t{1} << 32;  // bytes; away from 0 so a bad address stands out
  std::uint64_t alignment = 4096;                     // bytes; a page
  std::uint32_t grid_cell_bytes = 1;                  // bytes per occupancy cell: 1, 2, 4 or 8
};

struct KernelRecord {
  StepProgramKind step_kind = StepProgramKind::kDdaStep;
  LeafProgramKind leaf_kind = LeafProgramKind::kNone;
  std::shared_ptr<const MicroProgram> program;  // the step program
  std::shared_ptr<const MicroProgram> leaf;     // null when leaf_kind == kNone

  std::vector<MemoryRegion> regions;  // every region a fetch may address
  std::uint32_t node_bytes = 1;       // bytes of one fetched node (one kind per kernel)
  // Bytes of the floating-point scalar the host kernel computed in: 8
  // (double: the ray casters, the ball query, MoveBot's and CarriBot's
  // collision checks) or 4 (a float collision kernel). The SIMT model prices
  // the CUDA kernel of that precision by default (simt.precision = host).
  std::uint8_t scalar_bytes = 8;

  std::vector<std::uint64_t> fetch_offsets{0};  // size queries + 1
  // The RETURN_IF that fired in each node's pass, or kNoExit, in one of
  // three forms (the other two then empty or null):
  //   node_exits     per fetch;
  //   last_exits     per query, for kernels whose loop can exit only in a
  //                  query's last pass (the ray casts; kNoExit for a query
  //                  without nodes);
  //   tallied_exits  per query, its passes counted by exit as the kernel ran
  //                  (CollideBatchRecorded): what the cost models price,
  //                  without a byte per fetch, but not which pass exited.
  // ExitAt reads the first two.
  std::vector<std::uint8_t> node_exits;
  std::vector<std::uint8_t> last_exits;
  std::shared_ptr<const ExitProfile> tallied_exits;
  std::vector<std::uint64_t> fetch_addresses;  // device byte addresses of the kept queries
  // Which queries' addresses are kept. With every query kept
  // (address_sample.KeepsAll()), address_offsets is empty and query i's
  // addresses sit at its exits' positions, [fetch_offsets[i],
  // fetch_offsets[i+1]). Otherwise address_offsets has one entry per block
  // of the sample (address_sample.BlockQueries() consecutive queries, the
  // last perhaps partial) plus one, KeptAddressOffsets: a kept block b's
  // queries' addresses are [address_offsets[b], address_offsets[b+1]), in
  // launch order, and an unkept block's range is empty.
  AddressSample address_sample;
  std::vector<std::uint64_t> address_offsets;
  // With a sample: how many distinct sectors (address_sample.sector_bytes,
  // numbered from footprint_begin()) the whole batch touched, which is what
  // an L2 that holds the footprint misses (0: not counted).
  std::uint64_t touched_sectors = 0;

  std::size_t query_count() const { return fetch_offsets.size() - 1; }
  std::uint32_t nodes(std::size_t query) const {
    return static_cast<std::uint32_t>(fetch_offsets[query + 1] - fetch_offsets[query]);
  }
  std::uint64_t total_nodes() const { return fetch_offsets.back(); }
  bool sampled() const { return !address_offsets.empty(); }
  bool exits_per_query() const { return !last_exits.empty(); }
  bool exits_tallied() const { return tallied_exits != nullptr; }
  // The exit of query q's pass over its k-th node (k < nodes(q)); not for a
  // record with tallied exits, which keeps no pass's own exit (throws).
  std::uint8_t ExitAt(std::size_t query, std::uint32_t k) const {
    if (exits_tallied()) throw std::logic_error("ExitAt: a record with tallied exits keeps no pass's own exit");
    if (exits_per_query()) return k + 1 == nodes(query) ? last_exits[query] : kNoExit;
    return node_exits[fetch_offsets[query] + k];
  }
  // For a record with exits per query: how many of query q's loop passes
  // ended at no RETURN_IF (all but the last when the last exits), and
  // whether its last pass exited (a query without nodes has no pass).
  std::uint32_t QuietPasses(std::size_t query) const {
    return last_exits[query] == kNoExit ? nodes(query) : nodes(query) - 1;
  }
  bool LastPassExits(std::size_t query) const { return nodes(query) > 0 && last_exits[query] != kNoExit; }
  // Whether query i's addresses are kept.
  bool KeepsAddresses(std::size_t query) const { return !sampled() || address_sample.KeepsQuery(query); }
  // Query i's addresses (nodes(i) of them); only for a kept query.
  const std::uint64_t* addresses(std::size_t query) const {
    if (!sampled()) return fetch_addresses.data() + fetch_offsets[query];
    const std::size_t block = query / address_sample.BlockQueries();
    return fetch_addresses.data() + address_offsets[block] +
           (fetch_offsets[query] - fetch_offsets[block * address_sample.BlockQueries()]);
  }
  // Lowest address and one past the highest byte of all regions.
  std::uint64_t footprint_begin() const;
  std::uint64_t footprint_end() const;

  // Throws std::logic_error if the arrays disagree (a sampled record must
  // keep exactly the queries its sample names), an address lies outside
  // every region, or an exit names a RETURN_IF the loop does not have.
  void Validate() const;

 private:
  // Validate's checks of tallied_exits: a profile per query whose passes add
  // up to its node count.
  void ValidateTalliedExits() const;
};

// A sampled record's address_offsets for these fetch offsets (queries + 1
// prefix sums): per block of `sample`, where its kept addresses begin, and
// the total at the end (blocks + 1 entries).
std::vector<std::uint64_t> KeptAddressOffsets(const std::vector<std::uint64_t>& fetch_offsets,
                                              const AddressSample& sample);

// A record built by hand (tests, the collision kernel): queries with the
// given node addresses and exits, one region covering them.
class KernelRecordBuilder {
 public:
  KernelRecordBuilder(std::shared_ptr<const MicroProgram> program, StepProgramKind kind, MemoryRegion region);
  KernelRecordBuilder& SetLeaf(std::shared_ptr<const MicroProgram> leaf, LeafProgramKind kind);
  // Appends one query; `exits` is empty (no exits) or one per address.
  KernelRecordBuilder& AddQuery(const std::vector<std::uint64_t>& addresses,
                                const std::vector<std::uint8_t>& exits = {});
  KernelRecord Build() const;  // validated

 private:
  KernelRecord record_;
};

}  // namespace rc
