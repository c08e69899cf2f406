#include "pair_generator.h"

#include <cmath>

#include <Eigen/Geometry>

#include "common/random_stream.h"

namespace rc::test {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Vec3 RandomUnit(RandomStream& r) {
  Vec3 v(r.Gaussian(), r.Gaussian(), r.Gaussian());
  while (v.norm() < 1e-6) v = Vec3(r.Gaussian(), r.Gaussian(), r.Gaussian());
  return v.normalized();
}

Mat3 RandomRotation(RandomStream& r) {
  Eigen::Quaterniond q(r.Gaussian(), r.Gaussian(), r.Gaussian(), r.Gaussian());
  return q.normalized().toRotationMatrix();
}

// A signed permutation: every OBB axis (anti)parallel to a world axis.
// Handedness is left random on purpose: a box does not care.
Mat3 SignedPermutation(RandomStream& r) {
  int perm[3] = {0, 1, 2};
  for (int i = 2; i > 0; --i) std::swap(perm[i], perm[r.Below(i + 1)]);
  Mat3 m = Mat3::Zero();
  for (int i = 0; i < 3; ++i) m(perm[i], i) = r.Below(2) ? 1.0 : -1.0;
  return m;
}

Mat3 ParallelRotation(RandomStream& r) {
  switch (r.Below(3)) {
    case 0: return SignedPermutation(r);
    case 1: {  // about one world axis: that axis stays parallel
      const int axis = static_cast<int>(r.Below(3));
      return SignedPermutation(r) * Eigen::AngleAxisd(r.Uniform(0, 6.283185307179586), Vec3::Unit(axis)).matrix();
    }
    default: {  // nearly parallel
      const double angle = std::pow(10.0, r.Uniform(-12, -4));
      return Eigen::AngleAxisd(angle, RandomUnit(r)).matrix() * SignedPermutation(r);
    }
  }
}

double Sign(double v) { return v < 0 ? -1.0 : 1.0; }

// The corner of a box centred at the origin that lies furthest along n.
Vec3 SupportOffset(const Mat3& axes, const Vec3& half, const Vec3& n) {
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 3; ++i) p += Sign(axes.col(i).dot(n)) * half[i] * axes.col(i);
  return p;
}

// The midpoint of the edge along axis `edge` furthest along n.
Vec3 EdgeSupportOffset(const Mat3& axes, const Vec3& half, const Vec3& n, int edge) {
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    if (i != edge) p += Sign(axes.col(i).dot(n)) * half[i] * axes.col(i);
  return p;
}

Vec3 RandomHalf(RandomStream& r, double scale) {
  return Vec3(r.Uniform(0.05, 1), r.Uniform(0.05, 1), r.Uniform(0.05, 1)) * scale;
}

}  // namespace

const char* ToString(PairFamily family) {
  switch (family) {
    case PairFamily::kGeneric: return "generic";
    case PairFamily::kVertexVertex: return "vertex-vertex";
    case PairFamily::kEdgeEdge: return "edge-edge";
    case PairFamily::kVertexOnFace: return "vertex-on-face";
    case PairFamily::kParallel: return "parallel";
  }
  return "?";
}

