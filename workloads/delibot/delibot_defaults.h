#pragma once
// The settings `rcbench delibot` starts from, in one place. How each was
// chosen, by which rule, on which data, and what was checked on data the
// choice never saw: docs/defaults.md. DelibotSettings' own member defaults
// stay the plain filter (beam model, 2000 uniform particles, augmented
// MCL): the library's tests and the studies that name their options build
// on those.
#include <string>

#include "workloads/delibot/delibot_run.h"

namespace rc {

// The likelihood field (nav2's cube sum, unknown space as an edge) while the
// belief has rivals, the beam model (also the cube sum) once one hypothesis is left;
// the dense first set sized by the map (kAutoInitialParticles); a
// 500-particle floor per hypothesis in a 6-nat window, the set growing to
// 20000 while rivals are alive; no random injection; every claim of being
// localized audited before it is made (claim_audit.h).
DelibotSettings DefaultDelibotSettings();

// Which options the user gave; the defaults of the others follow them.
struct GivenDelibotOptions {
  bool sensor_model = false;
  bool initial_particles = false;
  bool hypothesis_floor = false;
  bool max_particles = false;
  bool claim_audit = false;  // --claim-audit or --no-claim-audit
  bool max_range = false;    // --max-range (not given: fitted to the trace, returns_beyond_reach.h)
};

// Fits the defaults the user did not override to the options they gave:
// the floor at most half the particles (a floor above that is refused, see
// MclOptions), the set's cap at least the particles and 0 without a floor.
// For the MRPT engine the options MRPT has no counterpart of go back to
// "off" unless given (given, the engine refuses them), and an unstated
// sensor model is the beam model: MRPT has no staged model. With our
// engine and the beam model alone, claims are not audited unless asked
// (the audit was checked scoring with the likelihood field). Returns notes
// for the user, one per line, empty if none.
std::string FitDefaultsToGivenOptions(DelibotSettings& settings, const GivenDelibotOptions& given, bool mrpt_engine);

}  // namespace rc
