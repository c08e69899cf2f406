// How much pricing costs next to the kernel it prices (DESIGN.md: a
// trace-driven model should run at roughly the speed of the functional
// kernel; the target is all five modelled backends in under ~1x the
// kernel's host time).
//
// Workload: the Wean map (../shared/data/wean/wean.dat, 800 x 800 at 10 cm)
// with 500 particles x 180 beams = 90,000 rays, max range 10 m (the RoWild
// DeliBot configuration), particles uniformly placed in free space (the
// first MCL update, when rays are longest). Without the shared data the
// benchmarks skip with a message.
//
//   BM_Kernel/<method>          CastRayBatch (the functional kernel)
//   BM_KernelRecorded/<method>/<sampled>
//                               CastRayBatchRecorded (kernel + record);
//                               sampled 0 keeps every address, 1 one SM's
//                               of 8 (the CLI's default sample)
//   BM_PriceAll/<method>/<sampled>
//                               the five modelled backends on one record,
//                               sharing the memory replay (PriceAll);
//                               sampled 0 keeps every address, 1 the CLI's
//                               default sample (kReplaySms SMs, every
//                               kReplayBlockStride-th block of each)
//   BM_Price/<backend>/<method> one backend alone
//   BM_Overhead/<method>        the ratio itself, measured in one run: each
//                               iteration times the kernel, then PriceAll
//                               on the same batch, so both see the same
//                               machine load; counters pricing_over_kernel
//                               (host time of PriceAll / CastRayBatch) and
//                               record_and_price_over_kernel (adds the
//                               recording).
#include <chrono>
#include <filesystem>
#include <memory>

#include <benchmark/benchmark.h>

