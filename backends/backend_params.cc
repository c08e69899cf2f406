#include "backends/backend_params.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/input_error.h"

namespace rc {
namespace {

// Calls f(prefix, struct) for every parameter struct, in printing order.
template <class Params, class F>
void ForEachStruct(Params& p, F&& f) {
  f("gpu", p.gpu, [](auto& s, auto& v) { GpuParams::Fields(s, v); });
  f("energy", p.energy, [](auto& s, auto& v) { EnergyParams::Fields(s, v); });
  f("simt", p.simt, [](auto& s, auto& v) { SimtParams::Fields(s, v); });
  f("ttaplus", p.ttaplus, [](auto& s, auto& v) { TtaPlusParams::Fields(s, v); });
  f("robocore", p.robocore, [](auto& s, auto& v) { RoboCoreParams::Fields(s, v); });
}

std::string FormatValue(int v) { return std::to_string(v); }
std::string FormatValue(SimtPrecision v) { return ToString(v); }
std::string FormatValue(SimtIsa v) { return ToString(v); }
std::string FormatValue(SimtBeamLeaf v) { return ToString(v); }
std::string FormatValue(double v) {
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

struct Describer {
  std::string prefix;
  std::vector<ParameterDescription>* rows;
  template <class T>
  void operator()(const std::string& name, const T& value, const char* unit, const char* source) {
    rows->push_back({prefix + "." + name, FormatValue(value), unit, source});
  }
};

// Flattens nested JSON objects into dotted keys: {"gpu": {"sms": 8}} ->
// "gpu.sms" = 8.
void Flatten(const nlohmann::json& j, const std::string& prefix,
             std::map<std::string, nlohmann::json>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it.value().is_object())
      Flatten(it.value(), key, out);
    else
      out[key] = it.value();
  }
}

struct Overrider {
  std::string prefix;
  std::map<std::string, nlohmann::json>* values;
  const std::string* file;
  void operator()(const std::string& name, int& field, const char*, const char*) {
    const auto it = values->find(prefix + "." + name);
    if (it == values->end()) return;
    if (!it->second.is_number_integer())
      throw InputError(*file, 0, it->first, "expected an integer, got " + it->second.dump());
    const auto v = it->second.get<long long>();
    if (v < INT_MIN || v > INT_MAX) throw InputError(*file, 0, it->first, "integer out of range");
    field = static_cast<int>(v);
    values->erase(it);
  }
  void operator()(const std::string& name, double& field, const char*, const char*) {
    const auto it = values->find(prefix + "." + name);
    if (it == values->end()) return;
    if (!it->second.is_number())
      throw InputError(*file, 0, it->first, "expected a number, got " + it->second.dump());
    field = it->second.get<double>();
    values->erase(it);
  }
  // A choice: a JSON string naming one of its values (the unit lists them).
  template <class Choice>
  void ChooseFrom(const std::string& name, Choice& field, const char* unit) {
    const auto it = values->find(prefix + "." + name);
    if (it == values->end()) return;
    if (!it->second.is_string() || !ParseChoice(it->second.get<std::string>(), &field))
      throw InputError(*file, 0, it->first, std::string("expected one of ") + unit + ", got " + it->second.dump());
    values->erase(it);
  }
  void operator()(const std::string& name, SimtPrecision& field, const char* unit, const char*) {
    ChooseFrom(name, field, unit);
  }
  void operator()(const std::string& name, SimtIsa& field, const char* unit, const char*) {
    ChooseFrom(name, field, unit);
  }
  void operator()(const std::string& name, SimtBeamLeaf& field, const char* unit, const char*) {
    ChooseFrom(name, field, unit);
  }
};

bool Fail(std::string* error, const std::string& what) {
  if (error) *error = what;
  return false;
}

}  // namespace

int GpuParams::DramExtraCycles() const {
  return static_cast<int>(std::lround((dram_latency_dram_cycles + dram_cas_dram_cycles) *
                                      core_clock_hz / dram_clock_hz));
}

