#pragma once
// How the per-beam scores of one scan make the scan's likelihood. Both
// sensor models offer the same two rules, so the choice is one concept here.
#include <cmath>
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

// One scan's log-likelihood, built beam by beam under a combination: the
// product adds each beam's log density, the cube sum adds pz^3 to 1 and
// takes the log at the end. A model asks cube_sum() which of the two
// per-beam quantities to compute.
class ScanLikelihood {
 public:
  explicit ScanLikelihood(BeamCombination combination) : cube_sum_(combination == BeamCombination::kAmclCubeSum) {}
  bool cube_sum() const { return cube_sum_; }
  void AddLogDensity(double log_density) { log_product_ += log_density; }
  void AddProbability(double pz) { cube_total_ += pz * pz * pz; }
  double Log() const { return cube_sum_ ? std::log(cube_total_) : log_product_; }

 private:
  bool cube_sum_;
  double log_product_ = 0.0;
  double cube_total_ = 1.0;
};

}  // namespace rc
