#include "robocore/collision/sact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

// Relative slack of the sphere pre-tests: 16 ulps covers the rounding of a
// squared distance, a norm and a sum, so a pre-test never decides a pair
// that real arithmetic would decide the other way.
template <typename Scalar>
constexpr Scalar kSphereSlack = 16 * std::numeric_limits<Scalar>::epsilon();

}  // namespace

template <typename Scalar>
bool SactOptions<Scalar>::IsValid(std::string* error) const {
  if (!(parallel_epsilon >= 0) || !std::isfinite(parallel_epsilon)) {
    if (error) *error = "parallel_epsilon must be finite and >= 0";
    return false;
  }
  return true;
}

template <typename Scalar>
std::optional<SactResult> SactSpherePretest(const Obb<Scalar>& obb, const Aabb<Scalar>& box) {
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

template <typename Scalar>
SactResult TestObbAabb(const Obb<Scalar>& obb, const Aabb<Scalar>& box, const SactOptions<Scalar>& options) {
  return TestPreparedObbAabb(PrepareSactObb(obb, options), box);
}

template struct SactOptions<float>;
template struct SactOptions<double>;
template SactResult TestObbAabb(const Obb<float>&, const Aabb<float>&, const SactOptions<float>&);
template SactResult TestObbAabb(const Obb<double>&, const Aabb<double>&, const SactOptions<double>&);
template std::optional<SactResult> SactSpherePretest(const Obb<float>&, const Aabb<float>&);
template std::optional<SactResult> SactSpherePretest(const Obb<double>&, const Aabb<double>&);

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