double GpuParams::DramBytesPerCoreCycle() const {
  return dram_channels * dram_bus_bytes * dram_transfers_per_clock * dram_clock_hz / core_clock_hz;
}

bool GpuParams::IsValid(std::string* error) const {
  if (sms < 1 || max_warps_per_sm < 1 || warp_size < 1 || warps_per_block < 1)
    return Fail(error, "gpu: sms, max_warps_per_sm, warp_size and warps_per_block must be >= 1");
  if (!(core_clock_hz > 0 && dram_clock_hz > 0)) return Fail(error, "gpu: clocks must be > 0 Hz");
  auto power_of_two = [](int v) { return v > 0 && (v & (v - 1)) == 0; };
  if (!power_of_two(sector_bytes) || !power_of_two(line_bytes) || line_bytes < sector_bytes ||
      line_bytes / sector_bytes > 8)
    return Fail(error, "gpu: sector_bytes and line_bytes must be powers of two, a line 1 to 8 sectors");
  if (l1_bytes < line_bytes || l1_bytes % line_bytes != 0)
    return Fail(error, "gpu.l1_bytes must be a positive multiple of line_bytes");
  if (l2_ways < 1 || l2_bytes % (line_bytes * l2_ways) != 0)
    return Fail(error, "gpu.l2_bytes must be a positive multiple of line_bytes * l2_ways");
  if (l1_latency_cycles < 1 || l2_latency_cycles < 0 || dram_latency_dram_cycles < 0 ||
      dram_cas_dram_cycles < 0 || kernel_launch_cycles < 0)
    return Fail(error, "gpu: latencies must be >= 0 (L1 >= 1)");
  if (dram_channels < 1 || dram_bus_bytes < 1 || dram_transfers_per_clock < 1)
    return Fail(error, "gpu: DRAM channels, bus bytes and transfers must be >= 1");
  if (registers_per_sm < warp_size) return Fail(error, "gpu.registers_per_sm too small");
  return true;
}

bool EnergyParams::IsValid(std::string* error) const {
  struct NonNegative {
    std::string bad;
    void operator()(const std::string& name, double value, const char*, const char*) {
      if (!(value >= 0 && std::isfinite(value)) && bad.empty()) bad = "energy." + name + " must be >= 0";
    }
  } check;
  Fields(*this, check);
  return check.bad.empty() || Fail(error, check.bad);
}

std::array<int, kOpcodeCount> SimtParams::DefaultInstructionsPerElement() {
  std::array<int, kOpcodeCount> n{};
  n.fill(1);
  n[static_cast<int>(Opcode::kCross)] = 2;
  n[static_cast<int>(Opcode::kXform)] = 3;
  for (Opcode op : {Opcode::kPre, Opcode::kBox, Opcode::kEdge, Opcode::kLoad})
    n[static_cast<int>(op)] = 0;  // counted through their expansion / instructions_per_load
  return n;
}

int SimtParams::ResidentWarps(const GpuParams& gpu, int registers) const {
  const int by_registers = gpu.registers_per_sm / (std::max(1, registers) * gpu.warp_size);
  return std::max(1, std::min(gpu.max_warps_per_sm, by_registers));
}

