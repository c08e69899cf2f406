// The MoveBot robot, its obstacle file and its scene: forward kinematics
// against hand-computed frames, the file reader's errors, and the scene's
// kernel answers against the exact reference for axis-aligned and rotated
// obstacles.
#include <cmath>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "backends/calibration/sact_kernel_record.h"
#include "common/input_error.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "workloads/movebot/arm_scene.h"
#include "workloads/movebot/locobot_arm.h"
#include "workloads/movebot/obstacle_file.h"

namespace rc {
namespace {

TEST(LocobotArm, ZeroConfigurationFramesFollowTheLinkTranslations) {
  const LocobotArm arm;
  const auto f = arm.ForwardKinematics({0, 0, 0, 0, 0});
  EXPECT_TRUE(f[0].translation().isApprox(Eigen::Vector3d(0.08, 0, 0.159)));
  EXPECT_TRUE(f[1].translation().isApprox(Eigen::Vector3d(0.08, 0, 0.20025)));
  EXPECT_TRUE(f[2].translation().isApprox(Eigen::Vector3d(0.13, 0, 0.40025)));
  EXPECT_TRUE(f[3].translation().isApprox(Eigen::Vector3d(0.3302, 0, 0.40025)));
  const auto links = arm.LinkObbs({0, 0, 0, 0, 0});
  EXPECT_TRUE(links[0].centre.isApprox(Eigen::Vector3d(0.08, 0, 0.29025)));
  EXPECT_TRUE(links[0].half.isApprox(Eigen::Vector3d(0.025, 0.025, 0.125)));
  EXPECT_TRUE(links[0].axes.isApprox(Eigen::Matrix3d::Identity()));
}

TEST(LocobotArm, WaistTurnsAboutZAndShoulderTipsTheArmForward) {
  const LocobotArm arm;
  // Waist +pi/2: the elbow frame, 0.05 m ahead of the shoulder, swings to +y.
  auto f = arm.ForwardKinematics({M_PI / 2, 0, 0, 0, 0});
  EXPECT_TRUE(f[2].translation().isApprox(Eigen::Vector3d(0.08, 0.05, 0.40025), 1e-12));
  // Shoulder +pi/2 about y: the upper arm's +z turns to +x.
  f = arm.ForwardKinematics({0, M_PI / 2, 0, 0, 0});
  EXPECT_TRUE(f[2].translation().isApprox(Eigen::Vector3d(0.28, 0, 0.15025), 1e-12));
  // Wrist roll about -x: +y turns to -z.
  f = arm.ForwardKinematics({0, 0, 0, 0, M_PI / 2});
  EXPECT_NEAR((f[4].linear() * Eigen::Vector3d::UnitY()).z(), -1.0, 1e-12);
}

TEST(LocobotArm, LinkAxesStayOrthonormalAndLimitsAreChecked) {
  const LocobotArm arm;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-M_PI / 2, M_PI / 2);
  for (int i = 0; i < 100; ++i) {
    ArmConfiguration q;
    for (double& v : q) v = u(rng);
    EXPECT_TRUE(arm.WithinLimits(q));
    for (const Obbd& o : arm.LinkObbs(q)) {
      EXPECT_TRUE((o.axes.transpose() * o.axes).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
      EXPECT_NEAR(o.axes.determinant(), 1.0, 1e-12);
    }
  }
  std::string why;
  EXPECT_FALSE(arm.WithinLimits({0, 0, 1.6, 0, 0}, &why));
  EXPECT_NE(why.find("joint 3"), std::string::npos) << why;
  EXPECT_FALSE(arm.WithinLimits({0, 0, 0, 0, std::nan("")}));
}

TEST(ObstacleFile, ReadsRowildFormatWithCommentsAndRotations) {
  std::istringstream in(
      "# a comment\n\n0, 0, 0, 1, 2, 3, 0.2, 0.4, 0.6\n0.0, 0.0, 1.5707963267948966, 0, 0, 0, 1, 1, 0\n");
  const auto obstacles = ReadObstacleFile(in, "obs.txt");
  ASSERT_EQ(obstacles.size(), 2u);
  EXPECT_EQ(obstacles[0].line, 3);
  EXPECT_TRUE(obstacles[0].box.centre.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(obstacles[0].box.half.isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  EXPECT_TRUE(obstacles[0].box.axes == Eigen::Matrix3d::Identity());
  // Yaw pi/2: the box's x axis points along world y.
  EXPECT_TRUE((obstacles[1].box.axes.col(0)).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

void ExpectInputError(const std::string& text, long line, const std::string& field) {
  test::ExpectInputError(
      [&] {
        std::istringstream in(text);
        ReadObstacleFile(in, "bad.txt");
      },
      "bad.txt", line, field);
}

TEST(ObstacleFile, MalformedLinesNameLineAndField) {
  ExpectInputError("# c\n0, 0, 0, 1, 2, 3, 0.2, 0.4\n", 2, "dimZ");         // the first missing field
  ExpectInputError("0, 0, 0, 1, 2, 3, 0.2, 0.4, 0.6, 7\n", 1, "field 10");  // the first extra one
  ExpectInputError("0, 0, 0, 0x1p0, 2, 3, 0.2, 0.4, 0.6\n", 1, "x");        // hexadecimal
  ExpectInputError("0, 0, 0, 1, 2, 3, 0.2, 0.4, 0.6\n0, 0, 0, x, 2, 3, 0.2, 0.4, 0.6\n", 2, "x");
  ExpectInputError("0, 0, 0, 1, 2, 3, 0.2, -0.4, 0.6\n", 1, "dimY");
  ExpectInputError("0, 0, nan, 1, 2, 3, 0.2, 0.4, 0.6\n", 1, "yaw");
  ExpectInputError("0, 0, 0, 1, 2, 3, 0.2, 0.4, \n", 1, "dimZ");
  EXPECT_THROW(ReadObstacleFile("/nonexistent/obs.txt"), InputError);
}

// A file with no obstacle would plan in an empty scene and exit 0: more
// likely a wrong or truncated file than an intended empty scene.
TEST(ObstacleFile, AFileWithoutObstaclesIsRefused) {
  for (const char* text : {"", "\n\n", "# roll, pitch, yaw, x, y, z, dimX, dimY, dimZ\n"})
    ExpectInputError(text, 0, "obstacles");
  test::TempDir dir;
  const std::string folder = dir.path().string();
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadObstacleFile(folder); }, 0, "", "is a directory, not a file"));
}

TEST(ObstacleFile, AByteOrderMarkIsSkipped) {
  std::istringstream in(
      "\xEF\xBB\xBF"
      "0, 0, 0, 1, 2, 3, 0.2, 0.4, 0.6\n");
  ASSERT_EQ(ReadObstacleFile(in, "obs.txt").size(), 1u);
  std::istringstream comment("\xEF\xBB\xBF# header\n0, 0, 0, 1, 2, 3, 0.2, 0.4, 0.6\n");
  ASSERT_EQ(ReadObstacleFile(comment, "obs.txt").size(), 1u);
}

TEST(ObstacleFile, SharedLocobotSceneIsAxisAligned) {
  RC_REQUIRE_SHARED_DATA("movebot/locobot_obs.txt");
  const auto obstacles = ReadObstacleFile(test::SharedDataPath("movebot/locobot_obs.txt"));
  ASSERT_EQ(obstacles.size(), 8u);
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  ASSERT_EQ(scene.frames().size(), 1u);
  EXPECT_TRUE(scene.frames()[0].identity);
  EXPECT_EQ(scene.box_count(), 8u);
}

// The exact answer: the link box in the obstacle's frame, the LP reference.
bool ExactCollides(const Obbd& link, const std::vector<Obstacle>& obstacles) {
  for (const Obstacle& o : obstacles) {
    Obbd local;
    local.centre = o.box.axes.transpose() * (link.centre - o.box.centre);
    local.axes = o.box.axes.transpose() * link.axes;
    local.half = link.half;
    Aabbd box;
    box.half = o.box.half;
    if (ExactObbAabbOverlap(local, box).overlaps()) return true;
  }
  return false;
}

TEST(ArmScene, RotatedAndAlignedObstaclesAnswerAsTheExactReference) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-0.6, 0.6), size(0.02, 0.3), angle(-M_PI, M_PI);
  std::vector<Obstacle> obstacles;
  for (int i = 0; i < 12; ++i) {
    Obstacle o;
    o.box.centre = {pos(rng), pos(rng), pos(rng) + 0.3};
    o.box.half = {size(rng), size(rng), size(rng)};
    if (i % 3 != 0)  // two thirds rotated, a third axis-aligned; two share a rotation
      o.box.axes =
          (Eigen::AngleAxisd(i % 3 == 1 ? 0.7 : angle(rng), Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
    obstacles.push_back(o);
  }
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  EXPECT_GT(scene.frames().size(), 2u);
  const LocobotArm arm;
  std::uniform_real_distribution<double> joint(-M_PI / 2, M_PI / 2);
  std::vector<Obbd> obbs;
  for (int i = 0; i < 200; ++i) {
    ArmConfiguration q;
    for (double& v : q) v = joint(rng);
    for (const Obbd& o : arm.LinkObbs(q)) obbs.push_back(o);
  }
  CollisionBatch batch = scene.NewBatch();
  const std::vector<bool> kernel = scene.Collide(obbs, {}, batch);
  int collisions = 0;
  for (std::size_t i = 0; i < obbs.size(); ++i) {
    EXPECT_EQ(kernel[i], ExactCollides(obbs[i], obstacles)) << "link OBB " << i;
    collisions += kernel[i];
  }
  EXPECT_GT(collisions, 20);  // the test sees both answers
  EXPECT_LT(collisions, static_cast<int>(obbs.size()) - 20);
  // One query per OBB and frame, every fetch inside the scene's node region.
  EXPECT_EQ(batch.query_count(), obbs.size() * scene.frames().size());
  const KernelRecord record = SactKernelRecord(batch);  // validates addresses
  EXPECT_EQ(record.query_count(), batch.query_count());
}

TEST(ArmScene, EmptySceneSendsNoQuery) {
  const ArmScene scene = ArmScene::FromObstacles({});
  EXPECT_TRUE(scene.empty());
  CollisionBatch batch = scene.NewBatch();
  const LocobotArm arm;
  const auto links = arm.LinkObbs({0, 0, 0, 0, 0});
  const auto hits = scene.Collide({links.begin(), links.end()}, {}, batch);
  for (bool h : hits) EXPECT_FALSE(h);
  EXPECT_EQ(batch.query_count(), 0u);
}

}  // namespace
}  // namespace rc
