#include "backends/calibration/collision_calibration.h"

#include <functional>

#include <fmt/format.h>

#include "backends/calibration/pricing_helpers.h"
#include "backends/calibration/sact_datapath_variants.h"
#include "backends/calibration/why_sentences.h"
#include "backends/energy_model.h"
#include "backends/simt_backend.h"

namespace rc {
namespace {

constexpr double kNoPaperNumber = std::numeric_limits<double>::quiet_NaN();

// One batch to price: a SACT record and the same OBBs as spheres.
struct SactInput {
  const KernelRecord* sact = nullptr;
  const KernelRecord* spheres = nullptr;
  std::uint64_t sphere_false_collisions = 0;
};

// Everything one preset's pricing of a list of batches measured.
struct SactColumn {
  SideEvidence simt{"the CUDA cores"}, tta{"TTA+"}, tta_p{"TTA+-p"}, tta_cr{"TTA+-cr"}, robo{"RoboCore"};
  SideEvidence half{"RoboCore"}, twice{"RoboCore"}, parallel{"RoboCore"}, doubled{"RoboCore"};
  SideEvidence spheres{"RoboCore (spheres)"};
  double queries = 0, nodes = 0, overlaps = 0, exit_axis_sum = 0, separated = 0;
  double with_exit = 0, without_exit = 0, parallel_cycles = 0,
         doubled_cycles = 0;  // computation cycles, summed over queries
  double sphere_nodes = 0, sphere_queries = 0, false_collisions = 0;
  std::string simt_kernel;  // what the SIMT model priced
  int predicated_op_cycles = 1;
  double robo_memory_joules = 0, simt_memory_joules = 0;
};

// Sums another batch's column into this one.
void Merge(SactColumn& c, const SactColumn& more) {
  for (auto [to, from] : {std::pair{&c.simt, &more.simt},
                          {&c.tta, &more.tta},
                          {&c.tta_p, &more.tta_p},
                          {&c.tta_cr, &more.tta_cr},
                          {&c.robo, &more.robo},
                          {&c.half, &more.half},
                          {&c.twice, &more.twice},
                          {&c.parallel, &more.parallel},
                          {&c.doubled, &more.doubled},
                          {&c.spheres, &more.spheres}})
    to->Add(*from);
  for (auto [to, from] : {std::pair{&c.queries, more.queries},
                          {&c.nodes, more.nodes},
                          {&c.overlaps, more.overlaps},
                          {&c.exit_axis_sum, more.exit_axis_sum},
                          {&c.separated, more.separated},
                          {&c.with_exit, more.with_exit},
                          {&c.without_exit, more.without_exit},
                          {&c.parallel_cycles, more.parallel_cycles},
                          {&c.doubled_cycles, more.doubled_cycles},
                          {&c.sphere_nodes, more.sphere_nodes},
                          {&c.sphere_queries, more.sphere_queries},
                          {&c.false_collisions, more.false_collisions},
                          {&c.robo_memory_joules, more.robo_memory_joules},
                          {&c.simt_memory_joules, more.simt_memory_joules}})
    *to += from;
  if (c.simt_kernel.empty()) c.simt_kernel = more.simt_kernel;
  c.predicated_op_cycles = more.predicated_op_cycles;
}

SactColumn PriceSact(const std::vector<SactInput>& inputs, const BackendParameters& params) {
  SactColumn c;
  c.predicated_op_cycles = params.ttaplus.unit.predicated_op_cycles;
  const SimtBackend simt_model(params);
  BackendParameters half = params, twice = params;
  half.robocore.sact_latency_scale *= 0.5;
  twice.robocore.sact_latency_scale *= 2.0;
  const auto robocore = Backend::Create("robocore", params);
  const DatapathConfig datapath = params.robocore.Datapath();
  DatapathConfig no_exit = datapath;
  no_exit.exit_mode = EarlyExitMode::kNone;
  for (const SactInput& in : inputs) {
    const KernelRecord& r = *in.sact;
    const auto cost = PriceByName({"simt", "ttaplus", "ttaplus-p", "ttaplus-cr", "robocore"}, r, params);
    c.simt.Add(cost.at("simt"));
    c.tta.Add(cost.at("ttaplus"));
    c.tta_p.Add(cost.at("ttaplus-p"));
    c.tta_cr.Add(cost.at("ttaplus-cr"));
    c.robo.Add(cost.at("robocore"));
    c.robo_memory_joules += MemoryEnergyJoules(cost.at("robocore").memory, params.gpu, params.energy);
    c.simt_memory_joules += MemoryEnergyJoules(cost.at("simt").memory, params.gpu, params.energy);
    c.half.Add(Backend::Create("robocore", half)->Price(r));
    c.twice.Add(Backend::Create("robocore", twice)->Price(r));
    const double q = static_cast<double>(r.query_count());
    c.queries += q;
    c.nodes += static_cast<double>(r.total_nodes());
    for (std::uint8_t exit : r.node_exits) {
      c.overlaps += exit == kNoExit;
      if (exit != kNoExit) c.separated += 1, c.exit_axis_sum += exit;
    }
    c.with_exit += q * AverageComputationCycles(r, datapath);
    c.without_exit += q * AverageComputationCycles(r, no_exit);
    const KernelRecord parallel = VariantRecord(r, FullyParallelSact(), datapath.latencies);
    const KernelRecord doubled = VariantRecord(r, SactUnitCopies(2), datapath.latencies);
    c.parallel.Add(robocore->Price(parallel));
    c.doubled.Add(robocore->Price(doubled));
    c.parallel_cycles += q * AverageComputationCycles(parallel, datapath);
    c.doubled_cycles += q * AverageComputationCycles(doubled, datapath);
    c.spheres.Add(robocore->Price(*in.spheres));
    c.sphere_nodes += static_cast<double>(in.spheres->total_nodes());
    c.sphere_queries += static_cast<double>(in.spheres->query_count());
    c.false_collisions += static_cast<double>(in.sphere_false_collisions);
    const SimtInstructionMix mix = simt_model.InstructionMix(r);
    c.simt_kernel = mix.source;
  }
  return c;
}

std::string Tags(std::initializer_list<const SideEvidence*> sides) {
  std::string text;
  for (const SideEvidence* s : sides) text += (text.empty() ? "" : "; ") + LimitTag(*s);
  return text;
}

// The rows, as functions of one column, so that both columns come from the
// same code.
struct RowSpec {
  std::string result, workload, paper;
  double paper_value;
  CalibrationUnit unit;
  std::function<ColumnValue(const SactColumn&)> measure;
};

std::vector<RowSpec> Specs(const std::string& suffix, const std::string& workload) {
  std::vector<RowSpec> specs;
  specs.push_back({"SACT collision queries, RoboCore vs CUDA" + suffix, workload, "13.3x faster", 13.3,
                   CalibrationUnit::kSpeedup, [](const SactColumn& c) {
                     return ColumnValue{Speedup(c.simt.kernel_seconds(), c.robo.kernel_seconds()),
                                        "The CUDA cores run " + c.simt_kernel + ". " + CompareSides(c.robo, c.simt),
                                        Tags({&c.robo, &c.simt})};
                   }});
  specs.push_back(
      {"SACT collision queries, RoboCore vs CUDA, incl. launch" + suffix, workload, "13.3x faster", 13.3,
       CalibrationUnit::kSpeedup, [](const SactColumn& c) {
         const double share = c.robo.launch_share();
         const double launch = double(c.robo.total().launch_cycles) / double(c.robo.launches());
         return ColumnValue{
             Speedup(c.simt.seconds(), c.robo.seconds()),
             share >= kLaunchShareWorthNaming
                 ? fmt::format("The {:.0f}-cycle launch (kernel launch + program and decode configuration) is {:.0f}% "
                               "of RoboCore's time for this batch, so the ratio moves toward 1.",
                               launch, 100.0 * share)
                 : fmt::format("The {:.0f}-cycle launch is {:.1f}% of RoboCore's time for this batch, so including "
                               "it changes the ratio little.",
                               launch, 100.0 * share),
             Tags({&c.robo})};
       }});
  specs.push_back({"SACT, TTA+ with conditional return vs TTA+" + suffix, workload, "1.40x faster", 1.40,
                   CalibrationUnit::kSpeedup, [](const SactColumn& c) {
                     return ColumnValue{
                         Speedup(c.tta.kernel_seconds(), c.tta_cr.kernel_seconds()),
                         fmt::format("Conditional return cuts executed micro-ops from {:.3g} to {:.3g} ({:+.0f}%). ",
                                     c.tta.micro_ops(), c.tta_cr.micro_ops(),
                                     PercentChange(c.tta.micro_ops(), c.tta_cr.micro_ops())) +
                             CompareSides(c.tta_cr, c.tta),
                         Tags({&c.tta_cr, &c.tta})};
                   }});
  specs.push_back({"SACT, RoboCore vs TTA+ with conditional return" + suffix, workload, "1.22x faster", 1.22,
                   CalibrationUnit::kSpeedup, [](const SactColumn& c) {
                     return ColumnValue{
                         Speedup(c.tta_cr.kernel_seconds(), c.robo.kernel_seconds()),
                         fmt::format("The chained SACT units replace each axis's TTA+ expansion ({:.3g} micro-ops, "
                                     "{:.3g} hops) by one native micro-op with CTRL-folded exits ({:.3g} micro-ops, "
                                     "{:.3g} hops). ",
                                     c.tta_cr.micro_ops(), double(c.tta_cr.total().interconnect_hops),
                                     c.robo.micro_ops(), double(c.robo.total().interconnect_hops)) +
                             CompareSides(c.robo, c.tta_cr),
                         Tags({&c.robo, &c.tta_cr})};
                   }});
  specs.push_back({"SACT, TTA+ with predication vs TTA+" + suffix, workload, "almost no change (~1x)", 1.0,
                   CalibrationUnit::kSpeedup, [](const SactColumn& c) {
                     return ColumnValue{
                         Speedup(c.tta.kernel_seconds(), c.tta_p.kernel_seconds()),
                         fmt::format("Predicated-off micro-ops ({:.3g}) take {} cycle(s) in their unit instead of "
                                     "their latency (artifact rt_op_unit::cycle). ",
                                     double(c.tta_p.total().predicated_off_micro_ops), c.predicated_op_cycles) +
                             CompareSides(c.tta_p, c.tta),
                         Tags({&c.tta_p, &c.tta})};
                   }});
  specs.push_back(
      {"SACT collision queries, energy RoboCore vs CUDA" + suffix, workload, "87% less", -87.0,
       CalibrationUnit::kPercentChange, [](const SactColumn& c) {
         const double robo_memory = c.robo_memory_joules / c.robo.total().energy_joules;
         const double simt_memory = c.simt_memory_joules / c.simt.total().energy_joules;
         return ColumnValue{
             PercentChange(c.simt.total().energy_joules, c.robo.total().energy_joules),
             fmt::format("Both fetch the same nodes ({:.3g} sectors); memory is {:.0f}% of RoboCore's energy and "
                         "{:.0f}% of the CUDA cores', whose rest is instruction fetch and register accesses per "
                         "instruction, RoboCore's packet-buffer accesses per micro-op; {} (Horowitz 45 nm; "
                         "leakage not modelled).",
                         double(c.robo.total().memory.sector_requests), 100.0 * robo_memory, 100.0 * simt_memory,
                         robo_memory >= 0.5 ? "RoboCore's energy is mostly memory traffic, which no datapath saves"
                                            : "RoboCore's energy is mostly its micro-ops' buffer accesses"),
             ""};
       }});
  specs.push_back(
      {"SACT early exit, average computation latency per query (RoboCore)" + suffix, workload, "-65%", -65.0,
       CalibrationUnit::kPercentChange, [](const SactColumn& c) {
         const double overlap = c.overlaps / c.nodes;
         std::string mechanism =
             overlap >= 0.5 ? fmt::format(
                                  "{:.0f}% of our node tests overlap, and an overlapping test runs every axis (a query "
                                  "descends only through boxes it overlaps and stops at its first colliding leaf)",
                                  100.0 * overlap)
                            : fmt::format(
                                  "{:.0f}% of our node tests separate, at axis {:.1f} of 15 on average, and {:.0f}% "
                                  "overlap and run every axis",
                                  100.0 * (1.0 - overlap), c.separated ? 1.0 + c.exit_axis_sum / c.separated : 0.0,
                                  100.0 * overlap);
         return ColumnValue{PercentChange(c.without_exit, c.with_exit),
                            fmt::format("{:.0f} vs {:.0f} computation cycles per query: ", c.with_exit / c.queries,
                                        c.without_exit / c.queries) +
                                mechanism + ".",
                            ""};
       }});
  for (double factor : {0.5, 2.0}) {
    specs.push_back({fmt::format("SACT unit latency x{:g}, RoboCore total time", factor) + suffix, workload,
                     "small change", kNoPaperNumber, CalibrationUnit::kPercentChange, [factor](const SactColumn& c) {
                       const SideEvidence& scaled = factor < 1 ? c.half : c.twice;
                       return ColumnValue{PercentChange(c.robo.kernel_seconds(), scaled.kernel_seconds()),
                                          "With the SACT latencies scaled, " + BoundClause(scaled) + ".",
                                          Tags({&scaled})};
                     }});
  }
  specs.push_back({"Fully parallel SACT (6 box + 9 edge units), RoboCore total time" + suffix, workload,
                   "-41% latency (3.7x area)", -41.0, CalibrationUnit::kPercentChange, [](const SactColumn& c) {
                     return ColumnValue{
                         PercentChange(c.robo.kernel_seconds(), c.parallel.kernel_seconds()),
                         fmt::format("Our smallest model (sact_datapath_variants.h): all 15 axes in one round "
                                     "after PRE, so a query computes for {:.0f} cycles instead of {:.0f}; ",
                                     c.parallel_cycles / c.queries, c.with_exit / c.queries) +
                             BoundClause(c.parallel) + ".",
                         Tags({&c.parallel})};
                   }});
  specs.push_back({"Two of each SACT unit, RoboCore" + suffix, workload, "1.2x faster (1.8x area)", 1.2,
                   CalibrationUnit::kSpeedup, [](const SactColumn& c) {
                     return ColumnValue{
                         Speedup(c.robo.kernel_seconds(), c.doubled.kernel_seconds()),
                         fmt::format("Modelled as two axes of a stage per round (sact_datapath_variants.h): {:.0f} "
                                     "instead of {:.0f} computation cycles per query; ",
                                     c.doubled_cycles / c.queries, c.with_exit / c.queries) +
                             BoundClause(c.doubled) + ".",
                         Tags({&c.doubled})};
                   }});
  specs.push_back(
      {"Sphere robot on RoboCore vs OBB SACT on CUDA" + suffix, workload, "21x faster; 10% false collisions", 21.0,
       CalibrationUnit::kSpeedup, [](const SactColumn& c) {
         return ColumnValue{
             Speedup(c.simt.kernel_seconds(), c.spheres.kernel_seconds()),
             fmt::format("One bounding sphere per OBB, 9 micro-ops per node on the generic OP units ({:.2f} nodes "
                         "per sphere against {:.2f} per OBB); the spheres report {:.0f} false collisions in {:.0f} "
                         "queries ({:.1f}%), measured against the SACT's answers. ",
                         c.sphere_nodes / c.sphere_queries, c.nodes / c.queries, c.false_collisions, c.queries,
                         100.0 * c.false_collisions / c.queries) +
                 CompareSides(c.spheres, c.simt),
             Tags({&c.spheres, &c.simt})};
       }});
  return specs;
}

void AddRows(std::vector<CalibrationRow>& rows, const std::vector<RowSpec>& specs, CalibrationScale scale,
             const SactColumn& artifact, const SactColumn& ours) {
  for (const RowSpec& spec : specs) {
    CalibrationRow row;
    row.result = spec.result;
    row.scale = scale;
    row.workload = spec.workload;
    row.paper = spec.paper;
    row.paper_value = spec.paper_value;
    row.unit = spec.unit;
    SetColumns(row, spec.measure(artifact), spec.measure(ours));
    rows.push_back(std::move(row));
  }
}

}  // namespace

std::vector<CalibrationRow> CollisionRows(const CalibrationWorkloads& w, const BackendPreset& artifact,
                                          const BackendPreset& ours) {
  std::vector<CalibrationRow> rows;
  if (!w.scenes.empty()) {
    SactColumn all_artifact, all_ours;
    std::uint32_t fewest = ~0u, most = 0;
    for (const SactSceneWorkload& s : w.scenes) {
      const SactInput in{&s.sact, &s.spheres, s.sphere_false_collisions};
      fewest = std::min(fewest, s.octree_nodes);
      most = std::max(most, s.octree_nodes);
      // The headline ratio per scene; every row over all scenes.
      const SactColumn o = PriceSact({in}, ours.backend);
      const SactColumn a = &artifact == &ours ? o : PriceSact({in}, artifact.backend);
      std::vector<RowSpec> headline = Specs(std::string(" (") + ToString(s.kind) + ")", s.Size());
      headline.resize(1);
      AddRows(rows, headline, CalibrationScale::kPaperScale, a, o);
      Merge(all_artifact, a);
      Merge(all_ours, o);
    }
    const std::string workload =
        fmt::format("{} scenes, {:.0f} queries x {:.1f} nodes; {}-{}-node octrees", w.scenes.size(), all_ours.queries,
                    all_ours.nodes / all_ours.queries, fewest, most);
    AddRows(rows, Specs(" (all scenes)", workload), CalibrationScale::kPaperScale, all_artifact, all_ours);
  }
  const SactInput small{&w.sact, &w.spheres, w.sphere_false_collisions};
  const std::string workload =
      fmt::format("{} queries x {:.1f} nodes; {:.0f}-node binary tree", w.sact.query_count(),
                  double(w.sact.total_nodes()) / double(w.sact.query_count()), double(w.sact.regions.front().elements));
  const SactColumn small_ours = PriceSact({small}, ours.backend);
  AddRows(rows, Specs("", workload), CalibrationScale::kSmallBatch,
          &artifact == &ours ? small_ours : PriceSact({small}, artifact.backend), small_ours);
  return rows;
}

}  // namespace rc
