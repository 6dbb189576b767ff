// Mirrors mesher/mesher.hpp: meshDomain's progress reports (MeshOptions::progress) come in
// stage order from the calling thread and do not change the mesh.
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
    if (std::string(p.stage) != "placement") EXPECT_GT(p.nodes, 0) << p.stage;
  int lastStep = -1;
  for (const auto& p : reports)  // placement steps, if reported, only grow
    if (p.step >= 0) {
      EXPECT_GE(p.step, lastStep);
      lastStep = p.step;
    }
}
