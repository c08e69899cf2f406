// What pricing costs end to end (issue #24's goal: pricing every backend
// at most 1.3x the unpriced run's wall time): whole DeliBot runs, the
// filter with its recording and the ledger's pricing, against the same run
// with pricing off.
//
// Workloads: the built-in demo's inputs (the generated office map and a
// simulated trace, 2000 particles x 30 beams, rm), and, with the shared
// data, robotdata1 on the Wean map with every beam (2000 particles x 180
// beams, rm), the configuration the issue measured at 4.7-5x.
//
//   BM_Run/<workload>/<mode>  one run; mode unpriced | sampled (the CLI's
//                             default, one SM replayed) | exact (every SM)
//   BM_Overhead/<workload>/<mode>
//                             each iteration runs unpriced then priced, so
//                             both see the same machine load; counter
//                             priced_over_unpriced = the ratio of their
//                             summed wall times.
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "traces/trace_reader.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {
namespace {

struct Inputs {
  OccupancyGrid grid;
  SensorTrace trace;
  DelibotSettings settings;
};

const Inputs* Office() {
  static const std::unique_ptr<Inputs> inputs = [] {
    auto in = std::make_unique<Inputs>();
    in->grid = GenerateOfficeMap(OfficeMapOptions{});
    SimulationOptions sim;
    sim.record_count = 150;
    in->trace = SimulateTrace(in->grid, sim).trace;
    in->settings.ray_caster = RayCastMethod::kRayMarching;
    return in;
  }();
  return inputs.get();
}

const Inputs* Wean() {
  static const std::unique_ptr<Inputs> inputs = []() -> std::unique_ptr<Inputs> {
    const std::string dir = std::string(RC_SHARED_DATA_DIR) + "/wean/";
    if (!std::filesystem::exists(dir + "robotdata1.log")) return nullptr;
    auto in = std::make_unique<Inputs>();
    in->grid = LoadCmuMap(dir + "wean.dat");
    in->trace = ReadTrace(dir + "robotdata1.log", TraceReadOptions{});
    in->settings.ray_caster = RayCastMethod::kRayMarching;
    in->settings.mcl.beams.beam_step = 1;
    in->settings.max_records = 60;
    return in;
  }();
  return inputs.get();
}

const Inputs* InputsOf(int workload) { return workload == 0 ? Office() : Wean(); }

// mode 0 unpriced, 1 sampled (one SM replayed), 2 exact.
DelibotSettings SettingsOf(const Inputs& in, int mode) {
  DelibotSettings s = in.settings;
  s.price_backends = mode > 0;
  s.ledger.replay_sms = mode == 1 ? 1 : 0;
  return s;
}

double RunSeconds(const Inputs& in, int mode) {
  const auto start = std::chrono::steady_clock::now();
  const DelibotResult r = RunDelibot(in.grid, in.trace, nullptr, SettingsOf(in, mode));
  benchmark::DoNotOptimize(r.summary.rays);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_Run(benchmark::State& state) {
  const Inputs* in = InputsOf(static_cast<int>(state.range(0)));
  if (!in) {
    state.SkipWithError("../shared/data/wean/robotdata1.log is absent");
    return;
  }
  for (auto _ : state) RunSeconds(*in, static_cast<int>(state.range(1)));
}

void BM_Overhead(benchmark::State& state) {
  const Inputs* in = InputsOf(static_cast<int>(state.range(0)));
  if (!in) {
    state.SkipWithError("../shared/data/wean/robotdata1.log is absent");
    return;
  }
  double unpriced = 0, priced = 0;
  for (auto _ : state) {
    unpriced += RunSeconds(*in, 0);
    priced += RunSeconds(*in, static_cast<int>(state.range(1)));
  }
  state.counters["priced_over_unpriced"] = priced / unpriced;
}

void Workloads(benchmark::internal::Benchmark* b, bool with_unpriced) {
  b->ArgNames({"workload", "mode"});
  for (int workload : {0, 1})
    for (int mode = with_unpriced ? 0 : 1; mode <= 2; ++mode) b->Args({workload, mode});
  b->Unit(benchmark::kSecond)->Iterations(3);
}

BENCHMARK(BM_Run)->Apply([](auto* b) { Workloads(b, true); });
BENCHMARK(BM_Overhead)->Apply([](auto* b) { Workloads(b, false); });

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
