// DeliBot end to end on RoWild's work, and the filter's parallel efficiency.
//
// Workload (issue 24's table, RoWild's DeliBot configuration): the Wean map
// (../shared/data/wean/wean.dat, 800 x 800 at 10 cm), robotdata1.log, 500
// and 2000 particles x 180 beams (every beam) x 200 records, every record a
// sensor update (update_min_d = update_min_a = 0), global localization,
// default filter otherwise, no pricing. Without the shared data the
// benchmarks skip with a message.
//
//   BM_DelibotRoWildWork/<caster>/<particles>   one thread; counters
//       ms_per_update (the filter: RunDelibot's rows' wall time, motion +
//       sensor update + resampling + estimate), cpu_ms_per_update (process
//       CPU time of the run over its updates) and rays_per_s.
//   BM_DelibotThreads/<particles>/<threads>      rm, 50 records, wall time;
//       parallel efficiency = T(1) / (2 T(2)) from two rows. Meaningful
//       only with both cores free: on the shared machine, docs/performance.md
//       ("Threads") runs rcbench pinned at SCHED_FIFO instead, and reports
//       0.92-0.96 (medians) from 2000 particles up.
//
// The peer, RoWild DeliBot (cmu-roboarch/rowild e2e/DeliBot, built from its
// own Makefile: -O3 -fopenmp -mavx512f/vl/bw/dq, run with
// OMP_THREAD_LIMIT=1), is not a Debian package, so it is not linked here; it
// was run side by side with `rcbench delibot` on the same work, whole
// processes alternating (docs/performance.md gives the script and the
// conversion of wean.dat, whose values are P(free), into RoWild's
// occupancy). Quoted from docs/performance.md (2026-11-25, load average
// 15-18), one thread, CPU time of the whole process (load and parse
// included), 3 alternating rounds, medians; RoWild's time over ours
// (median of the paired ratios):
//
//   particles  RoWild    rcbench rm      rcbench dda     rcbench march
//   500        3.19 s    1.65 s (1.92x)  1.83 s (1.74x)  1.58 s (2.07x)
//   2000       12.26 s   5.53 s (2.22x)  5.98 s (2.05x)  6.27 s (2.04x)
//
// Peak memory: RoWild 10 MB, rcbench 107-113 MB (mostly the shared
// libraries the rcbench binary links).
//
// Run: build/benchmarks/delibot_benchmark --benchmark_counters_tabular=true
#include <omp.h>

#include <ctime>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "maps/cmu_map_loader.h"
#include "traces/cmu_log_reader.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

struct WeanInputs {
  bool present = false;
  OccupancyGrid grid;
  SensorTrace trace;
};

const WeanInputs& Wean() {
  static const WeanInputs inputs = [] {
    WeanInputs w;
    const std::string dir = std::string(RC_SHARED_DATA_DIR) + "/wean/";
    if (!std::filesystem::exists(dir + "wean.dat") || !std::filesystem::exists(dir + "robotdata1.log")) return w;
    w.grid = LoadCmuMap(dir + "wean.dat");
    w.trace = ReadCmuLog(dir + "robotdata1.log");
    w.present = true;
    return w;
  }();
  return inputs;
}

DelibotSettings RoWildWork(RayCastMethod caster, int particles, long records) {
  DelibotSettings s;
  s.ray_caster = caster;
  s.mcl.particle_count = particles;
  s.mcl.beams.beam_step = 1;
  s.mcl.update_min_d_m = 0.0;
  s.mcl.update_min_a_rad = 0.0;
  s.max_records = records;
  s.price_backends = false;
  return s;
}

void Report(benchmark::State& state, const DelibotResult& last, double cpu_s) {
  const double updates = static_cast<double>(last.summary.sensor_updates);
  state.counters["ms_per_update"] = 1e3 * last.summary.wall_s / updates;
  state.counters["cpu_ms_per_update"] = 1e3 * cpu_s / updates;  // all threads' CPU time
  state.counters["rays_per_s"] = static_cast<double>(last.summary.rays) / last.summary.wall_s;
  state.counters["updates"] = updates;
}

void BM_DelibotRoWildWork(benchmark::State& state, RayCastMethod caster) {
  const WeanInputs& w = Wean();
  if (!w.present) {
    state.SkipWithError("shared data absent: ../shared/data/wean/{wean.dat,robotdata1.log}");
    return;
  }
  const int particles = static_cast<int>(state.range(0));
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(1);
  DelibotResult last;
  double cpu_s = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    last = RunDelibot(w.grid, w.trace, nullptr, RoWildWork(caster, particles, 200));
    cpu_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  }
  omp_set_num_threads(saved_threads);
  Report(state, last, cpu_s);
  state.SetLabel(ToString(caster) + ", " + std::to_string(particles) +
                 " particles x 180 beams x 200 updates, 1 thread");
}

void BM_DelibotThreads(benchmark::State& state) {
  const WeanInputs& w = Wean();
  if (!w.present) {
    state.SkipWithError("shared data absent: ../shared/data/wean/{wean.dat,robotdata1.log}");
    return;
  }
  const int particles = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(threads);
  DelibotResult last;
  double cpu_s = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    last = RunDelibot(w.grid, w.trace, nullptr, RoWildWork(RayCastMethod::kRayMarching, particles, 50));
    cpu_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  }
  omp_set_num_threads(saved_threads);
  Report(state, last, cpu_s);
  state.SetLabel("rm, " + std::to_string(particles) + " particles x 180 beams x 50 updates, " +
                 std::to_string(threads) + " thread(s)");
}

BENCHMARK_CAPTURE(BM_DelibotRoWildWork, rm, RayCastMethod::kRayMarching)
    ->Arg(500)
    ->Arg(2000)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DelibotRoWildWork, dda, RayCastMethod::kDda)
    ->Arg(500)
    ->Arg(2000)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_DelibotRoWildWork, march, RayCastMethod::kMarch)
    ->Arg(500)
    ->Arg(2000)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_DelibotThreads)
    ->Args({2000, 1})
    ->Args({2000, 2})
    ->Args({8000, 1})
    ->Args({8000, 2})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