#include "backends/backend.h"
#include "common/angles.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "robocore/address_sample.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {
namespace {

constexpr int kParticles = 500;
constexpr int kBeams = 180;
constexpr double kMaxRangeM = 10.0;

const RayCastMethod kMethods[] = {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching};

struct Workload {
  OccupancyGrid grid;
  std::unique_ptr<RayCastScene> scenes[3];
  RayBatch batch;
  KernelRecord records[3];
  KernelRecord sampled_records[3];  // the CLI's default address sample
};

const Workload* LoadWorkload() {
  static const std::unique_ptr<Workload> workload = []() -> std::unique_ptr<Workload> {
    const std::string path = std::string(RC_SHARED_DATA_DIR) + "/wean/wean.dat";
    if (!std::filesystem::exists(path)) return nullptr;
    auto w = std::make_unique<Workload>();
    w->grid = LoadCmuMap(path);
    RandomStream s(7, StreamPurpose::kTest, 0, 0);
    w->batch.max_range_m = kMaxRangeM;
    for (int placed = 0; placed < kParticles;) {
      const double x = s.Uniform(0, w->grid.extent_x_m()), y = s.Uniform(0, w->grid.extent_y_m());
      if (!w->grid.IsFreePoint(x, y)) continue;
      const double heading = s.Uniform(-kPi, kPi);
      for (int k = 0; k < kBeams; ++k) w->batch.queries.push_back({x, y, heading - kPi / 2 + kPi * k / (kBeams - 1)});
      ++placed;
    }
    std::vector<RayHit> hits;
    for (int m = 0; m < 3; ++m) {
      w->scenes[m] = std::make_unique<RayCastScene>(w->grid, kMethods[m]);
      CastRayBatchRecorded(*w->scenes[m], w->batch, hits, w->records[m]);
      RecordOptions sampled;
      sampled.sample.sampled_sms = kReplaySms;
      sampled.sample.block_stride = kReplayBlockStride;
      CastRayBatchRecorded(*w->scenes[m], w->batch, hits, w->sampled_records[m], sampled);
    }
    return w;
  }();
  return workload.get();
}

bool Skip(benchmark::State& state, const Workload* w) {
  if (w) return false;
  state.SkipWithError("shared data absent: ../shared/data/wean/wean.dat");
  return true;
}

// The five modelled backends with default parameters, as PriceAll takes them.
struct ModelledBackends {
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  ModelledBackends() {
    for (const std::string& name : Backend::ModelledNames()) {
      owned.push_back(Backend::Create(name, BackendParameters{}));
      backends.push_back(owned.back().get());
    }
  }
};

void SetCounters(benchmark::State& state, const KernelRecord& record) {
  state.counters["rays"] = static_cast<double>(record.query_count());
  state.counters["nodes_per_ray"] =
      static_cast<double>(record.total_nodes()) / static_cast<double>(record.query_count());
}

void BM_Kernel(benchmark::State& state) {
  const Workload* w = LoadWorkload();
  if (Skip(state, w)) return;
  const int m = static_cast<int>(state.range(0));
  std::vector<RayHit> hits;
  for (auto _ : state) CastRayBatch(*w->scenes[m], w->batch, hits);
  SetCounters(state, w->records[m]);
  state.SetLabel(ToString(kMethods[m]));
}

void BM_KernelRecorded(benchmark::State& state) {
  const Workload* w = LoadWorkload();
  if (Skip(state, w)) return;
  const int m = static_cast<int>(state.range(0));
  std::vector<RayHit> hits;
  KernelRecord record;
  RecordOptions options;
  options.sample.sampled_sms = static_cast<int>(state.range(1));
  for (auto _ : state) CastRayBatchRecorded(*w->scenes[m], w->batch, hits, record, options);
  SetCounters(state, w->records[m]);
  state.SetLabel(ToString(kMethods[m]));
}

void BM_PriceAll(benchmark::State& state) {
  const Workload* w = LoadWorkload();
  if (Skip(state, w)) return;
  const int m = static_cast<int>(state.range(0));
  const KernelRecord& record = state.range(1) ? w->sampled_records[m] : w->records[m];
  const ModelledBackends all;
  for (auto _ : state) benchmark::DoNotOptimize(PriceAll(all.backends, record));
  SetCounters(state, record);
  state.SetLabel(ToString(kMethods[m]));
}

void BM_Price(benchmark::State& state) {
  const Workload* w = LoadWorkload();
  if (Skip(state, w)) return;
  const std::string name = Backend::ModelledNames()[static_cast<std::size_t>(state.range(0))];
  const int m = static_cast<int>(state.range(1));
  const auto backend = Backend::Create(name, BackendParameters{});
  BatchCost cost;
  for (auto _ : state) benchmark::DoNotOptimize(cost = backend->Price(w->records[m]));
  SetCounters(state, w->records[m]);
  state.counters["modelled_us"] = cost.seconds * 1e6;
  state.counters["l1_hit_rate"] =
      static_cast<double>(cost.memory.l1_hits) / static_cast<double>(cost.memory.sector_requests);
  state.SetLabel(name + " " + ToString(kMethods[m]));
}

void BM_Overhead(benchmark::State& state) {
  const Workload* w = LoadWorkload();
  if (Skip(state, w)) return;
  const int m = static_cast<int>(state.range(0));
  const ModelledBackends all;
  std::vector<RayHit> hits;
  KernelRecord record;
  double kernel_s = 0, record_s = 0, price_s = 0;
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  for (auto _ : state) {
    const auto t0 = Clock::now();
    CastRayBatch(*w->scenes[m], w->batch, hits);
    const auto t1 = Clock::now();
    CastRayBatchRecorded(*w->scenes[m], w->batch, hits, record);
    const auto t2 = Clock::now();
    benchmark::DoNotOptimize(PriceAll(all.backends, record));
    const auto t3 = Clock::now();
    kernel_s += seconds(t0, t1);
    record_s += seconds(t1, t2);
    price_s += seconds(t2, t3);
  }
  SetCounters(state, w->records[m]);
  state.counters["kernel_ms"] = 1e3 * kernel_s / static_cast<double>(state.iterations());
  state.counters["price_all_ms"] = 1e3 * price_s / static_cast<double>(state.iterations());
  state.counters["pricing_over_kernel"] = price_s / kernel_s;
  state.counters["record_and_price_over_kernel"] = (record_s + price_s) / kernel_s;
  state.SetLabel(ToString(kMethods[m]));
}

BENCHMARK(BM_Kernel)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KernelRecorded)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PriceAll)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Overhead)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Price)
    ->ArgsProduct({benchmark::CreateDenseRange(0, 4, 1), {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
