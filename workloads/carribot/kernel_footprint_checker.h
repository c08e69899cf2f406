#pragma once
// The FootprintChecker that runs on the collision kernel: every pose becomes
// an OBB (the footprint rectangle, zero height) and is tested against the
// map's quadtree of blocked cells by the staged SACT (robocore/collision/
// tree_collision.h). One CheckPoses call is one kernel launch. A caller that
// prices the launches on the modelled backends gets each one as:
//  - a KernelRecord (set_record_observer): recorded in the kernel's own pass
//    (CollideBatchRecorded), parallel over the GPU's blocks of queries,
//    keeping the addresses of the queries a sample names; what carribot_run
//    uses;
//  - or a CollisionBatch with every visit (set_batch_observer), for callers
//    that want the visits themselves.
// With neither, a launch computes the outcomes and node counts only (in
// parallel) and keeps no visits.
//
// Exactness (it must equal RasterizedFootprintChecker on every lattice pose,
// tests/carribot/kernel_footprint_checker_test.cc):
//  - Units are cells, not metres: the tree is built from the grid at
//    resolution 1, so cell boxes have integer or half-integer coordinates
//    and the centre offsets the SACT forms are exact, as in the reference.
//  - Blocked means "not free" (unknown cells are obstacles), as in the
//    reference.
//  - Out of the map: the tree is built over the map padded with a ring of
//    blocked cells. A footprint whose centre lies in the open map rectangle
//    leaves that rectangle only through its boundary (it is convex), and the
//    ring covers the boundary, so touching the ring is exactly touching some
//    cell outside the map. A pose whose centre is not inside the open map
//    rectangle is answered "collision" on the host without a kernel query
//    (the reference says the same: the centre itself touches an outside
//    cell); planner poses never take that path.
//  - The footprint is planar: its OBB has zero z extent at the middle of the
//    cells' z slab and z axis exactly (0, 0, 1), so every z-related SACT
//    term is exactly zero and the test reduces to the 2D separating axes.
//  - SACT parallel epsilon 0: the epsilon exists to stop rounding noise on a
//    near-zero edge x edge axis from separating boxes (sact.h). In this
//    planar set-up the only parallel edge pairs give cross products whose
//    components are exact zeros, so there is no noise to guard against, and
//    a positive epsilon would turn near-contacts (gap below epsilon x the
//    box sizes) into false collisions.
//
// Cost: the quadtree has fewer than 2 nodes per blocked cell plus the ring
// (64-byte double nodes); building it is O(cells). A query visits the nodes
// whose bounds its OBB touches, depth-first, and stops at the first
// colliding leaf.
#include <cstdint>
#include <functional>

#include "maps/occupancy_grid.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/tree_collision.h"
#include "workloads/carribot/footprint_checker.h"

namespace rc {

class KernelFootprintChecker final : public FootprintChecker {
 public:
  using BatchObserver = std::function<void(const CollisionBatch&)>;
  using RecordObserver = std::function<void(const KernelRecord&)>;

  explicit KernelFootprintChecker(const OccupancyGrid& grid);

  const char* name() const override { return "kernel"; }
  void CheckPoses(const FootprintPose* poses, std::size_t count, std::uint8_t* collides) override;
  std::uint64_t poses_checked() const override { return poses_checked_; }

  // Called with every launched batch (null: none). Takes precedence over a
  // record observer.
  void set_batch_observer(BatchObserver observer) { observer_ = std::move(observer); }
  // Called with every launch's record, whose addresses are kept for the
  // queries `sample` names (robocore/address_sample.h; null observer: none).
  void set_record_observer(RecordObserver observer, const AddressSample& sample = AddressSample{}) {
    record_observer_ = std::move(observer);
    sample_ = sample;
  }

  const FlatBoxTree<double>& tree() const { return tree_; }
  std::uint64_t batches() const { return batches_; }  // kernel launches
  std::uint64_t kernel_queries() const { return kernel_queries_; }
  std::uint64_t node_visits() const { return node_visits_; }  // node fetches, every launch

 private:
  int size_x_ = 0;
  int size_y_ = 0;
  FlatBoxTree<double> tree_;
  CollisionOptions<double> options_;
  BatchObserver observer_;
  RecordObserver record_observer_;
  AddressSample sample_;
  std::vector<Obbd> obbs_;         // reused between launches
  std::vector<std::size_t> slot_;  // pose index of each OBB
  CollisionBatch batch_;           // the last launch (batch observer); its buffers are reused
  std::vector<TraversalOutcome> outcomes_;
  KernelRecord record_;  // the last launch (record observer)
  std::uint64_t poses_checked_ = 0;
  std::uint64_t batches_ = 0;
  std::uint64_t kernel_queries_ = 0;
  std::uint64_t node_visits_ = 0;
};

}  // namespace rc
