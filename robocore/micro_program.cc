#include "robocore/micro_program.h"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_error.h"

namespace rc {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A name, optionally with one component selector: p, p.x, tb.y.
bool IsIdentifier(std::string_view s) {
  if (s.size() > 2 && s[s.size() - 2] == '.' && (s.back() == 'x' || s.back() == 'y' || s.back() == 'z'))
    s.remove_suffix(2);
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

bool IsInteger(std::string_view s) {
  if (!s.empty() && s[0] == '-') s.remove_prefix(1);
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

class Parser {
 public:
  Parser(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  MicroProgram Run(std::string name) {
    std::size_t start = 0;
    while (start <= text_.size()) {
      const std::size_t end = text_.find('\n', start);
      std::string_view line = text_.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
      ++line_;
      ParseLine(line);
      if (end == std::string_view::npos) break;
      start = end + 1;
    }
    CheckLoads();
    return MicroProgram(std::move(name), std::move(sections_));
  }

 private:
  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const {
    throw InputError(file_, line_, field, problem);
  }

  void ParseLine(std::string_view line) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    line = Trim(line);
    if (line.empty()) return;
    if (line.back() == ':') return ParseLabel(Trim(line.substr(0, line.size() - 1)));
    ParseMicroOp(line);
  }

  void ParseLabel(std::string_view label) {
    int section = -1;
    for (int s = 0; s < kSectionCount; ++s)
      if (label == SectionName(static_cast<ProgramSection>(s))) section = s;
    if (section < 0) Fail("label", "unknown label '" + std::string(label) + "' (expected prologue, loop or epilogue)");
    if (seen_[section]) Fail("label", "section '" + std::string(label) + "' appears twice");
    if (section < current_)
      Fail("label", "section '" + std::string(label) + "' out of order (prologue, loop, epilogue)");
    seen_[section] = true;
    current_ = section;
  }

  void ParseMicroOp(std::string_view line) {
    if (current_ < 0) Fail("opcode", "micro-op before any section label (start with prologue:, loop: or epilogue:)");
    std::size_t split = 0;
    while (split < line.size() && !std::isspace(static_cast<unsigned char>(line[split]))) ++split;
    std::string_view head = line.substr(0, split);
    std::string_view rest = Trim(line.substr(split));

    std::string_view mnemonic = head;
    std::string_view width_text;
    if (const std::size_t dot = head.find('.'); dot != std::string_view::npos) {
      mnemonic = head.substr(0, dot);
      width_text = head.substr(dot + 1);
    }
    const auto opcode = ParseOpcode(mnemonic);
    if (!opcode) Fail("opcode", "unknown micro-op '" + std::string(mnemonic) + "'");
    const OpcodeInfo& info = InfoOf(*opcode);

    MicroOp op;
    op.opcode = *opcode;
    op.line = line_;
    op.width = static_cast<std::uint8_t>(info.default_width);
    if (head.find('.') != std::string_view::npos) {
      if (!info.has_width) Fail("width", std::string(info.mnemonic) + " takes no width suffix");
      if (width_text.size() != 1 || width_text[0] < '1' || width_text[0] > '3' || width_text[0] - '0' < info.min_width)
        Fail("width", "width '" + std::string(width_text) + "' of " + info.mnemonic + " must be " +
                          std::to_string(info.min_width) + " to 3");
      op.width = static_cast<std::uint8_t>(width_text[0] - '0');
    }

    if (!rest.empty()) {
      std::size_t start = 0;
      while (true) {
        const std::size_t comma = rest.find(',', start);
        std::string_view token =
            Trim(rest.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        const std::string field = "operand " + std::to_string(op.operands.size() + 1);
        if (token.empty()) Fail(field, "missing operand (empty between commas)");
        if (!IsIdentifier(token) && !IsInteger(token))
          Fail(field, "'" + std::string(token) + "' is neither a name nor an integer");
        op.operands.emplace_back(token);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
    }
    const int n = static_cast<int>(op.operands.size());
    const std::string usage = std::string(info.mnemonic) + " takes " + std::to_string(info.operand_count) +
                              " operand(s)" + (info.operand_count > 0 ? std::string(": ") + info.operand_names : "");
    if (n < info.operand_count) Fail("operand " + std::to_string(n + 1), "missing operand; " + usage);
    if (n > info.operand_count)
      Fail("operand " + std::to_string(info.operand_count + 1), "unexpected operand; " + usage);
    if (info.max_axis >= 0) {
      const std::string& axis = op.operands.back();
      // from_chars, not stol: a number too long for a long is out of range
      // here too, not an uncaught std::out_of_range (a tests/fuzz finding).
      long value = -1;
      const auto parsed = std::from_chars(axis.data(), axis.data() + axis.size(), value);
      if (!IsInteger(axis) || parsed.ec != std::errc() || value < 0 || value > info.max_axis)
        Fail("axis", std::string(info.mnemonic) + " axis '" + axis + "' must be an integer 0.." +
                         std::to_string(info.max_axis));
      op.axis = static_cast<int>(value);
    }
    if (op.opcode == Opcode::kLoad && current_ != static_cast<int>(ProgramSection::kLoop))
      Fail("opcode", "LOAD (a node fetch) belongs in the loop: section only");
    sections_[current_].push_back(std::move(op));
  }

  void CheckLoads() {
    // A leaf program (epilogue only) has no loop; a step program's loop
    // fetches exactly one node per pass.
    if (!seen_[static_cast<int>(ProgramSection::kLoop)]) return;
    const auto& loop = sections_[static_cast<int>(ProgramSection::kLoop)];
    int loads = 0;
    for (const MicroOp& op : loop) loads += op.opcode == Opcode::kLoad;
    if (loads != 1)
      throw InputError(file_, 0, "loop",
                       "the loop must hold exactly one LOAD (one node fetch per pass), found " + std::to_string(loads));
    if (loop.front().opcode != Opcode::kLoad)
      throw InputError(file_, loop.front().line, "opcode",
                       "a loop pass starts with its node fetch: LOAD must be the loop's first "
                       "micro-op");
  }

  std::string_view text_;
  std::string file_;
  long line_ = 0;
  int current_ = -1;
  std::array<bool, kSectionCount> seen_{};
  std::array<std::vector<MicroOp>, kSectionCount> sections_;
};

}  // namespace

const char* SectionName(ProgramSection s) {
  switch (s) {
    case ProgramSection::kPrologue: return "prologue";
    case ProgramSection::kLoop: return "loop";
    case ProgramSection::kEpilogue: return "epilogue";
  }
  return "?";
}

MicroProgram::MicroProgram(std::string name, std::array<std::vector<MicroOp>, kSectionCount> sections)
    : name_(std::move(name)), sections_(std::move(sections)) {}

int MicroProgram::ReturnIfCount(ProgramSection s) const {
  int n = 0;
  for (const MicroOp& op : section(s)) n += op.opcode == Opcode::kReturnIf;
  return n;
}

std::size_t MicroProgram::MicroOpCount() const {
  std::size_t n = 0;
  for (const auto& s : sections_) n += s.size();
  return n;
}

MicroProgram ParseMicroProgram(std::string_view text, const std::string& file_name) {
  const std::string stem = std::filesystem::path(file_name).stem().string();
  return Parser(text, file_name).Run(stem);
}

MicroProgram LoadMicroProgram(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open micro-op program");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseMicroProgram(text.str(), path);
}

}  // namespace rc