namespace {

// Places p.obb (axes and half set) against p.box (half set, centre 0) as
// p.family asks, with the gap p.gap; may move the box instead.
void Place(ObbAabbPair& p, RandomStream& r) {
  const Mat3 world = Mat3::Identity();
  p.box.centre = Vec3::Zero();
  switch (p.family) {
    case PairFamily::kGeneric:
      p.gap = 0;
      p.obb.centre = p.scale * Vec3(r.Uniform(-2.5, 2.5), r.Uniform(-2.5, 2.5), r.Uniform(-2.5, 2.5));
      break;
    case PairFamily::kVertexVertex: {
      // A lies beyond the plane through B's support corner, at `gap`.
      const Vec3 n = RandomUnit(r);
      const Vec3 vb = SupportOffset(world, p.box.half, n);
      const Vec3 va = SupportOffset(p.obb.axes, p.obb.half, -n);
      p.obb.centre = vb + p.gap * n - va;
      break;
    }
    case PairFamily::kEdgeEdge: {
      const int i = static_cast<int>(r.Below(3)), j = static_cast<int>(r.Below(3));
      Vec3 n = p.obb.axes.col(i).cross(Vec3::Unit(j));
      if (n.norm() < 1e-3) n = RandomUnit(r);  // nearly parallel edges: a vertex contact instead
      n.normalize();
      const Vec3 mb = EdgeSupportOffset(world, p.box.half, n, j);
      const Vec3 ma = EdgeSupportOffset(p.obb.axes, p.obb.half, -n, i);
      p.obb.centre = mb + p.gap * n - ma;
      break;
    }
    case PairFamily::kVertexOnFace:
    case PairFamily::kParallel: {
      const bool on_box_face = p.family == PairFamily::kParallel || r.Below(2);
      if (on_box_face) {  // a corner (or face) of the OBB on a face of the AABB
        const int j = static_cast<int>(r.Below(3));
        const Vec3 n = (r.Below(2) ? 1.0 : -1.0) * Vec3::Unit(j);
        Vec3 lateral = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
          if (k != j) lateral[k] = r.Uniform(-1, 1) * p.box.half[k];
        const Vec3 face_point = p.box.half[j] * n + lateral;
        p.obb.centre = face_point + p.gap * n - SupportOffset(p.obb.axes, p.obb.half, -n);
      } else {  // a corner of the AABB on a face of the OBB (OBB at the origin)
        const int i = static_cast<int>(r.Below(3));
        const Vec3 n = (r.Below(2) ? 1.0 : -1.0) * p.obb.axes.col(i);
        Vec3 lateral = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
          if (k != i) lateral += r.Uniform(-1, 1) * p.obb.half[k] * p.obb.axes.col(k);
        const Vec3 face_point = p.obb.half[i] * n + lateral;
        p.box.centre = face_point + p.gap * n - SupportOffset(world, p.box.half, -n);
        p.obb.centre = Vec3::Zero();
      }
      break;
    }
  }
}

PairFamily DrawFamily(RandomStream& r) {
  const double u = r.Uniform();
  return u < 0.4    ? PairFamily::kGeneric
         : u < 0.5  ? PairFamily::kVertexVertex
         : u < 0.65 ? PairFamily::kEdgeEdge
         : u < 0.8  ? PairFamily::kVertexOnFace
                    : PairFamily::kParallel;
}

double DrawGap(RandomStream& r, double scale) {
  return r.Uniform() < 0.25 ? 0.0 : (r.Below(2) ? 1 : -1) * scale * std::pow(10.0, r.Uniform(-15, -1));
}

}  // namespace

ObbAabbPair GeneratePair(std::uint64_t seed, std::uint64_t index) {
  RandomStream r(seed, StreamPurpose::kTest, 0, index);
  ObbAabbPair p;
  p.scale = std::pow(10.0, r.Uniform(-3, 3));
  p.family = DrawFamily(r);
  p.obb.axes = p.family == PairFamily::kParallel ? ParallelRotation(r) : RandomRotation(r);
  p.obb.half = RandomHalf(r, p.scale);
  p.box.half = RandomHalf(r, p.scale);
  if (r.Uniform() < 0.1) {
    Vec3& h = r.Below(2) ? p.obb.half : p.box.half;
    h[r.Below(3)] = 0;
  }
  p.gap = DrawGap(r, p.scale);
  Place(p, r);
  if (r.Uniform() < 0.25) {
    const Vec3 far = std::pow(10.0, r.Uniform(0, 6)) * p.scale * RandomUnit(r);
    p.obb.centre += far;
    p.box.centre += far;
  }
  return p;
}

Obbd ObbNearBox(const Aabbd& box, double obb_scale, std::uint64_t seed, std::uint64_t index) {
  RandomStream r(seed, StreamPurpose::kTest, 1, index);
  ObbAabbPair p;
  p.scale = obb_scale;
  p.family = DrawFamily(r);
  p.obb.axes = p.family == PairFamily::kParallel ? ParallelRotation(r) : RandomRotation(r);
  p.obb.half = RandomHalf(r, obb_scale);
  p.box.half = box.half;
  p.gap = DrawGap(r, obb_scale);
  Place(p, r);
  p.obb.centre += box.centre - p.box.centre;
  return p.obb;
}

}  // namespace rc::test
