#pragma once
// DeliBot's start probe for the adaptive scheduler (BackendLedger::Prepare,
// docs/scheduling.md, "Where to start"): before the first update nothing has
// been measured, and the first update of a global localization holds most
// of the run's cycles, so where the policy starts is most of the decision.
//
// The probe is the first update's batch as the run can know it in advance:
// `poses` poses drawn from the filter's initial distribution
// (MonteCarloLocalizer::DrawInitialPose: uniform over free space, or around
// the tracking start) from streams of their own (StreamPurpose::kStartProbe,
// seeded by the run's seed), each casting the update's selected beams with
// the run's ray caster and max range, in the update's launch order
// (particle-major, beam-minor), recorded as the update records its batch.
// It never sees the first update's particles or rays. Deterministic: the
// same seed gives the same probe at any thread count.
//
// Cost: one recorded cast of poses x beams rays (what the first update
// costs for that many particles, without the scoring).
#include <cstddef>

#include "robocore/ray_batch_recorded.h"
#include "workloads/delibot/monte_carlo_localizer.h"

namespace rc {

// `poses` for a first batch of `first_update_particles` particles with
// `beams_per_particle` rays each: every particle while the batch fits in
// BackendLedger::StartProbeQueries, otherwise as many whole particles as
// fit (at least one).
std::size_t StartProbePoses(std::size_t first_update_particles, int beams_per_particle);

KernelRecord CastStartProbe(const MonteCarloLocalizer& mcl, const RayCastScene& scene, const LaserGeometry& geometry,
                            const BeamSelection& beams, double max_range_m, std::size_t poses, std::uint64_t seed,
                            const RecordOptions& record_options);

}  // namespace rc
