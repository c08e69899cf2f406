#include "backends/calibration/delibot_calibration.h"

#include <fmt/format.h>

#include "backends/calibration/pricing_helpers.h"
#include "backends/calibration/why_sentences.h"
#include "robocore/shipped_programs.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

// What one preset's pricing of a DeliBot workload measured.
struct DelibotColumn {
  SideEvidence simt{"the CUDA cores"}, tta{"TTA+"}, robo{"RoboCore"};
  LoopMix mix;                             // the step program's loop
  std::uint32_t cell_bytes = 1;            // bytes per fetched cell
  double robo_cycles = 0, tta_cycles = 0;  // small batch: computation cycles per ray
  double queries = 0, nodes = 0;
  long updates = 0, records = 0;
};

DelibotColumn PriceFirstUpdate(const CalibrationWorkloads& w, RayCastMethod method, const BackendPreset& preset) {
  const RayCastScene scene(w.ray_grid, method);
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, w.first_update, hits, record, RecordOptionsFor(method, preset.kernel));
  const auto cost = PriceByName({"simt", "ttaplus", "robocore"}, record, preset.backend);
  DelibotColumn c;
  c.simt.Add(cost.at("simt"));
  c.tta.Add(cost.at("ttaplus"));
  c.robo.Add(cost.at("robocore"));
  c.mix = LoopMixOf(*record.program);
  c.cell_bytes = record.node_bytes;
  c.tta_cycles = AverageComputationCycles(record, preset.backend.ttaplus.Datapath(EarlyExitMode::kNone));
  c.robo_cycles = AverageComputationCycles(record, preset.backend.robocore.Datapath());
  c.queries = double(record.query_count());
  c.nodes = double(record.total_nodes());
  c.updates = c.records = 1;
  return c;
}

DelibotColumn PriceRun(const DelibotRunWorkload& run, const CalibrationOptions& o, const BackendPreset& preset) {
  DelibotSettings s;
  s.ray_caster = RayCastMethod::kMarch;
  s.mcl.particle_count = o.run_particles;
  s.mcl.beams.beam_step = o.run_beam_step;
  s.mcl.record_choices = preset.kernel;
  s.max_records = o.run_max_records;
  s.price_backends = true;
  s.backend_params = preset.backend;
  s.ledger.replay_sms = 1;  // as rcbench delibot: SM 0 replayed exactly, the rest estimated
  const DelibotResult result = RunDelibot(run.grid, run.trace, nullptr, s);
  DelibotColumn c;
  const std::vector<std::string>& names = result.pricing.backends;
  for (const DelibotRow& row : result.rows) {
    ++c.records;
    if (!row.priced || !row.pricing.priced) continue;
    ++c.updates;
    c.queries += double(row.rays);
    c.nodes += double(row.nodes);
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == "simt") c.simt.Add(row.pricing.costs[i]);
      if (names[i] == "ttaplus") c.tta.Add(row.pricing.costs[i]);
      if (names[i] == "robocore") c.robo.Add(row.pricing.costs[i]);
    }
  }
  RecordOptions options = RecordOptionsFor(RayCastMethod::kMarch, preset.kernel);
  c.mix = LoopMixOf(options.program ? *options.program : *ShippedStepProgram(StepProgramKind::kGridMarch));
  c.cell_bytes = options.layout.grid_cell_bytes;
  return c;
}

std::string ProgramClause(const DelibotColumn& c, const std::string& method) {
  return fmt::format("Our {} step runs {} micro-ops per cell ({} CMP) on {}-byte cells. ", method.c_str(),
                     c.mix.micro_ops, c.mix.compares, c.cell_bytes);
}

