#pragma once
// Batch ray casting with rays in flight in SIMD lanes, AVX-512 or AVX2 (the
// host fast path of CastRayBatch for all three methods: march, dda and rm).
//
// Why: one ray's traversal is a chain of dependent steps (the next cell
// depends on the comparison of two boundary times; rm's next fetch depends on
// the distance just fetched), and its x/y step pattern defeats the branch
// predictor. 32 rays advance together, one step each per round, in groups
// of one vector each (eight in AVX-512, four in AVX2), every per-step
// decision a lane mask instead of a branch, and every group's cell fetches
// one gather. A lane whose ray ended takes the batch's next query.
//
// Contract: every hit (range and node count) equals CastRay's for the same
// query, bit for bit. The lanes run CastMarch's, CastDda's and
// CastRayMarching's operations (ray_cast.h) on the same IEEE double values in the same order:
// multiply, subtract, divide, floor, min/max and compares are exact in SIMD
// as in scalar code, each select is written with the operand order of the
// scalar ternary it replaces, and the files are compiled with
// -ffp-contract=off so that no multiply-add is fused. A ray's set-up
// (sin, cos, 1/dir) is the scalar code itself. Both instruction sets run
// the same operations, so they also agree with each other.
//
// Dispatch is at run time: the widest instruction set the suite uses
// (AVX-512 F, VL, DQ; else AVX2; common/cpu_features.h, which `rcbench
// --simd` may lower). On a CPU with neither, with `--simd scalar`, on a
// target other than x86-64, or for a grid too large for 32-bit gather
// indices, CastRayBatch casts each query with CastRay instead; no global
// -march flag is needed.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "robocore/ray_batch.h"

namespace rc {

// Rays in flight: groups of one vector each are stepped in turn, because
// one group's round is a chain of about 130 cycles of dependent latency (a
// gather, a divide, conversions) and several groups keep the core busy; 4
// groups of 8 measured best in AVX-512 (docs/performance.md).
inline constexpr int kRaysInFlight = 32;

// The instruction sets the lanes are written in.
enum class RayLaneIsa { kAvx2, kAvx512 };
std::string_view ToString(RayLaneIsa isa);

// Every instruction set of the lanes this CPU runs, narrowest first; empty
// where it runs none (then CastRayBatch casts one query at a time).
const std::vector<RayLaneIsa>& HostRayLaneIsas();

// True when the lanes run in some instruction set: the CPU runs one and
// the suite uses it (UseAvx2(), common/cpu_features.h).
bool RayLanesSupported();

// The instruction set CastRayLanes runs. Requires RayLanesSupported().
RayLaneIsa RayLaneIsaInUse();

// True when `scene` can be cast by the lanes here: RayLanesSupported(), and
// a grid whose cell indices fit a 32-bit gather.
bool RayLanesApply(const RayCastScene& scene);

// The index of every node each query of a call fetched, in fetch order, as
// the lanes leave them: per lane, the queries it ran one after another.
// Query q's are the first hits[q].nodes entries at NodesOf(q). A recording
// that keeps addresses asks for it. The buffers keep their size from call to
// call; entries past a lane's last query's nodes are scratch.
struct LaneNodeLog {
  std::vector<std::uint32_t> lane[kRaysInFlight];
  std::vector<std::uint32_t> lane_of, start_of;  // per query of the call
  const std::uint32_t* NodesOf(std::size_t q) const { return lane[lane_of[q]].data() + start_of[q]; }
};

// What a recorded batch (robocore/ray_batch_recorded.h) also takes from the
// lanes: each query's last loop pass's exit, the sectors its node fetches
// touched, and the nodes it fetched.
struct LaneRecording {
  // Per query: kRayHitReturn when the last fetched node stopped the ray,
  // kRayEndReturn when the next one was out of range or off the map, kNoExit
  // for a query that fetched nothing (robocore/kernel_record.h). Null: not
  // wanted.
  std::uint8_t* last_exits = nullptr;
  // A byte per sector, numbered from the footprint's begin: set to 1 for
  // every fetched node's sector. Null: not wanted.
  std::uint8_t* touched = nullptr;
  std::uint64_t offset = 0;         // bytes from the footprint's begin to the fetched structure
  std::uint32_t element_bytes = 1;  // bytes per fetched node
  int sector_shift = 5;             // log2(sector bytes)
  LaneNodeLog* nodes = nullptr;     // null: not wanted
};

// Casts queries [0, count) into hits [0, count) with the scene's method,
// in RayLaneIsaInUse(). Requires RayLanesApply(scene).
// With a recording, also fills what it asks for (the last exits of
// [0, count), words of touched sectors, node indices).
void CastRayLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count, double max_range_m,
                  RayHit* hits, const LaneRecording* recording = nullptr);

// The same in instruction set `isa`, which must be one of HostRayLaneIsas()
// (tests and benchmarks compare them; std::invalid_argument otherwise).
void CastRayLanesIn(RayLaneIsa isa, const RayCastScene& scene, const RayQuery* queries, std::size_t count,
                    double max_range_m, RayHit* hits, const LaneRecording* recording = nullptr);

}  // namespace rc
