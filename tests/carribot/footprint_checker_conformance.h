#pragma once
// The contract of every FootprintChecker (footprint_checker.h), reusable by
// the collision-kernel backends: on every cell and heading of a map, the
// checker's answer must equal the exact configuration space.
#include <gtest/gtest.h>

#include <string>

#include "workloads/carribot/configuration_space.h"
#include "workloads/carribot/footprint_checker.h"
#include "workloads/carribot/footprint_stencils.h"

namespace rc::test {

inline ::testing::AssertionResult CheckerMatchesExactConfigurationSpace(FootprintChecker& checker,
                                                                        const OccupancyGrid& grid,
                                                                        const FootprintStencils& stencils) {
  const ConfigurationSpace exact = ConfigurationSpace::FromStencils(grid, stencils);
  const ConfigurationSpace asked = ConfigurationSpace::FromChecker(grid, stencils, checker);
  std::size_t differences = 0;
  std::string first;
  for (int ix = 0; ix < grid.size_x(); ++ix)
    for (int iy = 0; iy < grid.size_y(); ++iy)
      for (int h = 0; h < stencils.heading_count(); ++h)
        if (exact.IsFree(ix, iy, h) != asked.IsFree(ix, iy, h) && differences++ == 0)
          first = "cell (" + std::to_string(ix) + ", " + std::to_string(iy) + ") heading " + std::to_string(h) +
                  ": exact says " + (exact.IsFree(ix, iy, h) ? "free" : "collision");
  if (differences == 0)
    return ::testing::AssertionSuccess() << exact.CountFree() << " free states of " << exact.free_states().size();
  return ::testing::AssertionFailure() << checker.name() << " differs from the exact configuration space on "
                                       << differences << " states; first: " << first;
}

}  // namespace rc::test
