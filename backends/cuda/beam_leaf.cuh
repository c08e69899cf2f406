#pragma once
// The beam-model leaf on the CUDA cores, once per ray after the traversal,
// in two forms:
//   MaxLogBeamLogDensity  what programs/beam_leaf.asm computes on the RT
//                         units (whose ISA has no EXP or LOG): the max-log
//                         approximation of the mixture, from constants the
//                         host precomputes. The SIMT model prices this one
//                         by default, so every backend prices the same leaf.
//   BeamLogDensity        the host's exact log of the four-part mixture
//                         (workloads/delibot/beam_sensor_model.cc), statement
//                         for statement, with exp and log: the alternative
//                         simt.beam_leaf = exact.
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

// BeamModelParams (beam_sensor_model.h), in the kernel's scalar type.
template <typename T>
struct BeamParams {
  T z_hit;
  T z_short;
  T z_max;
  T z_rand;
  T sigma_hit_m;         // m
  T lambda_short_per_m;  // 1/m
  T max_range_m;         // m
  // The max-log leaf's constants (beam_leaf.asm's inputs).
  T neg_half_inv_var;  // -1 / (2 sigma_hit^2), 1/m^2
  T neg_lambda;        // -lambda_short, 1/m
  T log_z_hit;         // log(z_hit / (sigma_hit sqrt(2 pi)))
  T log_z_rand;        // log(z_rand / max_range)
  T log_z_max;         // log(z_max)
};

// beam_leaf.asm: the largest of the hit Gaussian's log, the short
// exponential's (only for z < z_star), the uniform floor, and the max-range
// point mass (only for a max reading).
template <typename T>
__device__ __forceinline__ T MaxLogBeamLogDensity(const BeamParams<T>& p, T z, T z_star) {
  const T e = z - z_star;
  const T lg_hit = e * e * p.neg_half_inv_var;
  const T lg_short = z < z_star ? z * p.neg_lambda : -T(INFINITY);
  T lg = Max(lg_hit, lg_short) + p.log_z_hit;
  lg = Max(lg, p.log_z_rand);
  if (z >= p.max_range_m) lg = Max(lg, p.log_z_max);
  return lg;
}

// What the host adds before the log of a max-range reading: 1e-300 in
// double; in float, whose smallest normal is about 1.2e-38, 1e-38.
__device__ __forceinline__ double LogFloor(double) { return 1e-300; }
__device__ __forceinline__ float LogFloor(float) { return 1e-38f; }

// Log density of the measured range z given the ray-cast range z_star.
template <typename T>
__device__ __forceinline__ T BeamLogDensity(const BeamParams<T>& p, T z, T z_star) {
  const T kInvSqrt2Pi = T(0.39894228040143267794);
  T density = T(0);
  if (z >= p.max_range_m) {
    density += p.z_max;
    return Log(density + LogFloor(T(0)));
  }
  const T e = (z - z_star) / p.sigma_hit_m;
  density += p.z_hit * kInvSqrt2Pi / p.sigma_hit_m * Exp(T(-0.5) * e * e);
  if (z < z_star) {
    const T normalizer = T(1) - Exp(-p.lambda_short_per_m * z_star);
    if (normalizer > T(0)) density += p.z_short * p.lambda_short_per_m * Exp(-p.lambda_short_per_m * z) / normalizer;
  }
  density += p.z_rand / p.max_range_m;
  return Log(density);
}

}  // namespace rc_cuda
