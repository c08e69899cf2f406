#pragma once
// The real-log settings of docs/real_logs.md, shared by the tests that check them on the
// Wean logs and on simulated traces.
#include "workloads/delibot/delibot_run.h"

namespace rc::test {

// The real-log recipe: likelihood field, 500,000 uniform particles for the
// first update, no random injection.
inline DelibotSettings RealLogRecipe() {
  DelibotSettings s;
  s.sensor_model = SensorModelKind::kLikelihoodField;
  s.mcl.initial_particle_count = 500000;
  s.mcl.alpha_slow = 0.0;
  return s;
}

// The cautious recipe (docs/real_logs_cautious_recipe.md): nav2's cube
// sum with unknown space as an edge, 2,000,000 first particles, a
// 500-particle floor in a 6-nat window, a set growing to 20000 while rivals
// are alive.
inline DelibotSettings CautiousRealLogRecipe() {
  DelibotSettings s = RealLogRecipe();
  s.likelihood.combination = BeamCombination::kAmclCubeSum;
  s.likelihood.unknown_is_edge = true;
  s.mcl.initial_particle_count = 2000000;
  s.mcl.hypothesis_floor = {500, 6.0};
  s.mcl.max_particle_count = 20000;
  return s;
}

}  // namespace rc::test
