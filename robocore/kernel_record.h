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
// Memory: 9 bytes per fetch (8-byte address + 1-byte exit) + 8 bytes per
// query. A Wean-sized DeliBot update (90,000 rays, about 26 nodes each)
// records about 21 MB.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robocore/micro_program.h"
#include "robocore/ray_cast.h"
#include "robocore/section_timing.h"

namespace rc {

// The kernel's step program.
enum class StepProgramKind : std::uint8_t {
  kGridMarch,  // march: programs/grid_march.asm
  kDdaStep,    // dda:   programs/dda_step.asm
  kRmStep,     // rm:    programs/rm_step.asm
  kSactTest,   // one OBB-vs-AABB SACT per node: programs/sact_obb_aabb.asm
  kSphereTest, // one sphere-vs-AABB test per node (sphere robot): programs/sphere_aabb.asm
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
struct DeviceLayout {
  std::uint64_t first_base = std::uint64_t{1} << 32;  // bytes; away from 0 so a bad address stands out
  std::uint64_t alignment = 4096;                     // bytes; a page
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
  std::vector<std::uint64_t> fetch_addresses;   // device byte addresses
  std::vector<std::uint8_t> node_exits;         // RETURN_IF that fired per fetch, or kNoExit

  std::size_t query_count() const { return fetch_offsets.size() - 1; }
  std::uint32_t nodes(std::size_t query) const {
    return static_cast<std::uint32_t>(fetch_offsets[query + 1] - fetch_offsets[query]);
  }
  std::uint64_t total_nodes() const { return fetch_addresses.size(); }
  // Lowest address and one past the highest byte of all regions.
  std::uint64_t footprint_begin() const;
  std::uint64_t footprint_end() const;

  // Throws std::logic_error if the arrays disagree, an address lies outside
  // every region, or an exit names a RETURN_IF the loop does not have.
  void Validate() const;
};

// A record built by hand (tests, the collision kernel): queries with the
// given node addresses and exits, one region covering them.
class KernelRecordBuilder {
 public:
  KernelRecordBuilder(std::shared_ptr<const MicroProgram> program, StepProgramKind kind,
                      MemoryRegion region);
  KernelRecordBuilder& SetLeaf(std::shared_ptr<const MicroProgram> leaf, LeafProgramKind kind);
  // Appends one query; `exits` is empty (no exits) or one per address.
  KernelRecordBuilder& AddQuery(const std::vector<std::uint64_t>& addresses,
                                const std::vector<std::uint8_t>& exits = {});
  KernelRecord Build() const;  // validated

 private:
  KernelRecord record_;
};

}  // namespace rc
