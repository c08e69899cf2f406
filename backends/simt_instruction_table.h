#pragma once
// The compiled instruction counts the SIMT model prices
// (backends/simt_instruction_table.json, written by
// scripts/simt_instruction_counts.py from the CUDA kernels in
// backends/cuda/; docs/simt_instruction_counts.md).
//
// Per shipped step program, per precision (fp32, fp64) and per ISA (PTX, and
// SASS where the table has it): the warp instructions one thread issues in
// each section, by class. prologue and epilogue run once per query, loop
// once per node fetch. The ray programs also have the kernels with a beam
// leaf compiled in (with_beam_leaf: the max-log leaf of beam_leaf.asm;
// with_exact_beam_leaf: the host's exact density). The JSON is embedded at build time, so
// a binary needs no file at run time.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/kernel_record.h"

namespace rc {

// Instruction classes, in the table's order. They follow how the artifact's
// GPGPU-Sim times a PTX instruction (ptx_instruction::set_opcode_and_latency):
// add/sub/min/max/mul/mad/fma by type, divisions by type, the SFU opcodes
// (rcp, sqrt, rsqrt, ex2, lg2, sin, cos), loads, stores and atomics,
// branches, and every other opcode (moves, compares, selects, conversions,
// logic), which it times as a 1-cycle ALU op.
enum class SimtClass : std::uint8_t {
  kFp32,
  kFp64,
  kInt,
  kFp32Div,
  kFp64Div,
  kIntDiv,
  kSfu,
  kLoad,
  kStore,
  kBranch,
  kOther,
};
inline constexpr int kSimtClassCount = 11;
const char* ToString(SimtClass c);  // "fp32", ..., as in the JSON

using SimtClassCounts = std::array<std::uint64_t, kSimtClassCount>;
std::uint64_t Total(const SimtClassCounts& c);
SimtClassCounts& operator+=(SimtClassCounts& a, const SimtClassCounts& b);

enum class SimtIsa : std::uint8_t { kPtx, kSass };
enum class SimtPrecision : std::uint8_t { kHost, kFp32, kFp64 };
// The beam leaf compiled into a ray kernel: none, the max-log leaf of
// programs/beam_leaf.asm, or the host's exact BeamLogDensity.
enum class SimtBeamLeaf : std::uint8_t { kNone, kMaxLog, kExact };

struct CompiledSections {
  SimtClassCounts prologue{};
  SimtClassCounts loop{};
  SimtClassCounts epilogue{};
};

// One compiled entry point.
struct CompiledKernel {
  std::string name;   // e.g. "rc_march_fp64"
  int registers = 0;  // per thread, ptxas -v
  CompiledSections ptx;
  CompiledSections sass;
  bool has_sass = false;
};

class SimtInstructionTable {
 public:
  // The table embedded at build time (parsed once).
  static const SimtInstructionTable& Shipped();
  // Parses a table; throws InputError naming `file_name` and the key.
  static SimtInstructionTable Parse(const std::string& json_text, const std::string& file_name);

  // The kernel compiled for a shipped step program (e.g. "dda_step.asm"),
  // with the given beam leaf; null when the table has none.
  const CompiledKernel* Find(const std::string& program_file, bool fp64, SimtBeamLeaf leaf) const;

  // True when every kernel has SASS counts (simt.isa = sass needs them).
  bool has_sass() const;
  const std::string& nvcc() const { return nvcc_; }
  const std::string& arch() const { return arch_; }

 private:
  struct Entry {
    std::string program_file;
    bool fp64 = false;
    SimtBeamLeaf leaf = SimtBeamLeaf::kNone;
    CompiledKernel kernel;
  };
  std::vector<Entry> entries_;
  std::string nvcc_;
  std::string arch_;
};

// The file of a shipped step program ("grid_march.asm", ...).
const char* ShippedProgramFile(StepProgramKind kind);

}  // namespace rc