bool SimtParams::IsValid(std::string* error) const {
  if (schedulers_per_sm < 1 || issue_per_scheduler_per_cycle < 1 || l1_sectors_per_cycle < 1)
    return Fail(error, "simt: schedulers, issue rate and L1 sectors per cycle must be >= 1");
  for (int c : {fp32_initiation_cycles, fp64_initiation_cycles, int_initiation_cycles, fp32_div_initiation_cycles,
                fp64_div_initiation_cycles, int_div_initiation_cycles, sfu_initiation_cycles, other_initiation_cycles})
    if (c < 1) return Fail(error, "simt: every initiation interval must be >= 1 cycle");
  for (int c : {fp32_latency_cycles, fp64_latency_cycles, int_latency_cycles, fp32_div_latency_cycles,
                fp64_div_latency_cycles, int_div_latency_cycles, sfu_latency_cycles, other_latency_cycles})
    if (c < 0) return Fail(error, "simt: every latency must be >= 0 cycles");
  if (beam_leaf == SimtBeamLeaf::kNone) return Fail(error, "simt.beam_leaf must be maxlog or exact");
  if (fp64_units_per_scheduler < 0) return Fail(error, "simt.fp64_units_per_scheduler must be >= 0");
  if (registers_per_thread < 0 || registers_per_thread > 255 || fallback_registers_per_thread < 1 ||
      fallback_registers_per_thread > 255)
    return Fail(error, "simt: registers per thread must be 0 (compiled) to 255; the fallback's 1 to 255");
  if (loop_branch_instructions < 0 || instructions_per_load < 1)
    return Fail(error, "simt: loop branch instructions must be >= 0 and instructions per load >= 1");
  for (int n : instructions_per_element)
    if (n < 0) return Fail(error, "simt.instructions_per_element must be >= 0");
  return true;
}

const char* ToString(SimtPrecision p) {
  switch (p) {
    case SimtPrecision::kHost: return "host";
    case SimtPrecision::kFp32: return "fp32";
    case SimtPrecision::kFp64: return "fp64";
  }
  return "?";
}

const char* ToString(SimtIsa isa) { return isa == SimtIsa::kPtx ? "ptx" : "sass"; }

bool ParseChoice(const std::string& text, SimtPrecision* out) {
  for (SimtPrecision p : {SimtPrecision::kHost, SimtPrecision::kFp32, SimtPrecision::kFp64})
    if (text == ToString(p)) return *out = p, true;
  return false;
}

const char* ToString(SimtBeamLeaf leaf) {
  switch (leaf) {
    case SimtBeamLeaf::kNone: return "none";
    case SimtBeamLeaf::kMaxLog: return "maxlog";
    case SimtBeamLeaf::kExact: return "exact";
  }
  return "?";
}

bool ParseChoice(const std::string& text, SimtBeamLeaf* out) {
  for (SimtBeamLeaf leaf : {SimtBeamLeaf::kMaxLog, SimtBeamLeaf::kExact})
    if (text == ToString(leaf)) return *out = leaf, true;
  return false;
}

bool ParseChoice(const std::string& text, SimtIsa* out) {
  for (SimtIsa isa : {SimtIsa::kPtx, SimtIsa::kSass})
    if (text == ToString(isa)) return *out = isa, true;
  return false;
}

bool RtUnitParams::IsValid(std::string* error) const {
  if (warp_buffer_warps < 1 || intersection_unit_sets < 1 || threads_accepted_per_cycle_per_set < 1 ||
      sector_requests_per_cycle < 1)
    return Fail(error, "rt unit: warp buffer, unit sets, intake and request rates must be >= 1");
  if (interconnect_hop_cycles < 0 || predicated_op_cycles < 1 || program_config_cycles_per_micro_op < 0)
    return Fail(error, "rt unit: hop >= 0, predicated op >= 1, program config >= 0 cycles");
  const OpUnitLatencies& l = latencies;
  for (int c : {l.addsub_cycles, l.minmax_cycles, l.maxmin_cycles, l.cmp_cycles, l.mul_cycles,
                l.rcp_cycles, l.pre_process_cycles, l.box_normal_cycles, l.edge_edge_cycles,
                l.logic_cycles, l.push_cycles, l.return_cycles, l.rcp_initiation_cycles})
    if (c < 1) return Fail(error, "rt unit: every OP-unit latency must be >= 1 cycle");
  return true;
}

DatapathConfig TtaPlusParams::Datapath(EarlyExitMode mode) const {
  DatapathConfig c;
  c.kind = DatapathKind::kTtaPlus;
  c.exit_mode = mode;
  c.latencies = unit.latencies;
  c.interconnect_hop_cycles = unit.interconnect_hop_cycles;
  c.predicated_op_cycles = unit.predicated_op_cycles;
  return c;
}

