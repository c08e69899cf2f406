#include "robocore/collision/sact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

template <typename Scalar>
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
template <typename Scalar>
using Mat3 = Eigen::Matrix<Scalar, 3, 3>;

// Relative slack of the sphere pre-tests: 16 ulps covers the rounding of a
// squared distance, a norm and a sum, so a pre-test never decides a pair
// that real arithmetic would decide the other way.
template <typename Scalar>
constexpr Scalar kSphereSlack = 16 * std::numeric_limits<Scalar>::epsilon();

template <typename Scalar>
std::optional<SactResult> SpherePretest(const Obb<Scalar>& obb, const Aabb<Scalar>& box) {
  const Scalar distance_sq = (box.centre - obb.centre).squaredNorm();
  const Scalar outer = obb.half.norm() + box.half.norm();
  if (distance_sq > outer * outer * (1 + kSphereSlack<Scalar>))
    return SactResult{kSactSphereSeparated, 0, SactDecision::kOuterSphereReject};
  // Inscribed balls: radius = smallest half extent; both balls lie in their
  // boxes, so if they meet, so do the boxes.
  const Scalar inner = obb.half.minCoeff() + box.half.minCoeff();
  if (distance_sq <= inner * inner * (1 - kSphereSlack<Scalar>))
    return SactResult{kSactOverlap, 0, SactDecision::kInnerSphereAccept};
  return std::nullopt;
}

}  // namespace

template <typename Scalar>
bool SactOptions<Scalar>::IsValid(std::string* error) const {
  if (!(parallel_epsilon >= 0) || !std::isfinite(parallel_epsilon)) {
    if (error) *error = "parallel_epsilon must be finite and >= 0";
    return false;
  }
  return true;
}

// A = the OBB (centre a, axes A_i = columns, half extents ea), B = the AABB
// (centre b, axes = world x, y, z, half extents eb). Ericson 4.4.1 with
// R_ij = A_i . B_j and t = the translation in A's frame.
template <typename Scalar>
SactResult TestObbAabb(const Obb<Scalar>& obb, const Aabb<Scalar>& box,
                       const SactOptions<Scalar>& options) {
  if (options.sphere_pretests) {
    if (const auto decided = SpherePretest(obb, box)) return *decided;
  }
  // Pre-process. B's axes are the world axes, so R_ij = A_i[j] exactly:
  // R needs no arithmetic at all, one reason the OBB/AABB test is more
  // robust than the general OBB/OBB test.
  const Vec3<Scalar> d = box.centre - obb.centre;
  const Mat3<Scalar> R = obb.axes.transpose();
  const Vec3<Scalar> t =
      options.convention == TranslationConvention::kBoxFrame ? Vec3<Scalar>(R * d) : Vec3<Scalar>(obb.axes * d);
  const Mat3<Scalar> abs_r = R.cwiseAbs().array() + options.parallel_epsilon;
  const Vec3<Scalar>& ea = obb.half;
  const Vec3<Scalar>& eb = box.half;

  SactResult result;
  // Box-normal stage, A's axes: |t_i| against ea_i + sum_j eb_j |R_ij|.
  for (int i = 0; i < 3; ++i) {
    ++result.axes_tested;
    if (std::abs(t[i]) > ea[i] + eb.dot(abs_r.row(i).transpose())) {
      result.separating_axis = static_cast<std::int8_t>(i);
      return result;
    }
  }
  // Box-normal stage, B's axes. The translation along world axis j is d_j;
  // Ericson writes it as t . R_col(j), which is the same number after one
  // more rounding. The artifact's convention needs the rotated form to keep
  // its (wrong) t.
  const Vec3<Scalar> t_b =
      options.convention == TranslationConvention::kBoxFrame ? d : Vec3<Scalar>(R.transpose() * t);
  for (int j = 0; j < 3; ++j) {
    ++result.axes_tested;
    if (std::abs(t_b[j]) > eb[j] + ea.dot(abs_r.col(j))) {
      result.separating_axis = static_cast<std::int8_t>(3 + j);
      return result;
    }
  }
  // Edge x edge stage: L = A_i x B_j; in A's frame L = e_i x R_col(j), so
  // t . L = t[i2] R[i1][j] - t[i1] R[i2][j], with (i, i1, i2) and (j, j1, j2)
  // cyclic (Ericson's nine unrolled cases, as one loop).
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      ++result.axes_tested;
      const Scalar ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const Scalar rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) {
        result.separating_axis = static_cast<std::int8_t>(6 + 3 * i + j);
        return result;
      }
    }
  }
  return result;  // no axis separates: overlap (touching included)
}

template struct SactOptions<float>;
template struct SactOptions<double>;
template SactResult TestObbAabb(const Obb<float>&, const Aabb<float>&, const SactOptions<float>&);
template SactResult TestObbAabb(const Obb<double>&, const Aabb<double>&, const SactOptions<double>&);

std::string SactAxisName(int axis) {
  if (axis == kSactOverlap) return "overlap";
  if (axis == kSactSphereSeparated) return "sphere";
  if (axis < 0 || axis >= kSactAxisCount) return "?";
  if (axis < 3) return "A" + std::to_string(axis);
  if (axis < 6) return "B" + std::to_string(axis - 3);
  const int k = axis - 6;
  return "A" + std::to_string(k / 3) + "xB" + std::to_string(k % 3);
}

SactStageCounts StagesOf(const SactResult& result, bool sphere_pretests) {
  SactStageCounts c;
  c.sphere_pretests = sphere_pretests ? 1 : 0;
  if (result.decided_by != SactDecision::kAxes) return c;
  c.pre_process = 1;
  c.box_normal = std::min<int>(result.axes_tested, kSactBoxNormalAxes);
  c.edge_edge = std::max<int>(result.axes_tested - kSactBoxNormalAxes, 0);
  return c;
}

void AppendStages(const SactResult& result, bool sphere_pretests, std::vector<SactStage>& stages) {
  const SactStageCounts c = StagesOf(result, sphere_pretests);
  if (c.sphere_pretests) stages.push_back(SactStage::kSpherePretest);
  if (c.pre_process) stages.push_back(SactStage::kPreProcess);
  stages.insert(stages.end(), c.box_normal, SactStage::kBoxNormal);
  stages.insert(stages.end(), c.edge_edge, SactStage::kEdgeEdge);
}

std::optional<Opcode> OpcodeOf(SactStage stage) {
  switch (stage) {
    case SactStage::kSpherePretest: return std::nullopt;
    case SactStage::kPreProcess: return Opcode::kPre;
    case SactStage::kBoxNormal: return Opcode::kBox;
    case SactStage::kEdgeEdge: return Opcode::kEdge;
  }
  return std::nullopt;
}

}  // namespace rc
