#pragma once
// Scenes, batches and hand-built records shared by the backend tests.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robocore/kernel_record.h"
#include "robocore/micro_program.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_cast.h"

namespace rc::test {

// A walled room with random occupied and unknown cells inside.
OccupancyGrid RoomGrid(int size_x, int size_y, double resolution_m, double clutter, std::uint64_t seed);

// Particle-major, beam-minor rays from random free points, as DeliBot
// launches them.
RayBatch FanBatch(const OccupancyGrid& grid, int particles, int beams, double max_range_m, std::uint64_t seed);

// FanBatch's rays cast by `method` on `grid` and recorded with every
// address kept: the record the backends price.
KernelRecord RecordedFan(const OccupancyGrid& grid, RayCastMethod method, int particles, int beams, double max_range_m,
                         std::uint64_t seed);

std::shared_ptr<const MicroProgram> Program(const std::string& text, const std::string& name = "test.asm");

// One region of 1-byte nodes at `base` holding `elements` nodes.
MemoryRegion ByteRegion(std::uint64_t base, std::uint64_t elements);

}  // namespace rc::test
