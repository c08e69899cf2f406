// gpu_ray_cast_export: the host half of the GPU check (docs/gpu_check.md).
//
// Builds the ray-cast benchmark's queries (benchmarks/ray_cast_benchmark.cc:
// free-cell starts, random headings, 10 m, seed 1; Wean from ../shared/data,
// else the generated office map), casts them on the host with each method,
// and writes
//   <out>/queries.bin  the map, the rays and the host's answers
//                      (ray_cast_query_file.h), which ray_cast_on_gpu.cu
//                      runs on a real GPU;
//   <out>/leaf.bin     a measured range per ray and the host's beam-model
//                      log density of each (beam_leaf_file.h), for the
//                      kernels with their beam leaf;
//   <out>/model.csv    what the SIMT (CUDA-core) model predicts for the same
//                      launches: each method x (traversal alone in random
//                      and in grid order; with the max-log and with the
//                      exact beam leaf in random order) x precision (fp64,
//                      fp32) x instruction set (ptx, sass) x preset.
//
// Presets: "default" (the model's GPU, backend_params.h) and each
// --preset FILE (backends/presets/h100.json: an H100 SXM5's published
// figures). Nothing here is fitted to a measurement.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backends/backend.h"
#include "backends/backend_preset.h"
#include "backends/calibration/pricing_helpers.h"
#include "benchmarks/gpu/beam_leaf_file.h"
#include "benchmarks/gpu/ray_cast_query_file.h"
#include "benchmarks/gpu/simt_model_columns.h"
#include "benchmarks/ray_cast_queries.h"
#include "common/exit_codes.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/ray_cast.h"
#include "workloads/delibot/beam_sensor_model.h"

