// Monte Carlo localization tracking, ours beside MRPT's
// CMonteCarloLocalization2D (`rcbench delibot --engine mrpt`), both in this
// process: time per sensor update at equal particles and beams.
//
// Workload (issue 24's table): Wean (../shared/data/wean/wean.dat) and
// robotdata1.log, tracking: both engines start around the same pose, the
// estimate our filter reaches by record 99 in a global-localization run
// (2000 particles, every 6th beam, default options; computed once, not
// timed), and process records 100-299. Every 6th beam (30 of 180), beam
// model, rm ray caster (exact; dda's ranges), 1000 and 5000 particles, one
// thread, no pricing, no recovery (MRPT has none: compare like with like,
// as tests/mrpt does). Without the shared data the benchmarks skip.
//
//   BM_MclTracking/<engine>/<particles>   counters ms_per_update (the
//       rows' wall time: prediction + update + resampling + estimate, for
//       both engines, over the sensor updates) and cpu_ms_per_update (the
//       process's CPU time for the whole run over the sensor updates).
//
// Run both sides alternating, repeated, and read the medians:
//   build/benchmarks/mcl_mrpt_benchmark --benchmark_repetitions=5
//     --benchmark_enable_random_interleaving=true --benchmark_counters_tabular=true
// (one command line).
#include <omp.h>

#include <ctime>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "maps/cmu_map_loader.h"
#include "traces/cmu_log_reader.h"
#include "workloads/delibot/mrpt/delibot_engine.h"

namespace rc {
namespace {

constexpr long kStartRecord = 100;
constexpr long kTrackedRecords = 200;

struct TrackingInputs {
  bool present = false;
  OccupancyGrid grid;
  SensorTrace tracked;  // records kStartRecord .. + kTrackedRecords
  Pose2 start;
};

const TrackingInputs& Inputs() {
  static const TrackingInputs inputs = [] {
    TrackingInputs in;
    const std::string dir = std::string(RC_SHARED_DATA_DIR) + "/wean/";
    if (!std::filesystem::exists(dir + "wean.dat") || !std::filesystem::exists(dir + "robotdata1.log")) return in;
    in.grid = LoadCmuMap(dir + "wean.dat");
    const SensorTrace full = ReadCmuLog(dir + "robotdata1.log");
    DelibotSettings global;
    global.mcl.particle_count = 2000;
    global.mcl.beams.beam_step = 6;
    global.max_records = kStartRecord;
    const DelibotResult located = RunDelibot(in.grid, full, nullptr, global);
    in.start = located.rows.back().estimate;
    in.tracked.source_path = full.source_path;
    in.tracked.format = full.format;
    in.tracked.geometry = full.geometry;
    in.tracked.scans.assign(full.scans.begin() + kStartRecord, full.scans.begin() + kStartRecord + kTrackedRecords);
    in.present = true;
    return in;
  }();
  return inputs;
}

void BM_MclTracking(benchmark::State& state, DelibotEngine engine) {
  const TrackingInputs& in = Inputs();
  if (!in.present) {
    state.SkipWithError("shared data absent: ../shared/data/wean/{wean.dat,robotdata1.log}");
    return;
  }
  DelibotSettings s;
  s.mcl.particle_count = static_cast<int>(state.range(0));
  s.mcl.beams.beam_step = 6;
  s.mcl.alpha_slow = s.mcl.alpha_fast = 0.0;
  s.ray_caster = RayCastMethod::kRayMarching;
  s.initial_pose = in.start;
  const int saved_threads = omp_get_max_threads();
  omp_set_num_threads(1);
  DelibotResult last;
  double cpu_s = 0.0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    last = RunDelibotEngine(engine, in.grid, in.tracked, nullptr, s);
    cpu_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  }
  omp_set_num_threads(saved_threads);
  const double updates = static_cast<double>(last.summary.sensor_updates);
  state.counters["ms_per_update"] = 1e3 * last.summary.wall_s / updates;
  // Process CPU time of the whole run (one thread) over its updates: what a
  // loaded shared machine distorts least.
  state.counters["cpu_ms_per_update"] = 1e3 * cpu_s / updates;
  state.counters["updates"] = static_cast<double>(last.summary.sensor_updates);
  state.counters["final_consistency"] = last.summary.end_consistency;
  state.SetLabel(ToString(engine) + ", " + std::to_string(s.mcl.particle_count) +
                 " particles x 30 beams, robotdata1 records 100-299, 1 thread");
}

BENCHMARK_CAPTURE(BM_MclTracking, ours, DelibotEngine::kOurs)
    ->Arg(1000)
    ->Arg(5000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MclTracking, mrpt, DelibotEngine::kMrpt)
    ->Arg(1000)
    ->Arg(5000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
