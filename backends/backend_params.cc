#include "backends/backend_params.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "backends/json_document.h"
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

std::string FormatRange(const ParameterSpec& spec) {
  if (spec.min == 0 && spec.max == 0) return "";  // a choice: its unit lists the values
  return "[" + FormatValue(spec.min) + ", " + FormatValue(spec.max) + "]";
}

struct Describer {
  std::string prefix;
  std::vector<ParameterDescription>* rows;
  template <class T>
  void operator()(const std::string& name, const T& value, const ParameterSpec& spec) {
    rows->push_back({prefix + "." + name, FormatValue(value), spec.unit, FormatRange(spec), spec.source});
  }
};

// The first parameter outside its declared range, if any.
struct RangeCheck {
  std::string prefix;
  std::string* bad;
  void Check(const std::string& name, double value, const ParameterSpec& spec) {
    if (bad->empty() && !spec.Contains(value))
      *bad = prefix + "." + name + " = " + FormatValue(value) + " is outside its range " + FormatRange(spec) + " (" +
             spec.unit + ")";
  }
  void operator()(const std::string& name, int value, const ParameterSpec& spec) { Check(name, value, spec); }
  void operator()(const std::string& name, double value, const ParameterSpec& spec) { Check(name, value, spec); }
  template <class Choice>
  void operator()(const std::string&, const Choice&, const ParameterSpec&) {}
};

// Flattens nested JSON objects into dotted keys: {"gpu": {"sms": 8}} ->
// "gpu.sms" = 8.
void Flatten(const nlohmann::json& j, const std::string& prefix, std::map<std::string, nlohmann::json>& out) {
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
  void operator()(const std::string& name, int& field, const ParameterSpec&) {
    const auto it = values->find(prefix + "." + name);
    if (it == values->end()) return;
    if (!it->second.is_number_integer())
      throw InputError(*file, 0, it->first, "expected an integer, got " + it->second.dump());
    const auto v = it->second.get<long long>();
    if (v < INT_MIN || v > INT_MAX) throw InputError(*file, 0, it->first, "integer out of range");
    field = static_cast<int>(v);
    values->erase(it);
  }
  void operator()(const std::string& name, double& field, const ParameterSpec&) {
    const auto it = values->find(prefix + "." + name);
    if (it == values->end()) return;
    if (!it->second.is_number()) throw InputError(*file, 0, it->first, "expected a number, got " + it->second.dump());
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
  template <class Choice>
  void operator()(const std::string& name, Choice& field, const ParameterSpec& spec) {
    ChooseFrom(name, field, spec.unit);
  }
};

bool Fail(std::string* error, const std::string& what) {
  if (error) *error = what;
  return false;
}

}  // namespace

int GpuParams::DramExtraCycles() const {
  return static_cast<int>(
      std::lround((dram_latency_dram_cycles + dram_cas_dram_cycles) * core_clock_hz / dram_clock_hz));
}

double GpuParams::DramBytesPerCoreCycle() const {
  return dram_channels * dram_bus_bytes * dram_transfers_per_clock * dram_clock_hz / core_clock_hz;
}

bool GpuParams::IsValid(std::string* error) const {
  auto power_of_two = [](int v) { return v > 0 && (v & (v - 1)) == 0; };
  if (!power_of_two(sector_bytes) || !power_of_two(line_bytes) || line_bytes < sector_bytes ||
      line_bytes / sector_bytes > 8)
    return Fail(error, "gpu: sector_bytes and line_bytes must be powers of two, a line 1 to 8 sectors");
  if (l1_bytes < line_bytes || l1_bytes % line_bytes != 0)
    return Fail(error, "gpu.l1_bytes must be a positive multiple of line_bytes");
  if (l2_bytes % (line_bytes * l2_ways) != 0)
    return Fail(error, "gpu.l2_bytes must be a positive multiple of line_bytes * l2_ways");
  if (registers_per_sm < warp_size) return Fail(error, "gpu.registers_per_sm too small");
  return true;
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
  if (beam_leaf == SimtBeamLeaf::kNone) return Fail(error, "simt.beam_leaf must be maxlog or exact");
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
  auto scale = [&](int& cycles) { cycles = std::max(1, static_cast<int>(std::lround(cycles * sact_latency_scale))); };
  scale(c.latencies.pre_process_cycles);
  scale(c.latencies.box_normal_cycles);
  scale(c.latencies.edge_edge_cycles);
  c.interconnect_hop_cycles = unit.interconnect_hop_cycles;
  c.predicated_op_cycles = unit.predicated_op_cycles;
  c.pre_process_initiation_cycles = pre_process_initiation_cycles;
  c.box_normal_initiation_cycles = box_normal_initiation_cycles;
  c.edge_edge_initiation_cycles = edge_edge_initiation_cycles;
  c.ctrl_exit_cycles = ctrl_exit_cycles;
  return c;
}

bool BackendParameters::IsValid(std::string* error) const {
  std::string bad;
  ForEachStruct(*this, [&](const char* prefix, const auto& s, auto fields) {
    RangeCheck check{prefix, &bad};
    fields(s, check);
  });
  if (!bad.empty()) return Fail(error, bad);
  return gpu.IsValid(error) && simt.IsValid(error);
}

std::vector<ParameterDescription> DescribeBackendParameters(const BackendParameters& p) {
  std::vector<ParameterDescription> rows;
  ForEachStruct(p, [&](const char* prefix, const auto& s, auto fields) {
    Describer d{prefix, &rows};
    fields(s, d);
  });
  return rows;
}

