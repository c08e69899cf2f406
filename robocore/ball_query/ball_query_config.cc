#include "robocore/ball_query/ball_query_config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace rc {

const char* ToString(BallQueryFormulation formulation) {
  switch (formulation) {
    case BallQueryFormulation::kPRay: return "pray";
    case BallQueryFormulation::kPSphere: return "psphere";
  }
  return "?";
}

BallQueryFormulation ParseBallQueryFormulation(const std::string& text) {
  std::string t;
  for (char c : text)
    if (c != '-') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "pray") return BallQueryFormulation::kPRay;
  if (t == "psphere") return BallQueryFormulation::kPSphere;
  throw std::invalid_argument("ball-query formulation '" + text + "' (expected pray or psphere)");
}

bool BallQueryConfig::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (formulation != BallQueryFormulation::kPRay && formulation != BallQueryFormulation::kPSphere)
    return fail("formulation: must be pray or psphere");
  if (!(std::isfinite(sphere_radius) && sphere_radius > 0))
    return fail("sphere_radius: " + std::to_string(sphere_radius) + " must be finite and > 0");
  if (!(std::isfinite(radius_growth) && radius_growth > 1))
    return fail("radius_growth: " + std::to_string(radius_growth) + " must be finite and > 1");
  return true;
}

}  // namespace rc
