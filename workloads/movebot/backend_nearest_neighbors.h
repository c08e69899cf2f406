#pragma once
// rc::BackendNearestNeighbors<T>: an ompl::NearestNeighbors<T> whose
// nearest, k-nearest and radius queries run as the ball-query kernel
// (robocore/ball_query/), each query recorded for the modelled backends.
//
// Interface agreed with the MoveBot planner (which injects it into stock
// RRTstar through the protected nn_ before setup()):
//   BackendNearestNeighbors(BallQueryConfig config,
//                           std::function<const double*(const T&)> coordinates,
//                           std::size_t dimension);
//   KernelRecord TakeKernelRecord();     // every query since the last take: one batch
//   BallQueryCounters counters() const;  // queries, nodes visited, nodes per query
// plus ResetCounters(). OMPL 1.5.2 has no virtual reportsExactResults(); the
// class answers reportsSortedResults() == true and offers a non-virtual
// reportsExactResults() == true.
//
// Distance: the kernel uses the Euclidean distance on `coordinates`, computed
// as OMPL's RealVectorStateSpace::distance does, so this class requires that
// distance (RRTstar sets distFun_ to si->distance(), which on a
// RealVectorStateSpace is it). add() checks the planner's distance function,
// if one is set, against the kernel's on the new and the previous element,
// and throws std::invalid_argument when they disagree.
//
// Results equal NearestNeighborsLinear's: the same elements, sorted by
// distance; between equal distances the element added first comes first
// (NearestNeighborsLinear::nearest's rule). remove() removes the most
// recently added element equal to the argument, as NearestNeighborsLinear
// does (a scan: O(size); RRTstar removes only when pruning). clear()
// empties the structure but keeps the record and counters. counters() add
// up from construction or ResetCounters(); a taken record carries its own
// batch's numbers (query_count(), total_nodes()).
//
// Memory: the tree (ball_query_tree.h: 32n + 8 bytes per node slot plus n
// doubles per state on the host) and the record (9 bytes per node fetch +
// 8 per query) until it is taken.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/Exception.h>

#include "robocore/ball_query/ball_query_config.h"
#include "robocore/ball_query/ball_query_record.h"
#include "robocore/ball_query/ball_query_search.h"
#include "robocore/ball_query/ball_query_tree.h"
#include "robocore/kernel_record.h"

namespace rc {

template <typename T>
class BackendNearestNeighbors : public ompl::NearestNeighbors<T> {
 public:
  using CoordinatesFunction = std::function<const double*(const T&)>;

  // Throws std::invalid_argument for an invalid config (naming the field),
  // an empty coordinates function, dimension 0, or a dimension the shipped
  // programs cannot record (> kMaxRecordedDimension with config.record).
  BackendNearestNeighbors(BallQueryConfig config, CoordinatesFunction coordinates, std::size_t dimension)
      : config_(Checked(config)), coordinates_(std::move(coordinates)), tree_(dimension) {
    if (!coordinates_) throw std::invalid_argument("BackendNearestNeighbors: the coordinates function is empty");
    if (config_.record) recorder_.emplace(config_.formulation, dimension, config_.base_address);
  }

  bool reportsSortedResults() const override { return true; }
  static constexpr bool reportsExactResults() { return true; }

  void clear() override {
    tree_.Clear();
    items_.clear();
    last_ = std::nullopt;
  }

  void add(const T& data) override {
    const double* p = coordinates_(data);
    if (last_ && this->distFun_) CheckDistance(data, p);
    const BallStateId id = tree_.Insert(p);
    if (id >= items_.size()) items_.resize(id + 1, data);
    items_[id] = data;
    last_ = id;
  }