void PrintBackendParameters(std::ostream& out, const BackendParameters& p, const std::string& given_by) {
  auto rows = DescribeBackendParameters(p);
  const auto defaults = DescribeBackendParameters(BackendParameters{});
  for (std::size_t i = 0; i < rows.size() && i < defaults.size(); ++i)
    if (rows[i].key == defaults[i].key && rows[i].value != defaults[i].value)
      rows[i].source = "given: " + (given_by.empty() ? std::string("an override") : given_by) + " (default " +
                       defaults[i].value + ", " + defaults[i].source + ")";
  std::size_t key_width = 0, value_width = 0, unit_width = 0, range_width = 5;
  for (const auto& r : rows) {
    key_width = std::max(key_width, r.key.size());
    value_width = std::max(value_width, r.value.size());
    unit_width = std::max(unit_width, r.unit.size());
    range_width = std::max(range_width, r.range.size());
  }
  auto cell = [&](const std::string& text, std::size_t width) {
    out << std::left << std::setw(static_cast<int>(width)) << text << "  ";
  };
  cell("parameter", key_width);
  cell("value", value_width);
  cell("unit", unit_width);
  cell("range", range_width);
  out << "source\n";
  for (const auto& r : rows) {
    cell(r.key, key_width);
    cell(r.value, value_width);
    cell(r.unit, unit_width);
    cell(r.range, range_width);
    out << r.source << "\n";
  }
}

namespace {

// Applies dotted-key overrides to `p` and checks the result.
void ApplyOverrides(BackendParameters& p, std::map<std::string, nlohmann::json> values, const std::string& file_name) {
  ForEachStruct(p, [&](const char* prefix, auto& s, auto fields) {
    Overrider o{prefix, &values, &file_name};
    fields(s, o);
  });
  if (!values.empty())
    throw InputError(file_name, 0, values.begin()->first, "unknown parameter (rcbench backends lists them all)");
  std::string error;
  if (!p.IsValid(&error)) throw InputError(file_name, 0, "", error);
}

// What a sweep tries for each kind of field.
struct VariantLister {
  std::string prefix;
  std::vector<ParameterVariants>* out;
  void Add(const std::string& name, const ParameterSpec& spec, const std::string& value,
           std::vector<std::string> alts) {
    out->push_back({prefix + "." + name, spec, value, std::move(alts)});
  }
  template <class T>
  void Numeric(const std::string& name, T value, const ParameterSpec& spec) {
    std::vector<std::string> alts;
    for (double factor : {0.5, 2.0}) {
      double v = std::clamp(static_cast<double>(value) * factor, spec.min, spec.max);
      if (std::is_integral<T>::value) v = std::round(v);
      const std::string text = std::is_integral<T>::value ? std::to_string(static_cast<long long>(v)) : FormatValue(v);
      if (v != static_cast<double>(value) && std::find(alts.begin(), alts.end(), text) == alts.end())
        alts.push_back(text);
    }
    Add(name, spec, FormatValue(value), std::move(alts));
  }
  void operator()(const std::string& name, int value, const ParameterSpec& spec) { Numeric(name, value, spec); }
  void operator()(const std::string& name, double value, const ParameterSpec& spec) { Numeric(name, value, spec); }
  template <class Choice>
  void operator()(const std::string& name, Choice value, const ParameterSpec& spec) {
    std::vector<std::string> alts;
    for (Choice c : AllChoices(value))
      if (c != value) alts.push_back(std::string("\"") + ToString(c) + "\"");
    Add(name, spec, ToString(value), std::move(alts));
  }
  static std::vector<SimtPrecision> AllChoices(SimtPrecision) {
    return {SimtPrecision::kHost, SimtPrecision::kFp32, SimtPrecision::kFp64};
  }
  static std::vector<SimtIsa> AllChoices(SimtIsa) { return {SimtIsa::kPtx, SimtIsa::kSass}; }
  static std::vector<SimtBeamLeaf> AllChoices(SimtBeamLeaf) { return {SimtBeamLeaf::kMaxLog, SimtBeamLeaf::kExact}; }
};

}  // namespace

BackendParameters ParseBackendParameters(const std::string& json_text, const std::string& file_name) {
  const nlohmann::json j = ParseJsonDocument(json_text, file_name);
  if (!j.is_object()) throw InputError(file_name, 0, "", "expected a JSON object at the top level");
  std::map<std::string, nlohmann::json> values;
  Flatten(j, "", values);
  BackendParameters p;
  ApplyOverrides(p, std::move(values), file_name);
  return p;
}

std::vector<ParameterVariants> SweepVariants(const BackendParameters& p) {
  std::vector<ParameterVariants> out;
  ForEachStruct(p, [&](const char* prefix, const auto& s, auto fields) {
    VariantLister lister{prefix, &out};
    fields(s, lister);
  });
  return out;
}

BackendParameters WithParameter(const BackendParameters& p, const std::string& key, const std::string& json_value) {
  BackendParameters out = p;
  const nlohmann::json value = ParseJsonDocument(json_value, "<parameter>", key);
  ApplyOverrides(out, {{key, value}}, "<parameter>");
  return out;
}

std::string ParameterValue(const BackendParameters& p, const std::string& key) {
  for (const ParameterDescription& d : DescribeBackendParameters(p))
    if (d.key == key) return d.value;
  throw std::invalid_argument("no backend parameter '" + key + "'");
}

BackendParameters LoadBackendParameters(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the backend parameter file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseBackendParameters(text.str(), path);
}

}  // namespace rc
