#pragma once
// How the per-beam scores of one scan make the scan's likelihood. Both
// sensor models offer the same two rules, so the choice is one concept here.
#include <string>

namespace rc {

enum class BeamCombination {
  // Product of the beams' densities, summed in the log domain (Thrun et al.
  // 6.3 and 6.4; MRPT). Treats the beams as independent, so a scan of n
  // beams is n pieces of evidence, and a map error that repeats scan after
  // scan adds up to hundreds of nats.
  kProduct,
  // nav2 AMCL's and Beluga's rule for both models: 1 + sum over beams of
  // pz^3, where pz is the beam's mixture without the Gaussian's normalizer
  // (so pz <= 1). A heuristic: one scan can change a weight by at most a
  // factor 1 + n * max(pz)^3 (about 6 for 30 likelihood-field beams at the
  // defaults), so evidence builds over many updates and repeated map errors
  // weigh less than under the product.
  kAmclCubeSum,
};

const char* ToString(BeamCombination combination);
// "product" | "amcl-cube"; throws std::invalid_argument otherwise.
BeamCombination ParseBeamCombination(const std::string& name);

}  // namespace rc
