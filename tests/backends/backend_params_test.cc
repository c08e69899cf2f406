// Backend parameters: the printed table, the JSON override file (valid,
// unknown key, wrong type, invalid value), and the sweep knobs.
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/backend_preset.h"
#include "common/input_error.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

InputError ParseError(const std::string& json) {
  return test::InputErrorFrom([&] { ParseBackendParameters(json, "sweep.json"); }, json);
}

TEST(BackendParameters, EveryFieldIsPrintedWithValueUnitAndSource) {
  const BackendParameters p;
  const auto rows = DescribeBackendParameters(p);
  std::set<std::string> keys;
  for (const auto& r : rows) {
    EXPECT_FALSE(r.value.empty()) << r.key;
    EXPECT_FALSE(r.unit.empty()) << r.key;
    EXPECT_FALSE(r.source.empty()) << r.key;
    EXPECT_TRUE(keys.insert(r.key).second) << "duplicate " << r.key;
  }
  for (const char* key :
       {"gpu.sms", "gpu.l1_bytes", "gpu.l2_latency_cycles", "energy.dram_pj", "simt.instructions_per_element.DOT",
        "ttaplus.warp_buffer_warps", "ttaplus.interconnect_hop_cycles", "robocore.sact_latency_scale",
        "robocore.box_normal_cycles"})
    EXPECT_TRUE(keys.count(key)) << key;
  std::ostringstream out;
  PrintBackendParameters(out, p);
  EXPECT_NE(out.str().find("gpu.l2_bytes"), std::string::npos);
  EXPECT_NE(out.str().find("3145728"), std::string::npos);
  EXPECT_NE(out.str().find("Horowitz"), std::string::npos);
}

TEST(BackendParameters, ValidOverrideFileNestedAndDotted) {
  const test::TempDir dir;
  const std::string path = dir.Write("rc_backend_params.json", R"({"gpu": {"sms": 16, "l1_bytes": 131072},
               "robocore.sact_latency_scale": 2.0,
               "ttaplus": {"warp_buffer_warps": 8},
               "simt": {"instructions_per_element": {"DOT": 2}}})");
  const BackendParameters p = LoadBackendParameters(path);
  EXPECT_EQ(p.gpu.sms, 16);
  EXPECT_EQ(p.gpu.l1_bytes, 131072);
  EXPECT_EQ(p.gpu.l2_ways, 16);  // untouched
  EXPECT_DOUBLE_EQ(p.robocore.sact_latency_scale, 2.0);
  EXPECT_EQ(p.ttaplus.unit.warp_buffer_warps, 8);
  EXPECT_EQ(p.robocore.unit.warp_buffer_warps, 4);
  EXPECT_EQ(p.simt.instructions_per_element[static_cast<int>(Opcode::kDot)], 2);
}

TEST(BackendParameters, UnknownKeyNamesFileAndKey) {
  const InputError e = ParseError(R"({"gpu": {"smz": 4}})");
  EXPECT_EQ(e.file(), "sweep.json");
  EXPECT_EQ(e.field(), "gpu.smz");
  EXPECT_EQ(ParseError(R"({"tpu": {"sms": 4}})").field(), "tpu.sms");
  EXPECT_EQ(ParseError(R"({"simt": {"instructions_per_element": {"BOX": 3}}})").field(),
            "simt.instructions_per_element.BOX");  // SACT ops are counted via their expansion
}

TEST(BackendParameters, WrongTypeNamesTheKey) {
  EXPECT_EQ(ParseError(R"({"gpu": {"sms": "eight"}})").field(), "gpu.sms");
  EXPECT_EQ(ParseError(R"({"gpu": {"sms": 8.5}})").field(), "gpu.sms");
  EXPECT_EQ(ParseError(R"({"robocore": {"sact_latency_scale": [2]}})").field(), "robocore.sact_latency_scale");
}

TEST(BackendParameters, InvalidValuesAndBadJson) {
  EXPECT_NE(std::string(ParseError(R"({"gpu": {"sms": 0}})").what()).find("sms"), std::string::npos);
  ParseError(R"({"robocore": {"sact_latency_scale": -1}})");
  ParseError(R"({"gpu": {"l1_bytes": 100}})");  // not a multiple of the line
  ParseError(R"({"gpu": )");
  ParseError(R"({"gpu": {"sms": 888E888888}})");  // number overflow: out_of_range, not parse_error
  ParseError(R"([1, 2])");
  EXPECT_THROW(LoadBackendParameters("/nonexistent/params.json"), InputError);
}

// A printed source never claims a value it did not give: an overridden
// parameter is sourced to the override, with the default beside it.
TEST(BackendParameters, PrintedSourceOfAnOverrideIsTheOverride) {
  const BackendParameters p = ParseBackendParameters(R"({"gpu": {"sms": 16}})", "sms.json");
  std::ostringstream out;
  PrintBackendParameters(out, p, "sms.json");
  std::string sms_line, l1_line, line;
  std::istringstream lines(out.str());
  while (std::getline(lines, line)) {
    if (line.rfind("gpu.sms ", 0) == 0) sms_line = line;
    if (line.rfind("gpu.l1_bytes ", 0) == 0) l1_line = line;
  }
  EXPECT_NE(sms_line.find("given: sms.json (default 8,"), std::string::npos) << sms_line;
  ASSERT_FALSE(l1_line.empty());
  EXPECT_EQ(l1_line.find("given:"), std::string::npos) << l1_line;
}

