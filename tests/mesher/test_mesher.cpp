// Mirrors mesher/mesher.hpp: meshDomain's progress reports (MeshOptions::progress) come in
// stage order from the calling thread and do not change the mesh; addPartStats sums the parts.
#include "ablmg/mesher/mesher.hpp"

#include "ablmg/core/metric_field.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <thread>
#include <vector>

using namespace ablmg;
using namespace ablmg::mesher;

TEST(MeshDomain, ProgressReportsStagesInOrderAndLeavesTheMeshAlone) {
  const Domain disk = Domain::disk({0, 0}, 3);
  const ConstantMetricField metric(Metric2::fromSizes(0.5, 0.2, std::numbers::pi / 4));
  const MeshResult plain = meshDomain(disk, metric);

  MeshOptions o;
  std::vector<std::string> stages;
  std::vector<Progress> reports;
  const auto caller = std::this_thread::get_id();
  bool otherThread = false;
  o.progress = [&](const Progress& p) {
    if (stages.empty() || stages.back() != p.stage) stages.push_back(p.stage);
    reports.push_back(p);
    otherThread = otherThread || std::this_thread::get_id() != caller;
  };
  const MeshResult reported = meshDomain(disk, metric, o);

  EXPECT_EQ(reported.mesh.vertices, plain.mesh.vertices);
  EXPECT_EQ(reported.mesh.triangles, plain.mesh.triangles);
  EXPECT_FALSE(otherThread);
  ASSERT_GE(stages.size(), 3u);
  EXPECT_EQ(stages[0], "placement");
  EXPECT_EQ(stages[1], "connection");
  EXPECT_EQ(stages[2], "improve");
  for (const auto& p : reports)
    if (std::string(p.stage) != "placement") { EXPECT_GT(p.nodes, 0) << p.stage; }
  int lastStep = -1;
  for (const auto& p : reports)  // placement steps, if reported, only grow
    if (p.step >= 0) {
      EXPECT_GE(p.step, lastStep);
      lastStep = p.step;
    }
}

TEST(AddPartStats, CountsAndTimesAddUpWorstPartSetsStepsAndFlags) {
  MeshStats whole, part;
  whole.placement.finalNodes = 300;
  whole.placement.predictedNodes = 290;
  whole.placement.steps = 40;
  whole.placement.nearestInRange = 0.9;
  whole.placement.defectsLast = -1;
  whole.connect.repairedTriangles = 2;
  whole.improve.qMinAfter = 0.6;
  whole.secondsValidate = 0.25;
  part.placement.finalNodes = 100;
  part.placement.predictedNodes = 110;
  part.placement.steps = 70;
  part.placement.nearestInRange = 0.5;
  part.placement.defectsLast = 4;
  part.placement.qualityPlateau = true;
  part.connect.repairedTriangles = 3;
  part.improve.qMinAfter = 0.4;
  part.secondsValidate = 0.5;
  addPartStats(whole, part);
  EXPECT_EQ(whole.placement.finalNodes, 400);
  EXPECT_EQ(whole.placement.predictedNodes, 400);
  EXPECT_EQ(whole.placement.steps, 70);
  EXPECT_DOUBLE_EQ(whole.placement.nearestInRange, 0.8);  // (0.9·300 + 0.5·100) / 400
  EXPECT_EQ(whole.placement.defectsLast, 4);              // −1 (none) plus 4
  EXPECT_TRUE(whole.placement.qualityPlateau);
  EXPECT_EQ(whole.connect.repairedTriangles, 5);
  EXPECT_DOUBLE_EQ(whole.improve.qMinAfter, 0.4);
  EXPECT_DOUBLE_EQ(whole.secondsValidate, 0.75);
}
