#pragma once
// The query file of the GPU check (docs/gpu_check.md): one ray batch,
// the map it is cast in, and the host's answers, written on the host by
// gpu_ray_cast_export and read on the GPU machine by ray_cast_on_gpu.cu.
// Plain C++17 and the standard library only, so that nvcc compiles it with
// no other dependency.
//
// Layout, little-endian, no padding, in this order:
//   char[8]   magic "RCRAYQ1"
//   int32     size_x, size_y          cells
//   float64   resolution_m, max_range_m
//   uint64    queries (n)
//   uint8     cells[size_x * size_y]  OccupancyGrid, 0 = free, ix * size_y + iy
//   float32   distance_m[size_x * size_y]  the ray-marching distance field
//   float64   origin_x[n], origin_y[n], dir_x[n], dir_y[n]
//             (m; unit direction = std::cos / std::sin of the heading, as
//             the host's CastRay computes it)
//   uint32    grid_order[n]           query index at each grid-order position
//   per method, march, dda, rm:
//     float32 range_m[n]; uint32 nodes[n]   the host's RayHit, query order
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "benchmarks/gpu/binary_io.h"

namespace rc::gpu_check {

inline constexpr char kQueryFileMagic[8] = "RCRAYQ1";
inline constexpr int kMethodCount = 3;
inline constexpr const char* kMethodNames[kMethodCount] = {"march", "dda", "rm"};

struct HostAnswers {
  std::vector<float> range_m;
  std::vector<std::uint32_t> nodes;
};

struct RayCastQueryFile {
  std::int32_t size_x = 0, size_y = 0;
  double resolution_m = 0, max_range_m = 0;
  std::vector<std::uint8_t> cells;
  std::vector<float> distance_m;
  std::vector<double> origin_x, origin_y, dir_x, dir_y;
  std::vector<std::uint32_t> grid_order;
  std::array<HostAnswers, kMethodCount> host;  // march, dda, rm

  std::size_t queries() const { return origin_x.size(); }
};

// Every array must hold its declared count (cells and distance_m
// size_x * size_y, the rest queries()); returns false with the reason if not,
// or if the file cannot be written.
inline bool WriteQueryFile(const RayCastQueryFile& f, const std::string& path, std::string* error) {
  using namespace binary_io;
  const std::size_t cells = static_cast<std::size_t>(f.size_x) * static_cast<std::size_t>(f.size_y);
  const std::size_t n = f.queries();
  bool sizes_agree = f.cells.size() == cells && f.distance_m.size() == cells && f.origin_y.size() == n &&
                     f.dir_x.size() == n && f.dir_y.size() == n && f.grid_order.size() == n;
  for (const HostAnswers& a : f.host) sizes_agree = sizes_agree && a.range_m.size() == n && a.nodes.size() == n;
  if (!sizes_agree) return Fail(error, path, "array sizes disagree with size_x * size_y and the query count");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Fail(error, path, "cannot open for writing");
  out.write(kQueryFileMagic, sizeof(kQueryFileMagic));
  Put(out, f.size_x);
  Put(out, f.size_y);
  Put(out, f.resolution_m);
  Put(out, f.max_range_m);
  Put(out, static_cast<std::uint64_t>(n));
  PutArray(out, f.cells);
  PutArray(out, f.distance_m);
  for (const auto* v : {&f.origin_x, &f.origin_y, &f.dir_x, &f.dir_y}) PutArray(out, *v);
  PutArray(out, f.grid_order);
  for (const HostAnswers& a : f.host) {
    PutArray(out, a.range_m);
    PutArray(out, a.nodes);
  }
  out.close();
  if (!out) return Fail(error, path, "write failed");
  return true;
}

// Reads a file WriteQueryFile wrote. Refuses, naming the field, a wrong
// magic, an impossible size, a truncated array, a grid_order entry out of
// range, or bytes after the last array.
inline bool ReadQueryFile(const std::string& path, RayCastQueryFile* f, std::string* error) {
  using namespace binary_io;
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, path, "cannot open");
  char magic[8] = {};
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kQueryFileMagic, sizeof(magic)) != 0)
    return Fail(error, path, "magic: not an RCRAYQ1 query file");
  std::uint64_t n = 0;
  if (!Get(in, &f->size_x) || !Get(in, &f->size_y) || !Get(in, &f->resolution_m) || !Get(in, &f->max_range_m) ||
      !Get(in, &n))
    return Fail(error, path, "header: truncated");
  if (f->size_x <= 0 || f->size_y <= 0 || std::int64_t{f->size_x} * f->size_y > (std::int64_t{1} << 28))
    return Fail(error, path, "size_x, size_y: must be positive, at most 2^28 cells in all");
  if (!(f->resolution_m > 0) || !(f->max_range_m > 0))
    return Fail(error, path, "resolution_m, max_range_m: must be > 0");
  if (n == 0 || n > (std::uint64_t{1} << 26)) return Fail(error, path, "queries: must be 1 to 2^26");
  const std::size_t cells = static_cast<std::size_t>(f->size_x) * static_cast<std::size_t>(f->size_y);
  if (!GetArray(in, cells, &f->cells)) return Fail(error, path, "cells: truncated");
  if (!GetArray(in, cells, &f->distance_m)) return Fail(error, path, "distance_m: truncated");
  const char* ray_fields[] = {"origin_x", "origin_y", "dir_x", "dir_y"};
  std::vector<double>* rays[] = {&f->origin_x, &f->origin_y, &f->dir_x, &f->dir_y};
  for (int i = 0; i < 4; ++i)
    if (!GetArray(in, n, rays[i])) return Fail(error, path, std::string(ray_fields[i]) + ": truncated");
  if (!GetArray(in, n, &f->grid_order)) return Fail(error, path, "grid_order: truncated");
  for (std::uint32_t q : f->grid_order)
    if (q >= n) return Fail(error, path, "grid_order: index out of range");
  for (int m = 0; m < kMethodCount; ++m) {
    if (!GetArray(in, n, &f->host[m].range_m) || !GetArray(in, n, &f->host[m].nodes))
      return Fail(error, path, std::string(kMethodNames[m]) + " answers: truncated");
  }
  if (in.peek() != std::ifstream::traits_type::eof()) return Fail(error, path, "bytes after the last array");
  return true;
}

}  // namespace rc::gpu_check
