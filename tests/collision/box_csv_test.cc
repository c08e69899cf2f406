// The OBB and box CSV readers: the real mpnet_master file, and every kind
// of bad input named by file, line and field.
#include <sstream>

#include <gtest/gtest.h>

#include "common/input_error.h"
#include "robocore/collision/box_csv.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

namespace rc {
namespace {

const std::string kHeader =
    "pos,joint,obb_center_x,obb_center_y,obb_center_z,obb_axis_x1,obb_axis_y1,obb_axis_z1,obb_axis_x2,obb_axis_y2,"
    "obb_axis_z2,obb_axis_x3,obb_axis_y3,obb_axis_z3,obb_half_length_x,obb_half_length_y,obb_half_length_z\n";
const std::string kRow = "3,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25,0.125\n";

InputError ObbError(const std::string& text) {
  return test::InputErrorFrom(
      [&] {
        std::istringstream in(text);
        ReadObbCsv(in, "obbs.csv");
      },
      text);
}

TEST(ObbCsv, ReadsAxesAsColumns) {
  std::istringstream in(kHeader + kRow + "\n");
  const std::vector<RobotObb> obbs = ReadObbCsv(in, "obbs.csv");
  ASSERT_EQ(obbs.size(), 1u);
  EXPECT_EQ(obbs[0].pose, 3);
  EXPECT_EQ(obbs[0].joint, 1);
  EXPECT_EQ(obbs[0].obb.centre, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(obbs[0].obb.axes.col(0), Eigen::Vector3d(0.6, 0.8, 0));   // axis 1
  EXPECT_EQ(obbs[0].obb.axes.col(1), Eigen::Vector3d(-0.8, 0.6, 0));  // axis 2
  EXPECT_EQ(obbs[0].obb.half, Eigen::Vector3d(0.5, 0.25, 0.125));
}

TEST(ObbCsv, ReadsTheRealMpnetMasterFile) {
  RC_REQUIRE_SHARED_DATA("collision/mpnet_master_obb.csv");
  const std::vector<RobotObb> obbs = ReadObbCsv(test::SharedDataPath("collision/mpnet_master_obb.csv"));
  ASSERT_EQ(obbs.size(), 70u);  // 10 poses x 7 links
  EXPECT_EQ(obbs.back().pose, 9);
  EXPECT_EQ(obbs.back().joint, 6);
  // Row 2 (pose 0, joint 1): axis 1 = (0.9517..., -0.3069..., 0).
  EXPECT_NEAR(obbs[1].obb.axes(0, 0), 0.9517324310555171, 1e-16);
  EXPECT_NEAR(obbs[1].obb.axes(1, 0), -0.3069289489069994, 1e-16);
  for (const RobotObb& r : obbs)
    EXPECT_LT((r.obb.axes.transpose() * r.obb.axes - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ObbCsv, BadInputNamesFileLineAndField) {
  InputError e = ObbError(kHeader + kRow + "3,1,nan,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25,0.125\n");
  EXPECT_EQ(e.file(), "obbs.csv");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.field(), "obb_center_x");
  e = ObbError(kHeader + "3,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,-0.25,0.125\n");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.field(), "obb_half_length_y");
  e = ObbError(kHeader + "3,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0.1,0,0,1,0.5,0.25,0.125\n");  // axis 2 too long
  EXPECT_EQ(e.field(), "obb_axis_x2");
  EXPECT_NE(std::string(e.what()).find("unit"), std::string::npos);
  e = ObbError(kHeader + "3,1,0.1,0.2,0.3,0.6,0.8,0,0.8,0.6,0,0,0,1,0.5,0.25,0.125\n");  // axes 1, 2 not orthogonal
  EXPECT_EQ(e.field(), "obb_axis_x2");
  EXPECT_NE(std::string(e.what()).find("orthogonal"), std::string::npos);
  e = ObbError(kHeader + "3,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25\n");  // truncated
  EXPECT_EQ(e.field(), "columns");
  EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos);
  e = ObbError(kHeader + "3,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25,0.125,7\n");
  EXPECT_EQ(e.field(), "columns");
  e = ObbError(kHeader + "-1,1,0.1,0.2,0.3,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25,0.125\n");
  EXPECT_EQ(e.field(), "pos");
  e = ObbError(kHeader + "3,1,0.1,0.2,,0.6,0.8,0,-0.8,0.6,0,0,0,1,0.5,0.25,0.125\n");
  EXPECT_EQ(e.field(), "obb_center_z");
  e = ObbError("cx,cy,cz,hx,hy,hz\n");  // a box file given as OBBs
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.field(), "columns");
  EXPECT_THROW(ReadObbCsv("/nonexistent/obbs.csv"), InputError);
}

// A data row behind a byte-order mark was taken for the optional header and
// dropped; and a file without rows ran zero queries or an empty scene.
TEST(ObbCsv, AByteOrderMarkIsSkippedAndAFileWithoutRowsRefused) {
  std::istringstream bom("\xEF\xBB\xBF" + kHeader + kRow);
  EXPECT_EQ(ReadObbCsv(bom, "obbs.csv").size(), 1u);
  for (const std::string& text : {std::string(), kHeader, "\n" + kHeader + "\n"}) {
    const InputError e = ObbError(text);
    EXPECT_EQ(e.line(), 0) << text;
    EXPECT_EQ(e.field(), "OBB row") << text;
  }
  test::TempDir dir;
  const std::string folder = dir.path().string();
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadObbCsv(folder); }, 0, "", "is a directory, not a file"));
}

