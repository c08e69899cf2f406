#pragma once
// A pass-through ompl::NearestNeighbors that counts the queries it forwards
// (nearest, nearestK, nearestR), so that the timeline can report NN queries
// for OMPL's own structures (GNAT), which keep no counters of their own.
// Answers are the inner structure's, unchanged.
#include <cstdint>
#include <memory>
#include <vector>

#include <ompl/datastructures/NearestNeighbors.h>

namespace rc {

template <typename T>
class CountingNearestNeighbors final : public ompl::NearestNeighbors<T> {
 public:
  explicit CountingNearestNeighbors(std::shared_ptr<ompl::NearestNeighbors<T>> inner) : inner_(std::move(inner)) {}

  void setDistanceFunction(const typename ompl::NearestNeighbors<T>::DistanceFunction& distance) override {
    ompl::NearestNeighbors<T>::setDistanceFunction(distance);
    inner_->setDistanceFunction(distance);
  }
  bool reportsSortedResults() const override { return inner_->reportsSortedResults(); }
  void clear() override { inner_->clear(); }
  void add(const T& data) override { inner_->add(data); }
  void add(const std::vector<T>& data) override { inner_->add(data); }
  bool remove(const T& data) override { return inner_->remove(data); }
  T nearest(const T& data) const override {
    ++queries_;
    return inner_->nearest(data);
  }
  void nearestK(const T& data, std::size_t k, std::vector<T>& nbh) const override {
    ++queries_;
    inner_->nearestK(data, k, nbh);
  }
  void nearestR(const T& data, double radius, std::vector<T>& nbh) const override {
    ++queries_;
    inner_->nearestR(data, radius, nbh);
  }
  std::size_t size() const override { return inner_->size(); }
  void list(std::vector<T>& data) const override { inner_->list(data); }

  // Queries since the last take.
  std::uint64_t TakeQueries() {
    const std::uint64_t q = queries_;
    queries_ = 0;
    return q;
  }

 private:
  std::shared_ptr<ompl::NearestNeighbors<T>> inner_;
  mutable std::uint64_t queries_ = 0;
};

}  // namespace rc