// Every way into the parameters parses JSON in one place, so an overflowing
// number is bad input on each (the preset path once let it escape as an
// internal error), and a syntax error names its line.
TEST(BackendParameters, EveryJsonEntryRefusesOverflowAsInput) {
  const std::string overflow = R"({"gpu": {"sms": 1e400}})";
  EXPECT_EQ(test::InputErrorFrom([&] { ParseBackendPreset(overflow, "preset.json"); }, overflow).file(), "preset.json");
  EXPECT_EQ(test::InputErrorFrom([&] { WithParameter(BackendParameters{}, "gpu.sms", "1e400"); }, "1e400").field(),
            "gpu.sms");
  const std::string broken = "{\n  \"gpu\": {\n    \"sms\": ,\n  }\n}";
  EXPECT_EQ(ParseError(broken).line(), 3);
  EXPECT_EQ(test::InputErrorFrom([&] { ParseBackendPreset(broken, "preset.json"); }, broken).line(), 3);
}

TEST(BackendParameters, SactLatencyScaleScalesOnlyTheSactUnits) {
  RoboCoreParams r;
  r.sact_latency_scale = 0.5;
  EXPECT_EQ(r.Datapath().latencies.pre_process_cycles, 7);
  EXPECT_EQ(r.Datapath().latencies.box_normal_cycles, 6);
  EXPECT_EQ(r.Datapath().latencies.edge_edge_cycles, 6);
  EXPECT_EQ(r.Datapath().latencies.mul_cycles, 5);
  r.sact_latency_scale = 2.0;
  EXPECT_EQ(r.Datapath().latencies.pre_process_cycles, 28);
  EXPECT_EQ(r.Datapath().exit_mode, EarlyExitMode::kConditionalReturn);
}

TEST(BackendParameters, CreateRejectsUnknownNamesAndInvalidParameters) {
  BackendParameters p;
  EXPECT_THROW(Backend::Create("gpu", p), std::invalid_argument);
  p.gpu.sms = 0;
  EXPECT_THROW(Backend::Create("simt", p), std::invalid_argument);
}

}  // namespace
}  // namespace rc

namespace rc {
namespace {

// Every parameter is declared once with a unit, a range that holds its
// default, and a source; the sweep's variants stay inside the range, and a
// value outside it is refused naming the key.
TEST(BackendParameters, EveryParameterHasARangeHoldingItsDefault) {
  const BackendParameters p;
  std::string error;
  ASSERT_TRUE(p.IsValid(&error)) << error;
  for (const ParameterVariants& v : SweepVariants(p)) {
    EXPECT_NE(std::string(v.spec.unit), "") << v.key;
    EXPECT_NE(std::string(v.spec.source), "") << v.key;
    const bool choice = v.spec.min == 0 && v.spec.max == 0;
    if (!choice) {
      EXPECT_TRUE(v.spec.Contains(std::stod(v.value))) << v.key << " = " << v.value;
    }
    for (const std::string& alt : v.alternatives) {
      if (!choice) {
        EXPECT_TRUE(v.spec.Contains(std::stod(alt))) << v.key << " -> " << alt;
      }
      EXPECT_NE(alt, v.value) << v.key;
    }
  }
}

TEST(BackendParameters, WithParameterChecksLikeTheFileLoader) {
  const BackendParameters p;
  EXPECT_EQ(WithParameter(p, "robocore.warp_buffer_warps", "8").robocore.unit.warp_buffer_warps, 8);
  EXPECT_EQ(WithParameter(p, "simt.precision", "\"fp32\"").simt.precision, SimtPrecision::kFp32);
  EXPECT_EQ(ParameterValue(p, "gpu.sms"), "8");
  const InputError zero_warps =
      test::InputErrorFrom([&] { WithParameter(p, "ttaplus.warp_buffer_warps", "0"); }, "a warp buffer of 0 warps");
  EXPECT_NE(std::string(zero_warps.what()).find("ttaplus.warp_buffer_warps"), std::string::npos) << zero_warps.what();
  EXPECT_THROW(WithParameter(p, "gpu.no_such_thing", "1"), InputError);
  EXPECT_THROW(ParseBackendParameters(R"({"energy": {"dram_pj": -1}})", "x.json"), InputError);
}

TEST(BackendParameters, TheSactInitiationAndOpUnitsArePricedParameters) {
  // The SACT units' initiation interval and the OP units per kind were
  // rules; now each is a declared parameter that moves the price.
  BackendParameters p;
  const DatapathConfig paper = p.robocore.Datapath();
  EXPECT_EQ(paper.pre_process_initiation_cycles, 4);
  EXPECT_EQ(paper.box_normal_initiation_cycles, 3);
  p = WithParameter(p, "robocore.box_normal_initiation_cycles", "1");
  EXPECT_EQ(p.robocore.Datapath().box_normal_initiation_cycles, 1);
  const auto rows = DescribeBackendParameters(BackendParameters{});
  bool op_units = false;
  for (const auto& r : rows) op_units = op_units || r.key == "robocore.op_units_per_kind_per_set";
  EXPECT_TRUE(op_units);
}

}  // namespace
}  // namespace rc
