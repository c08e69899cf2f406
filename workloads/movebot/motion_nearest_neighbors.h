#pragma once
// The one place that chooses the planner's nearest-neighbour structure.
//   gnat      OMPL's default for RRTstar (SelfConfig: GNAT on a metric
//             space), host-side; counted queries, no kernel record.
//   p-ray     the ball-query kernel on the backends, P-Ray formulation
//   p-sphere  the same kernel, P-Sphere formulation
//             (workloads/movebot/backend_nearest_neighbors.h)
// Whatever is chosen, the planner sees an ompl::NearestNeighbors<T>, and
// the timeline takes an NnWork per row through `take`.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <ompl/base/Planner.h>
#include <ompl/tools/config/SelfConfig.h>

#include "robocore/kernel_record.h"
#include "workloads/movebot/backend_nearest_neighbors.h"
#include "workloads/movebot/counting_nearest_neighbors.h"

namespace rc {

enum class NnKind { kGnat, kPRay, kPSphere };

inline const char* ToString(NnKind kind) {
  switch (kind) {
    case NnKind::kGnat: return "gnat";
    case NnKind::kPRay: return "p-ray";
    case NnKind::kPSphere: return "p-sphere";
  }
  return "?";
}

inline NnKind ParseNnKind(const std::string& name) {
  if (name == "gnat") return NnKind::kGnat;
  if (name == "p-ray") return NnKind::kPRay;
  if (name == "p-sphere") return NnKind::kPSphere;
  throw std::invalid_argument("nearest-neighbour structure '" + name + "': expected gnat, p-ray or p-sphere");
}

// What the structure did since the last take.
struct NnWork {
  std::uint64_t queries = 0;
  bool has_nodes = false;  // false for GNAT (it counts no visits)
  std::uint64_t nodes_visited = 0;
  std::optional<KernelRecord> record;  // the kernel's recorded batch (backend structures only)
};

template <typename T>
struct NnHandle {
  std::shared_ptr<ompl::NearestNeighbors<T>> nn;
  std::function<NnWork()> take;
};

// `coordinates` maps an element to its `dimension` doubles (the backend
// kernels need them; GNAT uses only the planner's distance function).
template <typename T>
NnHandle<T> MakeNearestNeighbors(NnKind kind, const ompl::base::Planner* planner,
                                 std::function<const double*(const T&)> coordinates, unsigned dimension) {
  if (kind != NnKind::kGnat) {
    BallQueryConfig config;  // ball_query_config.h defaults (first-pass radius 0.5 rad, early exit on)
    config.formulation = kind == NnKind::kPRay ? BallQueryFormulation::kPRay : BallQueryFormulation::kPSphere;
    auto backend = std::make_shared<BackendNearestNeighbors<T>>(config, std::move(coordinates), dimension);
    NnHandle<T> handle;
    handle.nn = backend;
    handle.take = [backend] {
      NnWork work;
      const BallQueryCounters c = backend->counters();
      backend->ResetCounters();
      work.queries = c.queries;
      work.has_nodes = true;
      work.nodes_visited = c.nodes_visited;
      KernelRecord record = backend->TakeKernelRecord();
      if (record.query_count() > 0) work.record = std::move(record);
      return work;
    };
    return handle;
  }
  auto counting = std::make_shared<CountingNearestNeighbors<T>>(
      std::shared_ptr<ompl::NearestNeighbors<T>>(ompl::tools::SelfConfig::getDefaultNearestNeighbors<T>(planner)));
  NnHandle<T> handle;
  handle.nn = counting;
  handle.take = [counting] {
    NnWork work;
    work.queries = counting->TakeQueries();
    return work;
  };
  return handle;
}

}  // namespace rc
