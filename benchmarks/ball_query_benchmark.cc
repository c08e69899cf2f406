// Ball-query kernel (robocore/ball_query) through its OMPL adapter, against
// OMPL's own structures, on 10^4 states of the 5-D arm's joint box:
//   BM_NearestK/<structure>/<k>   host queries per second (items_per_second)
//                                 and, for ours, fetched nodes per query;
//   BM_ModelledCycles/<formulation>/<k>  one batch of 1000 k-nearest queries
//                                 priced on every modelled backend: modelled
//                                 cycles per query (counters cycles_<backend>:
//                                 the batch's cycles / its 1000 queries), what
//                                 bounded each backend (label), and the time
//                                 the pricing takes.
// Structures: 0 NearestNeighborsLinear, 1 NearestNeighborsGNAT (RRTstar's
// default), 2 ours P-Sphere, 3 ours P-Ray (both record every query, as in
// the planner).
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsGNAT.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>

#include "backends/backend.h"
#include "workloads/movebot/backend_nearest_neighbors.h"

namespace {

using State = ompl::base::State*;
constexpr unsigned kDimension = 5;
constexpr int kStates = 10000;
constexpr int kQueries = 1000;

struct Data {
  std::shared_ptr<ompl::base::RealVectorStateSpace> space =
      std::make_shared<ompl::base::RealVectorStateSpace>(kDimension);
  std::vector<State> states, queries;
  Data() {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-M_PI / 2, M_PI / 2);  // joint limits, rad
    auto make = [&] {
      State s = space->allocState();
      for (unsigned i = 0; i < kDimension; ++i)
        s->as<ompl::base::RealVectorStateSpace::StateType>()->values[i] = u(rng);
      return s;
    };
    for (int i = 0; i < kStates; ++i) states.push_back(make());
    for (int i = 0; i < kQueries; ++i) queries.push_back(make());
  }
  ~Data() {
    for (State s : states) space->freeState(s);
    for (State s : queries) space->freeState(s);
  }
};

const Data& TheData() {
  static const Data data;
  return data;
}

const double* Coordinates(const State& s) { return s->as<ompl::base::RealVectorStateSpace::StateType>()->values; }

std::shared_ptr<ompl::NearestNeighbors<State>> Make(int structure) {
  const Data& d = TheData();
  std::shared_ptr<ompl::NearestNeighbors<State>> nn;
  if (structure == 0) nn = std::make_shared<ompl::NearestNeighborsLinear<State>>();
  if (structure == 1) nn = std::make_shared<ompl::NearestNeighborsGNAT<State>>();
  if (structure >= 2) {
    rc::BallQueryConfig config;
    config.formulation = structure == 2 ? rc::BallQueryFormulation::kPSphere : rc::BallQueryFormulation::kPRay;
    nn = std::make_shared<rc::BackendNearestNeighbors<State>>(config, Coordinates, kDimension);
  }
  auto space = d.space;
  nn->setDistanceFunction([space](const State& a, const State& b) { return space->distance(a, b); });
  nn->add(d.states);
  return nn;
}

const char* kStructureNames[] = {"linear", "gnat", "psphere", "pray"};

void BM_NearestK(benchmark::State& state) {
  const int structure = static_cast<int>(state.range(0));
  const std::size_t k = static_cast<std::size_t>(state.range(1));
  const auto nn = Make(structure);
  state.SetLabel(kStructureNames[structure]);
  const auto& queries = TheData().queries;
  std::vector<State> out;
  std::size_t i = 0;
  for (auto _ : state) {
    nn->nearestK(queries[i++ % queries.size()], k, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations());
  if (auto* ours = dynamic_cast<rc::BackendNearestNeighbors<State>*>(nn.get())) {
    state.counters["nodes_per_query"] = ours->counters().nodes_per_query();
    ours->TakeKernelRecord();
  }
}
BENCHMARK(BM_NearestK)->ArgsProduct({{0, 1, 2, 3}, {1, 10}})->Unit(benchmark::kMicrosecond);

void BM_ModelledCycles(benchmark::State& state) {
  const int structure = static_cast<int>(state.range(0));
  const std::size_t k = static_cast<std::size_t>(state.range(1));
  auto nn = std::static_pointer_cast<rc::BackendNearestNeighbors<State>>(Make(structure));
  std::vector<State> out;
  for (State q : TheData().queries) nn->nearestK(q, k, out);
  const rc::KernelRecord record = nn->TakeKernelRecord();
  std::vector<std::unique_ptr<rc::Backend>> owned;
  std::vector<const rc::Backend*> backends;
  for (const std::string& name : rc::Backend::ModelledNames()) {
    owned.push_back(rc::Backend::Create(name, rc::BackendParameters{}));
    backends.push_back(owned.back().get());
  }
  std::vector<rc::BatchCost> costs;
  for (auto _ : state) {
    costs = rc::PriceAll(backends, record);
    benchmark::DoNotOptimize(costs.data());
  }
  const double queries = static_cast<double>(record.query_count());
  state.counters["nodes_per_query"] = static_cast<double>(record.total_nodes()) / queries;
  std::string label = kStructureNames[structure];
  for (const rc::BatchCost& c : costs) {
    state.counters["cycles_" + c.backend] = static_cast<double>(c.cycles) / queries;
    label += "; " + c.backend + ": " + c.bound;  // what limited its busiest SM
  }
  state.SetLabel(label);
}
BENCHMARK(BM_ModelledCycles)->ArgsProduct({{2, 3}, {1, 10}})->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
