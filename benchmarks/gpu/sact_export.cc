// gpu_sact_export: the host half of the GPU check's collision part
// (docs/gpu_check.md).
//
// Builds the calibration's paper-scale SACT scenes (calibration_workloads.h:
// the four MPiNet-like OctoMap scenes, the mpnet_master arm's link OBBs
// jittered across each, at least 10,000 queries, double precision,
// depth-first, no sphere pre-tests), runs the collision kernel on the host,
// and writes
//   <out>/sact_<scene>.bin  the box tree, the OBBs and the host's outcomes
//                           (sact_query_file.h), which sact_on_gpu.cu runs
//                           on a real GPU;
//   <out>/sact_model.csv    what the SIMT (CUDA-core) model predicts for each
//                           scene x batch (the calibration's, and the same
//                           OBBs repeated kLargeRepeat times, enough to fill
//                           a large GPU) x precision x instruction set x
//                           preset.
// The priced record is the calibration's (the SACT rows of
// docs/calibration.md price the same batches).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "backends/backend.h"
#include "backends/backend_preset.h"
#include "backends/calibration/calibration_workloads.h"
#include "backends/calibration/pricing_helpers.h"
#include "benchmarks/gpu/sact_query_file.h"
#include "benchmarks/gpu/simt_model_columns.h"
#include "common/exit_codes.h"
#include "robocore/collision/flat_box_tree.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/tree_collision.h"

namespace rc {
namespace {

// The calibration's batch (about 10,000 OBBs, 313 warps) leaves most of a
// 132-SM GPU idle; the same OBBs repeated this many times fill it.
constexpr int kLargeRepeat = 16;

std::string FileNameOf(const std::string& scene) {
  std::string name = scene;
  for (char& c : name)
    if (c == ' ') c = '_';
  return name;
}

gpu_check::SactQueryFile QueryFileOf(const std::string& scene, const FlatBoxTree<double>& tree,
                                     const std::vector<Obbd>& obbs, const CollisionBatch& batch, double epsilon) {
  gpu_check::SactQueryFile f;
  f.scene = scene;
  f.parallel_epsilon = epsilon;
  for (const FlatNode<double>& node : tree.nodes()) {
    f.node_centre.insert(f.node_centre.end(), node.centre, node.centre + 3);
    f.node_half.insert(f.node_half.end(), node.half, node.half + 3);
    f.first_child.push_back(node.first_child);
    f.child_count.push_back(node.child_count);
    f.depth.push_back(node.depth);
  }
  for (const Obbd& b : obbs) {
    f.obb_centre.insert(f.obb_centre.end(), b.centre.data(), b.centre.data() + 3);
    f.obb_axes.insert(f.obb_axes.end(), b.axes.data(), b.axes.data() + 9);  // column-major
    f.obb_half.insert(f.obb_half.end(), b.half.data(), b.half.data() + 3);
  }
  for (const TraversalOutcome& o : batch.outcomes) {
    f.collides.push_back(o.collides ? 1 : 0);
    f.colliding_box.push_back(o.colliding_box);
    f.nodes_visited.push_back(o.nodes_visited);
  }
  return f;
}

int Run(int argc, char** argv) {
  CLI::App app{"gpu_sact_export: the SACT scenes, host outcomes and SIMT-model predictions for the GPU check"};
  std::string out_dir;
  std::vector<std::string> preset_files;
  CalibrationOptions options;
  options.data_dir = RC_SHARED_DATA_DIR;
  app.add_option("--out", out_dir, "folder for sact_<scene>.bin and sact_model.csv")->required();
  app.add_option("--preset", preset_files, "backend preset file to price under, beside the default")
      ->check(CLI::ExistingFile);
  app.add_option("--shared-data", options.data_dir, "the shared data folder (the mpnet_master arm)");
  CLI11_PARSE(app, argc, argv);

  std::vector<std::pair<std::string, BackendParameters>> presets = {{"default", DefaultPreset().backend}};
  for (const std::string& file : preset_files)
    presets.emplace_back(std::filesystem::path(file).stem().string(), LoadBackendPreset(file).backend);

  const ArmLinkPoses arm = MakeArmLinkPoses(options);
  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/sact_model.csv");
  csv << "scene,repeat,preset,precision,isa,collisions," << gpu_check::kSimtCostColumns << '\n';
  for (const MpinetSceneKind kind : kMpinetSceneKinds) {
    const std::string scene = ToString(kind);
    const SactSceneInputs inputs = MakeSactSceneInputs(kind, arm.poses, options);
    const FlatBoxTree<double> tree(inputs.octree.tree);
    const CollisionOptions<double> collision_options;
    const CollisionBatch batch = CollideBatch(tree, inputs.queries, collision_options);
    for (const int repeat : {1, kLargeRepeat}) {
      std::vector<Obbd> queries;
      for (int r = 0; r < repeat; ++r) queries.insert(queries.end(), inputs.queries.begin(), inputs.queries.end());
      const CollisionBatch repeated = repeat == 1 ? batch : CollideBatch(tree, queries, collision_options);
      const KernelRecord record = SactKernelRecord(repeated);
      std::uint64_t collisions = 0;
      for (const TraversalOutcome& o : repeated.outcomes) collisions += o.collides ? 1 : 0;
      for (const auto& [preset, base] : presets) {
        for (const auto& [precision, isa] : gpu_check::kSimtVariants) {
          BackendParameters params = base;
          params.simt.precision = precision;
          params.simt.isa = isa;
          csv << scene << ',' << repeat << ',' << preset << ',' << gpu_check::PrecisionName(precision) << ','
              << gpu_check::IsaName(isa) << ',' << collisions << ',';
          gpu_check::WriteSimtCost(csv, PriceByName({"simt"}, record, params).at("simt"));
          csv << '\n';
        }
      }
    }
    const std::string path = out_dir + "/sact_" + FileNameOf(scene) + ".bin";
    std::string error;
    if (!gpu_check::WriteSactFile(
            QueryFileOf(scene, tree, inputs.queries, batch, collision_options.sact.parallel_epsilon), path, &error)) {
      std::cerr << "gpu_sact_export: " << error << '\n';
      return 1;
    }
    std::cout << "wrote " << path << " (" << batch.query_count() << " OBBs, " << tree.nodes().size() << " nodes)\n";
  }
  csv.close();
  if (!csv) {
    std::cerr << "gpu_sact_export: " << out_dir << "/sact_model.csv: write failed\n";
    return 1;
  }
  std::cout << "arm: " << arm.source << "\nwrote " << out_dir << "/sact_model.csv\n";
  return 0;
}

}  // namespace
}  // namespace rc

int main(int argc, char** argv) {
  try {
    return rc::Run(argc, argv);
  } catch (...) {  // a bad preset or arm file: its name and field, exit 1 (common/exit_codes.h)
    return rc::ToInt(rc::ReportException(std::current_exception(), std::cerr, "gpu_sact_export"));
  }
}
