#pragma once
// Collects ball queries' node fetches into the KernelRecord every backend
// prices (DESIGN.md, "run once, price many times"), for the shipped program
// of the formulation:
//   P-Ray     programs/ball_query_pray.asm     (StepProgramKind::kBallQueryPRay)
//   P-Sphere  programs/ball_query_psphere.asm  (StepProgramKind::kBallQueryPSphere)
// Mapping:
//   region   the tree's device node array {base, 32n + 8 bytes, node slots}
//            (ball_query_tree.h), as long as the largest pool seen
//   query    one thread: all passes of one query, fetches in order,
//            address = base + node * node_bytes
//   exit     the RETURN_IF that fired in the node's pass (0: no child
//            inside, 1: no state inside), kNoExit when a state went into the
//            best list.
// Memory: 9 bytes per fetch + 8 per query.
#include <cstdint>

#include "robocore/ball_query/ball_query_config.h"
#include "robocore/ball_query/ball_query_search.h"
#include "robocore/kernel_record.h"

namespace rc {

StepProgramKind BallQueryProgramKind(BallQueryFormulation formulation);

class BallQueryRecorder {
 public:
  // Throws std::invalid_argument if dimension exceeds kMaxRecordedDimension.
  BallQueryRecorder(BallQueryFormulation formulation, std::size_t dimension, std::uint64_t base_address);

  // Appends one query (one thread of the batch); node_slots is the tree's
  // device array length when the query ran.
  void AddQuery(const BallQueryVisits& visits, std::size_t node_slots);
  std::size_t query_count() const { return record_.query_count(); }

  // Returns the record of every query since the last Take (validated) and
  // starts a new one. An empty record (no queries) has no region.
  KernelRecord Take();

 private:
  void Reset();

  BallQueryFormulation formulation_;
  std::uint32_t node_bytes_;
  std::uint64_t base_;
  std::uint64_t slots_ = 0;
  KernelRecord record_;
};

}  // namespace rc
