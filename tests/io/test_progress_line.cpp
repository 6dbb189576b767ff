// Tests of cli/progress_line.hpp (compiled into test_io by tests/cli/io_cli.cmake): the text of
// a report, and a line that stays silent when stderr is not a terminal (as under CTest).
#include "ablmg/cli/progress_line.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

using namespace ablmg;
using namespace ablmg::cli;

TEST(ProgressLine, FormatsStageStepResidualNodesAndTime) {
  Progress p{.stage = "placement", .step = 120, .residual = 0.0342, .target = 0.01, .nodes = 41944};
  EXPECT_EQ(ProgressLine::format("remesh", p, 2.34),
            "ablmg remesh: placement, step 120, residual 0.0342 / 0.01, 41944 nodes, 2.3 s");
  p.cycle = 2;
  p.cycles = 8;
  EXPECT_EQ(ProgressLine::format("adapt", p, 12.0),
            "ablmg adapt: cycle 3/8, placement, step 120, residual 0.0342 / 0.01, 41944 nodes, 12.0 s");
  EXPECT_EQ(ProgressLine::format("mesh", {.stage = "connection", .nodes = 900}, 0.5),
            "ablmg mesh: connection, 900 vertices, 0.5 s");
  EXPECT_EQ(ProgressLine::format("remesh", {.stage = "read"}, 0.0), "ablmg remesh: read, 0.0 s");
}

TEST(ProgressLine, OffWhenStderrIsNotATerminalOrVerbosityIsZero) {
  ProgressLine quiet("mesh", 0);
  EXPECT_FALSE(quiet.enabled());
  EXPECT_FALSE(bool(quiet.callback()));
  ProgressLine line("mesh", 1);
  EXPECT_EQ(line.enabled(), ::isatty(STDERR_FILENO) == 1);
  if (!line.enabled()) { EXPECT_FALSE(bool(line.callback())); }
}