namespace rc {
namespace {

constexpr RayCastMethod kMethods[gpu_check::kMethodCount] = {RayCastMethod::kMarch, RayCastMethod::kDda,
                                                             RayCastMethod::kRayMarching};

struct PresetColumn {
  std::string name;
  BackendParameters params;
};

int Run(int argc, char** argv) {
  CLI::App app{"gpu_ray_cast_export: the ray batch, host answers and SIMT-model predictions for the GPU check"};
  std::string out_dir;
  std::size_t queries = std::size_t{1} << 19;
  std::vector<std::string> preset_files;
  std::string shared_data = RC_SHARED_DATA_DIR;
  app.add_option("--out", out_dir, "folder for queries.bin, leaf.bin and model.csv")->required();
  app.add_option("--queries", queries, "rays in the batch")->check(CLI::Range(std::size_t{1}, std::size_t{1} << 24));
  app.add_option("--preset", preset_files, "backend preset file to price under, beside the default")
      ->check(CLI::ExistingFile);
  app.add_option("--shared-data", shared_data, "the shared data folder (Wean map)");
  CLI11_PARSE(app, argc, argv);

  OccupancyGrid grid;
  std::string map_name;
  const std::string wean = shared_data + "/wean/wean.dat";
  if (std::filesystem::exists(wean)) {
    grid = LoadCmuMap(wean);
    map_name = "wean";
  } else {
    grid = GenerateOfficeMap(OfficeMapOptions{});
    map_name = "office";
    std::cerr << "gpu_ray_cast_export: " << wean << " is absent; using the generated office map\n";
  }
  const RayCastQueries q = MakeRayCastQueries(grid, queries);
  RayBatch random_batch, grid_batch;
  random_batch.max_range_m = grid_batch.max_range_m = 10.0;
  random_batch.queries = q.random_order;
  for (std::uint32_t i : q.grid_order) grid_batch.queries.push_back(q.random_order[i]);

  std::vector<PresetColumn> presets = {{"default", DefaultPreset().backend}};
  for (const std::string& file : preset_files)
    presets.push_back({std::filesystem::path(file).stem().string(), LoadBackendPreset(file).backend});

  gpu_check::RayCastQueryFile file;
  file.size_x = grid.size_x();
  file.size_y = grid.size_y();
  file.resolution_m = grid.resolution_m();
  file.max_range_m = random_batch.max_range_m;
  file.cells.resize(grid.cell_count());
  std::transform(grid.cells().begin(), grid.cells().end(), file.cells.begin(),
                 [](CellState c) { return static_cast<std::uint8_t>(c); });
  for (const RayQuery& r : q.random_order) {
    file.origin_x.push_back(r.origin_x_m);
    file.origin_y.push_back(r.origin_y_m);
    file.dir_x.push_back(std::cos(r.angle_rad));  // as CastRay computes it
    file.dir_y.push_back(std::sin(r.angle_rad));
  }
  file.grid_order = q.grid_order;

  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/model.csv");
  csv << "map,preset,method,order,leaf,precision,isa," << gpu_check::kSimtCostColumns << '\n';
  // The launches the GPU runs: the traversal alone in random and grid order,
  // and with the beam leaf (random order) in its two forms.
  struct Launch {
    bool grid_ordered;
    LeafProgramKind leaf;
  };
  const Launch launches[] = {
      {false, LeafProgramKind::kNone}, {true, LeafProgramKind::kNone}, {false, LeafProgramKind::kBeamModel}};
  for (int m = 0; m < gpu_check::kMethodCount; ++m) {
    const RayCastScene scene(grid, kMethods[m]);
    if (kMethods[m] == RayCastMethod::kRayMarching) file.distance_m = scene.distance_field()->values();
    for (const Launch& launch : launches) {
      const RayBatch& batch = launch.grid_ordered ? grid_batch : random_batch;
      RecordOptions options;
      options.leaf = launch.leaf;
      std::vector<RayHit> hits;
      KernelRecord record;
      CastRayBatchRecorded(scene, batch, hits, record, options);
      if (!launch.grid_ordered && launch.leaf == LeafProgramKind::kNone) {
        for (const RayHit& h : hits) {
          file.host[m].range_m.push_back(h.range_m);
          file.host[m].nodes.push_back(h.nodes);
        }
      }
      const std::vector<SimtBeamLeaf> leaves =
          launch.leaf == LeafProgramKind::kNone
              ? std::vector<SimtBeamLeaf>{SimtBeamLeaf::kMaxLog}
              : std::vector<SimtBeamLeaf>{SimtBeamLeaf::kMaxLog, SimtBeamLeaf::kExact};
      for (const PresetColumn& preset : presets) {
        for (const SimtBeamLeaf beam_leaf : leaves) {
          for (const auto& [precision, isa] : gpu_check::kSimtVariants) {
            BackendParameters params = preset.params;
            params.simt.precision = precision;
            params.simt.isa = isa;
            params.simt.beam_leaf = beam_leaf;  // read only for a record with a leaf
            const char* leaf_name = launch.leaf == LeafProgramKind::kNone
                                        ? "none"
                                        : (beam_leaf == SimtBeamLeaf::kMaxLog ? "maxlog" : "exact");
            csv << map_name << ',' << preset.name << ',' << gpu_check::kMethodNames[m] << ','
                << (launch.grid_ordered ? "grid" : "random") << ',' << leaf_name << ','
                << gpu_check::PrecisionName(precision) << ',' << gpu_check::IsaName(isa) << ',';
            gpu_check::WriteSimtCost(csv, PriceByName({"simt"}, record, params).at("simt"));
            csv << '\n';
          }
        }
      }
    }
  }

  // The beam leaf's inputs: a measured range per ray, the host's dda range
  // plus Gaussian noise (0.1 m), clipped to [0, max range]; the beam model's
  // default parameters at the batch's max range; the host's exact log
  // density of each ray for each method (the leaf scores the float range).
  gpu_check::BeamLeafFile leaf;
  BeamModelParams beam;
  beam.max_range_m = random_batch.max_range_m;
  leaf.z_hit = beam.z_hit;
  leaf.z_short = beam.z_short;
  leaf.z_max = beam.z_max;
  leaf.z_rand = beam.z_rand;
  leaf.sigma_hit_m = beam.sigma_hit_m;
  leaf.lambda_short_per_m = beam.lambda_short_per_m;
  leaf.max_range_m = beam.max_range_m;
  RandomStream noise(2, StreamPurpose::kTest, 0, 0);
  for (float range_m : file.host[1].range_m)  // dda
    leaf.measured_m.push_back(std::clamp(range_m + 0.1 * noise.Gaussian(), 0.0, beam.max_range_m));
  for (int m = 0; m < gpu_check::kMethodCount; ++m)
    for (std::size_t i = 0; i < leaf.queries(); ++i)
      leaf.host_log_density[m].push_back(
          BeamLogDensity(beam, leaf.measured_m[i], static_cast<double>(file.host[m].range_m[i])));

  std::string error;
  if (!gpu_check::WriteQueryFile(file, out_dir + "/queries.bin", &error) ||
      !gpu_check::WriteBeamLeafFile(leaf, out_dir + "/leaf.bin", &error)) {
    std::cerr << "gpu_ray_cast_export: " << error << '\n';
    return 1;
  }
  csv.close();
  if (!csv) {
    std::cerr << "gpu_ray_cast_export: " << out_dir << "/model.csv: write failed\n";
    return 1;
  }
  std::cout << "wrote " << out_dir << "/queries.bin (" << map_name << ", " << file.queries() << " rays), " << out_dir
            << "/leaf.bin and " << out_dir << "/model.csv\n";
  return 0;
}

}  // namespace
}  // namespace rc

int main(int argc, char** argv) {
  try {
    return rc::Run(argc, argv);
  } catch (...) {  // a bad preset or map file: its name and field, exit 1 (common/exit_codes.h)
    return rc::ToInt(rc::ReportException(std::current_exception(), std::cerr, "gpu_ray_cast_export"));
  }
}