void AddPair(std::vector<CalibrationRow>& rows, const std::string& what, const std::string& method,
             CalibrationScale scale, const std::string& workload, const DelibotColumn& artifact,
             const DelibotColumn& ours) {
  auto vs_cuda = [&](const DelibotColumn& c) {
    return ColumnValue{Speedup(c.simt.seconds(), c.robo.seconds()),
                       ProgramClause(c, method) + CompareSides(c.robo, c.simt),
                       fmt::format("{} micro-ops per {}-byte cell; ", c.mix.micro_ops, c.cell_bytes) +
                           LimitTag(c.robo) + "; " + LimitTag(c.simt)};
  };
  auto vs_tta = [&](const DelibotColumn& c) {
    const std::string work =
        c.robo_cycles > 0
            ? fmt::format("{:.0f} computation cycles per ray against TTA+'s {:.0f}", c.robo_cycles, c.tta_cycles)
            : fmt::format("{:.3g} micro-ops executed against TTA+'s {:.3g}", c.robo.micro_ops(), c.tta.micro_ops());
    return ColumnValue{Speedup(c.tta.seconds(), c.robo.seconds()),
                       "A ray program has no SACT micro-ops, so RoboCore differs from plain TTA+ only by conditional "
                       "return, which ends just a ray's last pass while its RETURN_IFs run in every pass (" +
                           work + "). " + CompareSides(c.robo, c.tta),
                       LimitTag(c.robo) + "; " + LimitTag(c.tta)};
  };
  CalibrationRow cuda;
  cuda.result = what + ", RoboCore vs CUDA";
  cuda.scale = scale;
  cuda.workload = workload;
  cuda.paper = "1.10x faster";
  cuda.paper_value = 1.10;
  SetColumns(cuda, vs_cuda(artifact), vs_cuda(ours));
  rows.push_back(cuda);
  CalibrationRow tta;
  tta.result = what + ", RoboCore vs TTA+";
  tta.scale = scale;
  tta.workload = workload;
  tta.paper = "1.20x faster";
  tta.paper_value = 1.20;
  SetColumns(tta, vs_tta(artifact), vs_tta(ours));
  rows.push_back(tta);
}

}  // namespace

std::vector<CalibrationRow> DelibotRows(const CalibrationWorkloads& w, const BackendPreset& artifact,
                                        const BackendPreset& ours, std::vector<std::string>* notes) {
  std::vector<CalibrationRow> rows;
  for (const DelibotRunWorkload& run : w.runs) {
    const DelibotColumn o = PriceRun(run, w.options, ours);
    const DelibotColumn a = &artifact == &ours ? o : PriceRun(run, w.options, artifact);
    const std::string workload =
        fmt::format("{} updates of {:.0f} rays x {:.1f} nodes ({} records, {} particles x {} beams)", o.updates,
                    o.queries / double(o.updates), o.nodes / o.queries, o.records, w.options.run_particles,
                    (180 + w.options.run_beam_step - 1) / w.options.run_beam_step);
    AddPair(rows, "DeliBot MCL, whole run (" + run.name + ", march)", "march", CalibrationScale::kPaperScale, workload,
            a, o);
    if (notes)
      notes->push_back("DeliBot " + run.name + ": " + std::to_string(run.trace.scans.size()) +
                       " laser records, march ray caster, " + std::to_string(w.options.run_particles) +
                       " particles, every " + std::to_string(w.options.run_beam_step) +
                       "th beam, global localization; every update priced on every backend (memory replayed on "
                       "SM 0, the rest estimated).");
  }
  for (RayCastMethod method : {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    const DelibotColumn o = PriceFirstUpdate(w, method, ours);
    const DelibotColumn a = &artifact == &ours ? o : PriceFirstUpdate(w, method, artifact);
    const std::string workload = fmt::format("1 update of {:.0f} rays x {:.1f} nodes", o.queries, o.nodes / o.queries);
    AddPair(rows, std::string("DeliBot MCL (") + ToString(method) + ")", ToString(method),
            CalibrationScale::kSmallBatch, workload, a, o);
  }
  return rows;
}

}  // namespace rc
