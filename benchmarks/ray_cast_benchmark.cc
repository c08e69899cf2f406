// Ray-casting throughput of the three kernels, single-threaded, in RangeLibc's
// setting (issue 24): Wean Hall at 10 cm, 1M queries starting in free cells
// with random headings, max range 10 m, in random order and in grid
// (spatially sorted) order. Falls back to the generated office map when
// ../shared/data is absent, and says so in the benchmark label.
//
//   BM_RayCast/<method>_<order>       CastRay, one query at a time
//   BM_RayCastBatch/<method>_<order>  CastRayBatch on one thread: 32 rays in
//                                     flight in SIMD lanes (the widest the
//                                     CPU runs, named in the label), the
//                                     same hits
//   BM_RayCastLanes/<method>_<isa>    the lanes in one instruction set
//                                     (avx2, avx512), random order; skipped
//                                     where the CPU lacks it
//
// The peer, RangeLibc (kctess5/range_libc), is not a Debian package, so it is
// not linked here. It was built from its own sources with its own flags
// (-O3 -march=native -ffast-math) and run side by side with this benchmark's
// queries in one harness process, each pair alternating, 11 rounds, thread
// CPU time (docs/performance.md, "Ray casting", has the method). Quoted from
// there (2026-11-25, load average 13-17; M queries/s, medians, and the
// medians of the paired ratios):
//
//   rcbench rm batch    12.47   vs RangeLibc RM   7.98   1.56x
//   rcbench dda batch   12.66   vs RangeLibc BL   8.22   1.54x
//   rcbench march batch 12.68   vs RangeLibc BL          1.56x
//   RangeLibc CDDT 4.59, PCDDT 4.60, LUT 17.05 (138 MB, approximate: 2.0 px)
//
// rm and dda are exact (the same ranges); RangeLibc's methods are within
// 1.1-3.3 px on average.
//
// Run: build/benchmarks/ray_cast_benchmark --benchmark_counters_tabular=true
#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <omp.h>

#include "benchmarks/ray_cast_queries.h"
#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_batch_lanes.h"
#include "robocore/ray_cast.h"

