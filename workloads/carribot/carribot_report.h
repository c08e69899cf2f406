#pragma once
// CarriBot's outputs: the timeline (CSV, one row per query, preceded by a
// 'setup' row when the collision kernel filled the configuration space) and
// the backend summary printed at the end of a run (as DeliBot's).
//
// Timeline columns (units in the names):
//   scenario, bucket, sx, sy, gx, gy        the query (cells); empty for setup
//   path_length_cells, path_length_m, optimal_length_cells, turns
//   expanded, collision_queries             A* expansions; motions checked
//   kernel_launches, kernel_queries         collision-kernel work of the row
//   nodes_per_query                         tree nodes fetched per kernel query
//   wall_s                                  host time (pricing excluded)
//   status                                  found, no_path, ..., or setup
// and when priced: backend (the policy's choice), switched, cycles_<backend>
// for every modelled backend (core cycles; ttaplus-p is cycles_ttaplus_p),
// energy_j (the chosen backend's dynamic energy), cum_cycles_policy,
// cum_cycles_oracle, oracle_backend.
#include <ostream>
#include <string>
#include <vector>

#include "workloads/carribot/carribot_run.h"

namespace rc {

void WriteCarribotTimeline(const std::string& path, const std::vector<CarribotQuery>& queries,
                           const CarribotResult& result);

// The modelled time of every static backend, the policy and the hindsight
// oracle, and the threshold; nothing when the run was not priced.
void PrintCarribotPricing(std::ostream& out, const CarribotResult& result, const CarribotSettings& settings);

}  // namespace rc
