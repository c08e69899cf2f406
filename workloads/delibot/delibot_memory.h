#pragma once
// What a DeliBot run must hold at once, so that a particle count that cannot
// fit is refused before the filter allocates (common/memory_cap.h).
#include <cstdint>

#include "workloads/delibot/delibot_run.h"

namespace rc {

// A lower bound (bytes) on the memory that grows with particles and beams:
// per particle its pose and two log weights; per particle and used beam one
// ray query and its hit (beam model; the likelihood field casts no rays),
// and with pricing at least one fetch offset, address and exit code per ray
// in the kernel record. Built from the sizes of those structures, so it
// never exceeds what the run really allocates; the measured peak is several
// times larger (docs/robustness.md). Largest of the particle counts a run
// may reach (--particles, --initial-particles, --max-particles).
std::uint64_t DelibotMemoryLowerBound(const DelibotSettings& settings, int beam_count);

}  // namespace rc
