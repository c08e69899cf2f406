#pragma once
// The beam-leaf file of the GPU check (docs/gpu_check.md): a measured range
// for each ray of queries.bin, the beam model's parameters, and the host's
// exact log density of each ray for each method, written by
// gpu_ray_cast_export and read by ray_cast_on_gpu.cu, which runs the ray
// kernels with their beam leaf (backends/cuda/beam_leaf.cuh). Plain C++17.
//
// Layout, little-endian, no padding, in this order:
//   char[8]   magic "RCLEAF1"
//   uint64    queries (n), as in queries.bin
//   float64   z_hit, z_short, z_max, z_rand, sigma_hit_m, lambda_short_per_m,
//             max_range_m (BeamModelParams, workloads/delibot/beam_sensor_model.h)
//   float64   measured_m[n]
//   per method, march, dda, rm:
//     float64 host_log_density[n]   BeamLogDensity(params, measured_m, range_m)
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "benchmarks/gpu/binary_io.h"

namespace rc::gpu_check {

inline constexpr char kBeamLeafFileMagic[8] = "RCLEAF1";

struct BeamLeafFile {
  double z_hit = 0, z_short = 0, z_max = 0, z_rand = 0, sigma_hit_m = 0, lambda_short_per_m = 0, max_range_m = 0;
  std::vector<double> measured_m;
  std::array<std::vector<double>, 3> host_log_density;  // march, dda, rm

  std::size_t queries() const { return measured_m.size(); }
};

inline bool WriteBeamLeafFile(const BeamLeafFile& f, const std::string& path, std::string* error) {
  using namespace binary_io;
  for (const std::vector<double>& d : f.host_log_density)
    if (d.size() != f.queries()) return Fail(error, path, "array sizes disagree with the query count");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Fail(error, path, "cannot open for writing");
  out.write(kBeamLeafFileMagic, sizeof(kBeamLeafFileMagic));
  Put(out, static_cast<std::uint64_t>(f.queries()));
  for (double v : {f.z_hit, f.z_short, f.z_max, f.z_rand, f.sigma_hit_m, f.lambda_short_per_m, f.max_range_m})
    Put(out, v);
  PutArray(out, f.measured_m);
  for (const std::vector<double>& d : f.host_log_density) PutArray(out, d);
  out.close();
  if (!out) return Fail(error, path, "write failed");
  return true;
}

// Reads a file WriteBeamLeafFile wrote. Refuses, naming the field, a wrong
// magic, an impossible count, a parameter that is not a positive finite
// number where the model needs one, a truncated array, or trailing bytes.
inline bool ReadBeamLeafFile(const std::string& path, BeamLeafFile* f, std::string* error) {
  using namespace binary_io;
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, path, "cannot open");
  char magic[8] = {};
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kBeamLeafFileMagic, sizeof(magic)) != 0)
    return Fail(error, path, "magic: not an RCLEAF1 beam-leaf file");
  std::uint64_t n = 0;
  double* params[] = {&f->z_hit,      &f->z_short, &f->z_max, &f->z_rand, &f->sigma_hit_m, &f->lambda_short_per_m,
                      &f->max_range_m};
  bool ok = Get(in, &n);
  for (double* p : params) ok = ok && Get(in, p);
  if (!ok) return Fail(error, path, "header: truncated");
  if (n == 0 || n > (std::uint64_t{1} << 26)) return Fail(error, path, "queries: must be 1 to 2^26");
  if (!(f->sigma_hit_m > 0) || !(f->max_range_m > 0) || !(f->lambda_short_per_m > 0) || !(f->z_rand >= 0) ||
      !(f->z_hit >= 0) || !(f->z_short >= 0) || !(f->z_max >= 0))
    return Fail(error, path, "beam parameters: weights must be >= 0, sigma, lambda and max range > 0");
  if (!GetArray(in, n, &f->measured_m)) return Fail(error, path, "measured_m: truncated");
  for (std::vector<double>& d : f->host_log_density)
    if (!GetArray(in, n, &d)) return Fail(error, path, "host_log_density: truncated");
  if (in.peek() != std::ifstream::traits_type::eof()) return Fail(error, path, "bytes after the last array");
  return true;
}

}  // namespace rc::gpu_check