  bool remove(const T& data) override {
    std::optional<BallStateId> found;
    for (BallStateId id = 0; id < items_.size(); ++id)
      if (tree_.IsLive(id) && items_[id] == data && (!found || tree_.Sequence(id) > tree_.Sequence(*found))) found = id;
    if (!found) return false;
    tree_.Remove(*found);
    if (last_ && *last_ == *found) last_ = std::nullopt;
    if (tree_.empty()) clear();
    return true;
  }

  T nearest(const T& data) const override {
    if (tree_.empty()) throw ompl::Exception("No elements found in nearest neighbors data structure");
    BallNearestK(tree_, config_, coordinates_(data), 1, result_, &visits_);
    Account();
    return items_[result_.front().id];
  }

  void nearestK(const T& data, std::size_t k, std::vector<T>& nbh) const override {
    nbh.clear();
    if (k == 0 || tree_.empty()) return;
    BallNearestK(tree_, config_, coordinates_(data), k, result_, &visits_);
    Account();
    for (const BallNeighbor& n : result_) nbh.push_back(items_[n.id]);
  }

  void nearestR(const T& data, double radius, std::vector<T>& nbh) const override {
    nbh.clear();
    if (!(radius >= 0) || tree_.empty()) return;
    BallWithinRadius(tree_, config_, coordinates_(data), radius, result_, &visits_);
    Account();
    for (const BallNeighbor& n : result_) nbh.push_back(items_[n.id]);
  }

  std::size_t size() const override { return tree_.size(); }

  // In insertion order, as NearestNeighborsLinear::list.
  void list(std::vector<T>& data) const override {
    std::vector<BallStateId> ids;
    for (BallStateId id = 0; id < items_.size(); ++id)
      if (tree_.IsLive(id)) ids.push_back(id);
    std::sort(ids.begin(), ids.end(),
              [&](BallStateId a, BallStateId b) { return tree_.Sequence(a) < tree_.Sequence(b); });
    data.clear();
    for (BallStateId id : ids) data.push_back(items_[id]);
  }

  // Every query since the last take, one thread each, as one batch for
  // Backend::Price / PriceAll. Empty (query_count() == 0, no region) when
  // nothing was queried or config.record is off: do not price it.
  KernelRecord TakeKernelRecord() { return recorder_ ? recorder_->Take() : KernelRecord{}; }

  BallQueryCounters counters() const { return counters_; }
  void ResetCounters() { counters_ = BallQueryCounters{}; }

  const BallQueryConfig& config() const { return config_; }
  const BallQueryTree& tree() const { return tree_; }

 private:
  static BallQueryConfig Checked(const BallQueryConfig& config) {
    std::string error;
    if (!config.IsValid(&error)) throw std::invalid_argument("BackendNearestNeighbors: BallQueryConfig." + error);
    return config;
  }

  void CheckDistance(const T& data, const double* p) const {
    const double* q = tree_.Coordinates(*last_);
    const double ours = EuclideanDistance(p, q, tree_.dimension());
    const double theirs = this->distFun_(data, items_[*last_]);
    if (!(std::abs(ours - theirs) <= 1e-9 * (1.0 + ours)))
      throw std::invalid_argument("BackendNearestNeighbors: the distance function gives " + std::to_string(theirs) +
                                  " where the Euclidean distance on the coordinates is " + std::to_string(ours) +
                                  "; the ball-query kernel needs RealVectorStateSpace's distance");
  }

  void Account() const {
    ++counters_.queries;
    counters_.nodes_visited += visits_.nodes.size();
    counters_.passes += visits_.passes;
    if (recorder_) recorder_->AddQuery(visits_, tree_.node_slots());
  }

  BallQueryConfig config_;
  CoordinatesFunction coordinates_;
  BallQueryTree tree_;
  std::vector<T> items_;  // by state id
  std::optional<BallStateId> last_;
  mutable std::optional<BallQueryRecorder> recorder_;
  mutable BallQueryCounters counters_;
  mutable BallQueryVisits visits_;
  mutable std::vector<BallNeighbor> result_;
};

}  // namespace rc
