#pragma once
// An oriented bounding box: centre, rotation and half extents.
//
// Convention (the one the RoboGPU artifact got wrong, REFERENCE.md section
// 2): the COLUMNS of `axes` are the box's local axes expressed in world
// coordinates, so a point p in the box frame sits at centre + axes * p in
// the world, and a world offset d has box-frame coordinates axes^T * d.
// The mpnet_master_obb.csv file lists axis 1, axis 2, axis 3 in that order,
// each as a world-frame xyz triple; they become columns 0, 1, 2.
//
// The box is the set { centre + axes * p : |p_i| <= half_i }. A half extent
// may be 0 (a rectangle, a segment or a point); never negative.
#include <Eigen/Core>

namespace rc {

template <typename Scalar>
struct Obb {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  using Mat3 = Eigen::Matrix<Scalar, 3, 3>;

  Vec3 centre = Vec3::Zero();    // m, world frame
  Mat3 axes = Mat3::Identity();  // column i = box axis i in world coordinates (unit)
  Vec3 half = Vec3::Zero();      // m, half extent along each box axis (>= 0)

  template <typename To>
  Obb<To> Cast() const {
    Obb<To> o;
    o.centre = centre.template cast<To>();
    o.axes = axes.template cast<To>();
    o.half = half.template cast<To>();
    return o;
  }
};

using Obbd = Obb<double>;
using Obbf = Obb<float>;

// `box` expressed in the box frame of `frame` (frame's centre the origin,
// its axes the coordinate axes). There `frame` is the axis-aligned box of
// half extents frame.half centred at the origin: how a pair of OBBs becomes
// the OBB/AABB pair that the SACT and the exact reference test. frame.axes
// must be orthonormal (its transpose is taken as its inverse).
template <typename Scalar>
Obb<Scalar> InFrameOf(const Obb<Scalar>& box, const Obb<Scalar>& frame) {
  Obb<Scalar> local;
  local.centre = frame.axes.transpose() * (box.centre - frame.centre);
  local.axes = frame.axes.transpose() * box.axes;
  local.half = box.half;
  return local;
}

}  // namespace rc