namespace rc {
namespace {

constexpr double kMaxRangeM = 10.0;
constexpr std::size_t kQueries = 1000000;

struct Fixture {
  OccupancyGrid grid;
  std::string map_name;
  std::vector<std::array<double, 3>> random_order, grid_order;
};

const Fixture& GetFixture() {
  static const Fixture fixture = [] {
    Fixture f;
    const std::string wean = std::string(RC_SHARED_DATA_DIR) + "/wean/wean.dat";
    if (std::filesystem::exists(wean)) {
      f.grid = LoadCmuMap(wean);
      f.map_name = "wean";
    } else {
      f.grid = GenerateOfficeMap(OfficeMapOptions{});
      f.map_name = "office (shared data absent)";
    }
    const RayCastQueries queries = MakeRayCastQueries(f.grid, kQueries);
    for (const RayQuery& q : queries.random_order) f.random_order.push_back({q.origin_x_m, q.origin_y_m, q.angle_rad});
    for (std::uint32_t i : queries.grid_order) f.grid_order.push_back(f.random_order[i]);
    return f;
  }();
  return fixture;
}

// The counters every benchmark here reports: queries (per iteration) cast
// per second, nodes per query over all iterations, the scene's precomputed
// memory.
void SetCastCounters(benchmark::State& state, std::size_t queries, std::uint64_t nodes, const RayCastScene& scene) {
  const double cast = static_cast<double>(state.iterations() * queries);
  state.SetItemsProcessed(static_cast<std::int64_t>(cast));
  state.counters["queries_per_s"] = benchmark::Counter(cast, benchmark::Counter::kIsRate);
  state.counters["nodes_per_query"] = static_cast<double>(nodes) / cast;
  state.counters["precompute_MB"] = scene.precomputed_bytes() / 1e6;
}

void BM_RayCast(benchmark::State& state, RayCastMethod method, bool grid_order) {
  const Fixture& f = GetFixture();
  const RayCastScene scene(f.grid, method);
  const auto& queries = grid_order ? f.grid_order : f.random_order;
  std::uint64_t nodes = 0;
  for (auto _ : state) {
    for (const auto& q : queries) {
      const RayHit hit = CastRay(scene, q[0], q[1], q[2], kMaxRangeM);
      nodes += hit.nodes;
      benchmark::DoNotOptimize(hit);
    }
  }
  SetCastCounters(state, queries.size(), nodes, scene);
  state.SetLabel(f.map_name + (grid_order ? ", grid order" : ", random order"));
}

// What CastRayBatch runs on this CPU, for the labels.
std::string BatchPath() {
  return RayLanesSupported() ? std::string(ToString(RayLaneIsaInUse())) + " lanes" : "one query at a time";
}

// The same queries through the batch entry point (CastRayBatch) on one
// thread: 32 rays in flight in SIMD lanes where the CPU has them
// (ray_batch_lanes.h), the same hits as one query at a time.
void BM_RayCastBatch(benchmark::State& state, RayCastMethod method, bool grid_order) {
  const Fixture& f = GetFixture();
  const RayCastScene scene(f.grid, method);
  RayBatch batch;
  batch.max_range_m = kMaxRangeM;
  for (const auto& q : grid_order ? f.grid_order : f.random_order) batch.queries.push_back({q[0], q[1], q[2]});
  std::vector<RayHit> hits;
  std::uint64_t nodes = 0;
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(1);
  for (auto _ : state) {
    CastRayBatch(scene, batch, hits);
    nodes += TotalNodes(hits);
    benchmark::DoNotOptimize(hits.data());
  }
  omp_set_num_threads(saved_threads);
  SetCastCounters(state, batch.queries.size(), nodes, scene);
  state.SetLabel(f.map_name + (grid_order ? ", grid order, batch, " : ", random order, batch, ") + BatchPath());
}

// The lanes in instruction set `isa` (CastRayLanesIn), random order, one
// thread: an AVX-512 CPU also runs the AVX2 lanes, to compare the two.
void BM_RayCastLanes(benchmark::State& state, RayCastMethod method, RayLaneIsa isa) {
  const std::vector<RayLaneIsa>& host = HostRayLaneIsas();
  if (std::find(host.begin(), host.end(), isa) == host.end()) {
    state.SkipWithError(("this CPU does not run " + std::string(ToString(isa))).c_str());
    return;
  }
  const Fixture& f = GetFixture();
  const RayCastScene scene(f.grid, method);
  std::vector<RayQuery> queries;
  for (const auto& q : f.random_order) queries.push_back({q[0], q[1], q[2]});
  std::vector<RayHit> hits(queries.size());
  std::uint64_t nodes = 0;
  for (auto _ : state) {
    CastRayLanesIn(isa, scene, queries.data(), queries.size(), kMaxRangeM, hits.data());
    nodes += TotalNodes(hits);
    benchmark::DoNotOptimize(hits.data());
  }
  SetCastCounters(state, queries.size(), nodes, scene);
  state.SetLabel(f.map_name + ", random order, " + std::string(ToString(isa)) + " lanes");
}

BENCHMARK_CAPTURE(BM_RayCast, march_random, RayCastMethod::kMarch, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCast, march_grid, RayCastMethod::kMarch, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCast, dda_random, RayCastMethod::kDda, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCast, dda_grid, RayCastMethod::kDda, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCast, rm_random, RayCastMethod::kRayMarching, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCast, rm_grid, RayCastMethod::kRayMarching, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, march_random, RayCastMethod::kMarch, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, march_grid, RayCastMethod::kMarch, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, dda_random, RayCastMethod::kDda, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, dda_grid, RayCastMethod::kDda, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, rm_random, RayCastMethod::kRayMarching, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastBatch, rm_grid, RayCastMethod::kRayMarching, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastLanes, dda_avx2, RayCastMethod::kDda, RayLaneIsa::kAvx2)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastLanes, dda_avx512, RayCastMethod::kDda, RayLaneIsa::kAvx512)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastLanes, rm_avx2, RayCastMethod::kRayMarching, RayLaneIsa::kAvx2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RayCastLanes, rm_avx512, RayCastMethod::kRayMarching, RayLaneIsa::kAvx512)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
