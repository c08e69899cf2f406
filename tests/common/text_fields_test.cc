// LineReader and the number parser that every text reader shares: what a
// file from another tool may hold (a byte-order mark, CRLF) is read, and
// what no format here writes (hex numbers, a directory as the file) is an
// InputError naming the file, line and field.
#include "common/text_fields.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::istringstream in(text);
  LineReader reader(in, "t.txt");
  std::vector<std::string> lines;
  std::string line;
  while (reader.Next(line)) lines.push_back(line);
  return lines;
}

TEST(LineReader, SkipsAByteOrderMarkAtTheStartOfTheFileOnly) {
  const std::string bom(kUtf8Bom);
  EXPECT_EQ(Lines(bom + "a b\r\n" + bom + "c\n"), (std::vector<std::string>{"a b", bom + "c"}));
  EXPECT_EQ(Lines(bom), (std::vector<std::string>{""}));
  EXPECT_EQ(Lines("\xEF\xBB"
                  "x\n"),
            (std::vector<std::string>{"\xEF\xBB"
                                      "x"}));  // not a whole mark: kept
}

TEST(LineReader, ADirectoryIsNotAnEmptyFile) {
  test::TempDir dir;
  const std::string path = dir.Path("folder.log");
  std::filesystem::create_directory(path);
  std::ifstream in(path);
  LineReader reader(in, path);
  std::string line;
  const InputError e = test::InputErrorFrom([&] { reader.Next(line); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 0);
  EXPECT_NE(std::string(e.what()).find("is a directory, not a file"), std::string::npos) << e.what();
  EXPECT_THROW(RejectDirectory(dir.path().string()), InputError);
  EXPECT_NO_THROW(RejectDirectory(dir.Write("f.txt", "x")));
}

TEST(LineReader, ParseDoubleRefusesHexadecimalNumbers) {
  std::istringstream in("x\n");
  LineReader reader(in, "t.txt");
  std::string line;
  ASSERT_TRUE(reader.Next(line));
  for (const char* hex : {"0x1p7", "0x10", "0x1p-1", "-0X1.8p1", "+0x0"}) {
    EXPECT_TRUE(test::ThrowsInputError([&] { reader.ParseDouble(hex, "v"); }, 1, "v", "hexadecimal")) << hex;
  }
  for (const char* bad : {"inf", "-infinity", "nan", "NAN(1)", "1e400", "0x", "1x"}) {
    EXPECT_THROW(reader.ParseDouble(bad, "v"), InputError) << bad;
  }
  EXPECT_EQ(reader.ParseDouble("-12.5e-1", "v"), -1.25);
  EXPECT_EQ(reader.ParseDouble("010", "v"), 10.0);  // a leading zero is decimal, not octal
}

std::uint64_t BitsOf(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

// ParseDouble reads a plain decimal token with from_chars and everything
// else with strtod: it must give strtod's double for every text strtod
// accepts (both round correctly), and refuse what it refused. Texts of every
// shape a log or map holds, and the hard ones: 17 to 40 significant digits,
// halfway cases, subnormals, the largest and smallest exponents, a '+' sign
// and spaces.
TEST(LineReader, ParseDoubleGivesStrtodsDoubleForEveryDecimalText) {
  std::istringstream in("x\n");
  LineReader reader(in, "t.txt");
  std::string line;
  ASSERT_TRUE(reader.Next(line));
  std::mt19937_64 random(24);
  std::vector<std::string> texts = {"0",       "-0",        "0.0",     "5.",      ".5",     "-.5",    "+1.5",
                                    " 1.5",    "1.5 ",      "1e5",     "1E-5",    "1e+5",   "007.250", "-1e-320",
                                    "2.2250738585072011e-308", "4.9406564584124654e-324", "1.7976931348623157e308",
                                    "9007199254740993", "0.1000000000000000055511151231257827021181583404541015625",
                                    "1e-400",  "1e308",     "1.8e308", "1e",      "1e+",    "--1",    "1.2.3",
                                    "",        "-",         ".",       "e5",      "١"};
  char buffer[64];
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t bits = random();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    if (!std::isfinite(v)) continue;
    const int digits = 1 + static_cast<int>(random() % 40);
    std::snprintf(buffer, sizeof buffer, random() % 2 ? "%.*e" : "%.*g", digits, v);
    texts.push_back(buffer);
    std::snprintf(buffer, sizeof buffer, "%.*f", static_cast<int>(random() % 8),
                  static_cast<double>(static_cast<std::int64_t>(random() % 2000001) - 1000000) / 1000.0);
    texts.push_back(buffer);
  }
  std::size_t accepted = 0;
  for (const std::string& text : texts) {
    char* end = nullptr;
    errno = 0;
    const double want = std::strtod(text.c_str(), &end);
    const bool strtod_accepts = !text.empty() && end == text.c_str() + text.size() &&
                                !(errno == ERANGE && std::abs(want) > 1.0) && std::isfinite(want);
    if (!strtod_accepts) {
      EXPECT_THROW(reader.ParseDouble(text, "v"), InputError) << "'" << text << "'";
      continue;
    }
    double got = 0.0;
    ASSERT_NO_THROW(got = reader.ParseDouble(text, "v")) << "'" << text << "'";
    ASSERT_EQ(BitsOf(got), BitsOf(want)) << "'" << text << "'";
    ++accepted;
  }
  EXPECT_GT(accepted, 390000u);
}

TEST(LooksNumeric, TellsNumbersFromWordsInAnyFormStrtodReads) {
  for (const char* number : {"1", "-2.5e3", "0x1p7", "inf", "nan"}) EXPECT_TRUE(LooksNumeric(number)) << number;
  for (const char* word : {"", "host", "cx", "1,2", "0x"}) EXPECT_FALSE(LooksNumeric(word)) << word;
}

}  // namespace
}  // namespace rc
