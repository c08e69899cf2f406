// LineReader and the number parser that every text reader shares: what a
// file from another tool may hold (a byte-order mark, CRLF) is read, and
// what no format here writes (hex numbers, a directory as the file) is an
// InputError naming the file, line and field.
#include "common/text_fields.h"

#include <filesystem>
#include <fstream>
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

TEST(LooksNumeric, TellsNumbersFromWordsInAnyFormStrtodReads) {
  for (const char* number : {"1", "-2.5e3", "0x1p7", "inf", "nan"}) EXPECT_TRUE(LooksNumeric(number)) << number;
  for (const char* word : {"", "host", "cx", "1,2", "0x"}) EXPECT_FALSE(LooksNumeric(word)) << word;
}

}  // namespace
}  // namespace rc
