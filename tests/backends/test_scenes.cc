#include "test_scenes.h"

#include "common/angles.h"
#include "common/random_stream.h"
#include "robocore/ray_batch_recorded.h"

namespace rc::test {

OccupancyGrid RoomGrid(int sx, int sy, double r, double clutter, std::uint64_t seed) {
  OccupancyGrid g(sx, sy, r);
  RandomStream s(seed, StreamPurpose::kTest, 11, 0);
  for (int x = 0; x < sx; ++x)
    for (int y = 0; y < sy; ++y) {
      const bool wall = x == 0 || y == 0 || x == sx - 1 || y == sy - 1;
      const double u = s.Uniform();
      if (wall || u < clutter)
        g.Set(x, y, CellState::kOccupied);
      else if (u < clutter * 1.2)
        g.Set(x, y, CellState::kUnknown);
    }
  return g;
}

RayBatch FanBatch(const OccupancyGrid& g, int particles, int beams, double max_range_m, std::uint64_t seed) {
  RayBatch batch;
  batch.max_range_m = max_range_m;
  RandomStream s(seed, StreamPurpose::kTest, 12, 0);
  int placed = 0;
  while (placed < particles) {
    const double x = s.Uniform(0, g.extent_x_m()), y = s.Uniform(0, g.extent_y_m());
    if (!g.IsFreePoint(x, y)) continue;
    const double heading = s.Uniform(-kPi, kPi);
    for (int k = 0; k < beams; ++k)
      batch.queries.push_back({x, y, heading - kPi / 2 + kPi * k / std::max(1, beams - 1)});
    ++placed;
  }
  return batch;
}

std::shared_ptr<const MicroProgram> Program(const std::string& text, const std::string& name) {
  return std::make_shared<const MicroProgram>(ParseMicroProgram(text, name));
}

MemoryRegion ByteRegion(std::uint64_t base, std::uint64_t elements) {
  MemoryRegion r;
  r.name = "test nodes";
  r.kind = FetchKind::kGridCell;
  r.base = base;
  r.element_bytes = 1;
  r.elements = elements;
  return r;
}

KernelRecord RecordedFan(const OccupancyGrid& grid, RayCastMethod method, int particles, int beams, double max_range_m,
                         std::uint64_t seed) {
  const RayCastScene scene(grid, method);
  const RayBatch batch = FanBatch(grid, particles, beams, max_range_m, seed);
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record);
  return record;
}

}  // namespace rc::test
