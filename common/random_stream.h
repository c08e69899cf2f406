#pragma once
// Deterministic random streams, one per (seed, purpose, iteration, index).
//
// Why not std::mt19937 + std::normal_distribution: the standard distributions
// are implementation-defined, so the same seed would give different
// timelines on another standard library; and one shared generator would make
// results depend on thread scheduling. Here every particle (or task) owns a
// stream derived by hashing its coordinates, so the timeline is identical at
// any thread count (DESIGN.md, "Determinism"). RoWild's DeliBot draws one
// noise sample per update for all particles from a freshly seeded generator,
// which collapses the particle set; one stream per particle avoids that.
#include <cmath>
#include <cstdint>

namespace rc {

// Purposes keep streams of different components independent even when the
// other coordinates coincide.
enum class StreamPurpose : std::uint64_t {
  kMotion = 1,
  kResample = 2,
  kInjection = 3,
  kInitialization = 4,
  kSimulation = 5,
  kMapGeneration = 6,
  kTest = 7,
  kStartProbe = 8,  // the adaptive scheduler's start probe (workloads/delibot/start_probe.h)
  kClaimAudit = 9,  // the poses a claim audit samples (workloads/delibot/claim_audit.h)
};

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, StreamPurpose purpose, std::uint64_t iteration, std::uint64_t index) {
    std::uint64_t h = Mix(seed ^ 0x9E3779B97F4A7C15ULL);
    h = Mix(h ^ static_cast<std::uint64_t>(purpose));
    h = Mix(h ^ (iteration * 0xD1B54A32D192ED03ULL));
    h = Mix(h ^ (index * 0xABC98388FB8FAC03ULL));
    // xoshiro256** state from a splitmix64 sequence (its authors' advice).
    for (auto& s : state_) {
      h += 0x9E3779B97F4A7C15ULL;
      s = Mix(h);
    }
  }

  std::uint64_t NextU64() {
    const std::uint64_t result = Rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = Rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1), 53 random bits.
  double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; the bias is
  // below 2^-32 for the sizes used here).
  std::uint64_t Below(std::uint64_t n) {
    __extension__ typedef unsigned __int128 Wide;  // GCC/Clang builtin
    return static_cast<std::uint64_t>((static_cast<Wide>(NextU64()) * n) >> 64);
  }
  // Standard normal by Box-Muller; the spare value is kept, so the sequence
  // is a pure function of the stream's coordinates.
  double Gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = Uniform();
    while (u1 <= 0.0) u1 = Uniform();
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 6.283185307179586476925 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }
  double Gaussian(double sigma) { return sigma * Gaussian(); }

 private:
  static std::uint64_t Mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  static std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

  std::uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace rc
