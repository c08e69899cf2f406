#include "backends/simt_instruction_table.h"

#include <nlohmann/json.hpp>

#include "common/input_error.h"

namespace rc {

// Defined in the generated simt_instruction_table_json.cc (backends/CMakeLists.txt).
const char* EmbeddedSimtInstructionTable();

namespace {

constexpr const char* kClassNames[kSimtClassCount] = {"fp32", "fp64", "int",   "fp32_div", "fp64_div", "int_div",
                                                      "sfu",  "load", "store", "branch",   "other"};

using Json = nlohmann::json;

const Json& Member(const Json& j, const std::string& key, const std::string& path, const std::string& file) {
  if (!j.is_object() || !j.contains(key)) throw InputError(file, 0, path + key, "missing");
  return j.at(key);
}

SimtClassCounts ReadCounts(const Json& j, const std::string& path, const std::string& file) {
  if (!j.is_object()) throw InputError(file, 0, path, "expected an object of class counts");
  SimtClassCounts c{};
  for (int i = 0; i < kSimtClassCount; ++i) {
    const Json& v = Member(j, kClassNames[i], path + "/", file);
    if (!v.is_number_integer() || v.get<long long>() < 0)
      throw InputError(file, 0, path + "/" + kClassNames[i], "expected a count >= 0, got " + v.dump());
    c[i] = v.get<std::uint64_t>();
  }
  if (j.size() != static_cast<std::size_t>(kSimtClassCount))
    throw InputError(file, 0, path, "unknown instruction class (the classes are fp32 ... other)");
  return c;
}

CompiledSections ReadSections(const Json& j, const std::string& path, const std::string& file) {
  CompiledSections s;
  s.prologue = ReadCounts(Member(j, "prologue", path + "/", file), path + "/prologue", file);
  s.loop = ReadCounts(Member(j, "loop", path + "/", file), path + "/loop", file);
  s.epilogue = ReadCounts(Member(j, "epilogue", path + "/", file), path + "/epilogue", file);
  return s;
}

CompiledKernel ReadKernel(const Json& j, const std::string& path, const std::string& file) {
  CompiledKernel k;
  const Json& name = Member(j, "kernel", path + "/", file);
  const Json& registers = Member(j, "registers", path + "/", file);
  if (!name.is_string()) throw InputError(file, 0, path + "/kernel", "expected a string");
  if (!registers.is_number_integer() || registers.get<int>() < 1 || registers.get<int>() > 255)
    throw InputError(file, 0, path + "/registers", "expected 1 to 255 registers");
  k.name = name.get<std::string>();
  k.registers = registers.get<int>();
  k.ptx = ReadSections(Member(j, "ptx", path + "/", file), path + "/ptx", file);
  if (j.contains("sass")) {
    k.sass = ReadSections(j.at("sass"), path + "/sass", file);
    k.has_sass = true;
  }
  return k;
}

}  // namespace

const char* ToString(SimtClass c) { return kClassNames[static_cast<int>(c)]; }

std::uint64_t Total(const SimtClassCounts& c) {
  std::uint64_t n = 0;
  for (std::uint64_t v : c) n += v;
  return n;
}

SimtClassCounts& operator+=(SimtClassCounts& a, const SimtClassCounts& b) {
  for (int i = 0; i < kSimtClassCount; ++i) a[i] += b[i];
  return a;
}

const char* ShippedProgramFile(StepProgramKind kind) {
  switch (kind) {
    case StepProgramKind::kGridMarch: return "grid_march.asm";
    case StepProgramKind::kDdaStep: return "dda_step.asm";
    case StepProgramKind::kRmStep: return "rm_step.asm";
    case StepProgramKind::kSactTest: return "sact_obb_aabb.asm";
    case StepProgramKind::kSphereTest: return "sphere_aabb.asm";
    case StepProgramKind::kBallQueryPRay: return "ball_query_pray.asm";
    case StepProgramKind::kBallQueryPSphere: return "ball_query_psphere.asm";
  }
  return "?";
}

SimtInstructionTable SimtInstructionTable::Parse(const std::string& json_text, const std::string& file_name) {
  Json j;
  try {
    j = Json::parse(json_text);
  } catch (const Json::parse_error& e) {
    throw InputError(file_name, 0, "", std::string("not valid JSON: ") + e.what());
  }
  SimtInstructionTable table;
  const Json& nvcc = Member(j, "nvcc", "", file_name);
  const Json& arch = Member(j, "arch", "", file_name);
  if (!nvcc.is_string() || !arch.is_string()) throw InputError(file_name, 0, "nvcc", "expected strings nvcc, arch");
  table.nvcc_ = nvcc.get<std::string>();
  table.arch_ = arch.get<std::string>();
  const Json& classes = Member(j, "classes", "", file_name);
  if (!classes.is_array() || classes.size() != static_cast<std::size_t>(kSimtClassCount))
    throw InputError(file_name, 0, "classes", "expected the 11 instruction classes");
  for (int i = 0; i < kSimtClassCount; ++i)
    if (classes[i] != kClassNames[i])
      throw InputError(file_name, 0, "classes", "class " + std::to_string(i) + " must be " + kClassNames[i]);
  const Json& programs = Member(j, "programs", "", file_name);
  if (!programs.is_object()) throw InputError(file_name, 0, "programs", "expected an object");
  for (auto it = programs.begin(); it != programs.end(); ++it) {
    for (const char* precision : {"fp32", "fp64"}) {
      const std::string path = "programs/" + it.key() + "/" + precision;
      const Json& per = Member(it.value(), precision, "programs/" + it.key() + "/", file_name);
      const bool fp64 = precision[2] == '6';
      table.entries_.push_back({it.key(), fp64, SimtBeamLeaf::kNone, ReadKernel(per, path, file_name)});
      for (const auto& [key, leaf] : {std::pair{"with_beam_leaf", SimtBeamLeaf::kMaxLog},
                                      std::pair{"with_exact_beam_leaf", SimtBeamLeaf::kExact}})
        if (per.contains(key))
          table.entries_.push_back({it.key(), fp64, leaf, ReadKernel(per.at(key), path + "/" + key, file_name)});
    }
  }
  return table;
}

const SimtInstructionTable& SimtInstructionTable::Shipped() {
  static const SimtInstructionTable table =
      Parse(EmbeddedSimtInstructionTable(), "backends/simt_instruction_table.json (embedded)");
  return table;
}

bool SimtInstructionTable::has_sass() const {
  for (const Entry& e : entries_)
    if (!e.kernel.has_sass) return false;
  return !entries_.empty();
}

const CompiledKernel* SimtInstructionTable::Find(const std::string& program_file, bool fp64, SimtBeamLeaf leaf) const {
  for (const Entry& e : entries_)
    if (e.program_file == program_file && e.fp64 == fp64 && e.leaf == leaf) return &e.kernel;
  return nullptr;
}

}  // namespace rc