TEST(BoxCsv, AByteOrderMarkIsSkippedAndAFileWithoutBoxesRefused) {
  std::istringstream no_header(
      "\xEF\xBB\xBF"
      "1,2,3,0.5,1,1\n");
  ASSERT_EQ(ReadBoxCsv(no_header, "b.csv").size(), 1u);  // a box, not a header
  std::istringstream with_header(
      "\xEF\xBB\xBF"
      "cx,cy,cz,hx,hy,hz\n1,2,3,0.5,1,1\n");
  EXPECT_EQ(ReadBoxCsv(with_header, "b.csv").size(), 1u);
  for (const char* text : {"", "\n", "cx,cy,cz,hx,hy,hz\n"}) {
    test::ExpectInputError(
        [&] {
          std::istringstream in(text);
          ReadBoxCsv(in, "empty.csv");
        },
        "empty.csv", 0, "box row");
  }
  test::TempDir dir;
  const std::string folder = dir.path().string();
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadBoxCsv(folder); }, 0, "", "is a directory, not a file"));
  std::istringstream hex("1,2,0x3,0.5,1,1\n");  // a box row, refused for its hex number
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadBoxCsv(hex, "hex.csv"); }, 1, "cz", "hexadecimal"));
}

TEST(BoxCsv, OptionalHeaderRoundTripAndErrors) {
  std::istringstream with_header("cx,cy,cz,hx,hy,hz\n1,2,3,0.5,0,0.25\n\n-1e3,2e-3,0,1,1,1\n");
  const std::vector<Aabbd> boxes = ReadBoxCsv(with_header, "boxes.csv");
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].half, Eigen::Vector3d(0.5, 0, 0.25));
  std::istringstream without("0.1,0.2,0.3,1,2,3\n");
  EXPECT_EQ(ReadBoxCsv(without, "b.csv").size(), 1u);
  std::stringstream written;
  WriteBoxCsv(written, {Aabbd{Eigen::Vector3d(0.1, 1.0 / 3, -7e-9), Eigen::Vector3d(1e-3, 2, 0)}});
  const std::vector<Aabbd> back = ReadBoxCsv(written, "written.csv");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].centre, Eigen::Vector3d(0.1, 1.0 / 3, -7e-9));  // 17 digits: exact
  test::ExpectInputError(
      [] {
        std::istringstream bad("1,2,3,0.5,-1,0.25\n");
        ReadBoxCsv(bad, "bad.csv");
      },
      "bad.csv", 1, "hy");
  std::istringstream nan("1,2,3,0.5,1,inf\n");
  EXPECT_THROW(ReadBoxCsv(nan, "nan.csv"), InputError);
  std::istringstream truncated("1,2,3,0.5,1\n");
  EXPECT_THROW(ReadBoxCsv(truncated, "t.csv"), InputError);
}

}  // namespace
}  // namespace rc