DatapathConfig RoboCoreParams::Datapath() const {
  DatapathConfig c;
  c.kind = DatapathKind::kRoboCore;
  c.exit_mode = EarlyExitMode::kConditionalReturn;
  c.latencies = unit.latencies;
  auto scale = [&](int& cycles) {
    cycles = std::max(1, static_cast<int>(std::lround(cycles * sact_latency_scale)));
  };
  scale(c.latencies.pre_process_cycles);
  scale(c.latencies.box_normal_cycles);
  scale(c.latencies.edge_edge_cycles);
  c.interconnect_hop_cycles = unit.interconnect_hop_cycles;
  c.predicated_op_cycles = unit.predicated_op_cycles;
  c.sact_pipeline_stages = sact_pipeline_stages;
  c.ctrl_exit_cycles = ctrl_exit_cycles;
  return c;
}

bool RoboCoreParams::IsValid(std::string* error) const {
  if (!unit.IsValid(error)) return false;
  if (sact_pipeline_stages < 1) return Fail(error, "robocore.sact_pipeline_stages must be >= 1");
  if (!(sact_latency_scale > 0 && std::isfinite(sact_latency_scale)))
    return Fail(error, "robocore.sact_latency_scale must be > 0");
  if (ctrl_exit_cycles < 0 || decode_config_cycles_per_layout < 0)
    return Fail(error, "robocore: CTRL and decode cycles must be >= 0");
  return true;
}

bool BackendParameters::IsValid(std::string* error) const {
  return gpu.IsValid(error) && energy.IsValid(error) && simt.IsValid(error) &&
         ttaplus.unit.IsValid(error) && robocore.IsValid(error);
}

std::vector<ParameterDescription> DescribeBackendParameters(const BackendParameters& p) {
  std::vector<ParameterDescription> rows;
  ForEachStruct(p, [&](const char* prefix, const auto& s, auto fields) {
    Describer d{prefix, &rows};
    fields(s, d);
  });
  return rows;
}

void PrintBackendParameters(std::ostream& out, const BackendParameters& p) {
  const auto rows = DescribeBackendParameters(p);
  std::size_t key_width = 0, value_width = 0, unit_width = 0;
  for (const auto& r : rows) {
    key_width = std::max(key_width, r.key.size());
    value_width = std::max(value_width, r.value.size());
    unit_width = std::max(unit_width, r.unit.size());
  }
  out << std::left << std::setw(static_cast<int>(key_width)) << "parameter" << "  "
      << std::setw(static_cast<int>(value_width)) << "value" << "  "
      << std::setw(static_cast<int>(unit_width)) << "unit" << "  source\n";
  for (const auto& r : rows)
    out << std::left << std::setw(static_cast<int>(key_width)) << r.key << "  "
        << std::setw(static_cast<int>(value_width)) << r.value << "  "
        << std::setw(static_cast<int>(unit_width)) << r.unit << "  " << r.source << "\n";
}

BackendParameters ParseBackendParameters(const std::string& json_text, const std::string& file_name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file_name, 0, "", std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(file_name, 0, "", "expected a JSON object at the top level");
  std::map<std::string, nlohmann::json> values;
  Flatten(j, "", values);
  BackendParameters p;
  ForEachStruct(p, [&](const char* prefix, auto& s, auto fields) {
    Overrider o{prefix, &values, &file_name};
    fields(s, o);
  });
  if (!values.empty())
    throw InputError(file_name, 0, values.begin()->first,
                     "unknown parameter (rcbench backends lists them all)");
  std::string error;
  if (!p.IsValid(&error)) throw InputError(file_name, 0, "", error);
  return p;
}

BackendParameters LoadBackendParameters(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the backend parameter file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseBackendParameters(text.str(), path);
}

}  // namespace rc
