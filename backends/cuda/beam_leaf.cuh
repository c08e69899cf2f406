#pragma once
// The beam-model leaf on the CUDA cores: BeamLogDensity of
// workloads/delibot/beam_sensor_model.cc, statement for statement (the
// exact log of the four-part mixture, with exp and log), once per ray after
// the traversal. programs/beam_leaf.asm describes the same step for the RT
// units with a max-log approximation, because their ISA has no EXP or LOG;
// the CUDA cores compute what the host computes.
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
};

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
    if (normalizer > T(0))
      density += p.z_short * p.lambda_short_per_m * Exp(-p.lambda_short_per_m * z) / normalizer;
  }
  density += p.z_rand / p.max_range_m;
  return Log(density);
}

}  // namespace rc_cuda
