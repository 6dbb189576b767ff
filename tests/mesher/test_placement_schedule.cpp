#include "ablmg/mesher/placement_schedule.hpp"

#include <gtest/gtest.h>

using namespace ablmg::mesher;

TEST(PopulationSchedule, SettlesAfterTwoQuietPassesOrAtSixtyPercentOfTheSteps) {
  PopulationSchedule s(1000, 2000);
  EXPECT_TRUE(s.passDue(10));
  EXPECT_FALSE(s.passDue(15));
  s.afterPass(50, 10000);  // 0.5 %: busy
  EXPECT_FALSE(s.nearlySettled());
  s.afterPass(1, 10000);  // 1 in 10⁴: quiet
  EXPECT_TRUE(s.nearlySettled());
  EXPECT_FALSE(s.settled());
  s.afterPass(3, 10000);  // not quiet: the count restarts
  s.afterPass(0, 10000);
  EXPECT_FALSE(s.settled());
  s.afterPass(1, 10000);
  EXPECT_TRUE(s.settled());
  EXPECT_FALSE(s.passDue(100));

  PopulationSchedule late(1000, 2000);
  late.afterStep(1199);
  EXPECT_FALSE(late.settled());
  late.afterStep(1200);
  EXPECT_TRUE(late.settled());
}

TEST(PopulationSchedule, SteeringUpEndsWhenTheCountStopsGrowing) {
  PopulationSchedule s(1000, 2000);
  const int window = s.options().steerWindow;
  for (int k = 0; k <= window; ++k) {
    EXPECT_TRUE(s.options().steerUp) << k;
    s.afterPass(100, 900 + (k < 2 ? 10 * k : 10));  // grows twice, then stays
  }
  EXPECT_TRUE(s.options().steerUp);  // the last window still holds growth
  s.afterPass(100, 910);
  s.afterPass(100, 910);
  EXPECT_FALSE(s.options().steerUp);
}

TEST(PopulationSchedule, SteeringUpEndsWhenTheCountOnlyCreeps) {
  PopulationSchedule s(100000, 2000);
  const int window = s.options().steerWindow;
  const double creep = 0.5 * s.options().steerMinGrowth / window;  // per pass: half the tolerance over the window
  double count = 95000;
  for (int k = 0; k < window; ++k) {
    s.afterPass(450, int(count));  // a churn of 0.45 % that nets +creep
    EXPECT_TRUE(s.options().steerUp) << k;
    count *= 1 + creep;
  }
  s.afterPass(450, int(count));
  EXPECT_FALSE(s.options().steerUp);

  PopulationSchedule growing(100000, 2000);
  count = 90000;
  for (int k = 0; k <= 2 * window; ++k) {
    growing.afterPass(450, int(count));
    count *= 1 + 2 * growing.options().steerMinGrowth / window;  // twice the tolerance over the window
  }
  EXPECT_TRUE(growing.options().steerUp);
}

TEST(DefectSchedule, PassesComeEveryStepsApartUntilStopped) {
  DefectSchedule d(2, 20);
  EXPECT_TRUE(d.due(5));
  d.started(5);
  EXPECT_FALSE(d.due(24));
  EXPECT_TRUE(d.due(25));
  d.started(25);
  EXPECT_FALSE(d.left());
  EXPECT_FALSE(d.due(100));
  DefectSchedule e(6, 20);
  e.stop();
  EXPECT_FALSE(e.due(0));
}

TEST(StallRule, StallsWhenTheResidualHasNotHalvedWithinTheWindow) {
  StallRule r(3);
  EXPECT_FALSE(r.stalled(0, 1.0));  // first mark
  EXPECT_FALSE(r.stalled(1, 0.6));
  EXPECT_FALSE(r.stalled(2, 0.4));  // halved: new mark at step 2
  EXPECT_EQ(r.markStep(), 2);
  EXPECT_FALSE(r.stalled(4, 0.3));
  EXPECT_TRUE(r.stalled(5, 0.3));
  r.restart();
  EXPECT_EQ(r.markStep(), -1);
  EXPECT_FALSE(r.stalled(6, 0.3));
  EXPECT_FALSE(StallRule(0).enabled());
}

TEST(QualityPlateau, ReachedWhenTheShareGainsLessThanTheGainOverTheWindow) {
  QualityPlateau q(20, 0.01);  // two samples back
  EXPECT_TRUE(q.sampleDue(30));
  EXPECT_FALSE(q.sampleDue(35));
  EXPECT_FALSE(q.reached(0.80, true, 100));
  EXPECT_FALSE(q.reached(0.85, true, 100));
  EXPECT_FALSE(q.reached(0.86, true, 100));    // +0.06 over the window
  EXPECT_TRUE(q.reached(0.855, true, 100));    // +0.005 over the last two samples
  EXPECT_FALSE(q.reached(0.866, false, 100));  // population still busy
  EXPECT_FALSE(q.reached(0.867, true, 10));    // the residual halved 10 steps ago
  EXPECT_FALSE(QualityPlateau(0, 0.01).sampleDue(0));
}

TEST(RelaxBeforeStop, AnEarlyStopWaitsForTheRelaxationAfterTheLastEdit) {
  RelaxBeforeStop r(10);
  EXPECT_TRUE(r.allowsStop(3));  // no edit yet
  r.edited(40);
  EXPECT_FALSE(r.allowsStop(45));
  EXPECT_TRUE(r.relaxing());
  EXPECT_FALSE(r.over(49));
  EXPECT_TRUE(r.over(50));
  RelaxBeforeStop s(10);
  s.edited(40);
  EXPECT_TRUE(s.allowsStop(50));
  EXPECT_FALSE(s.relaxing());
}
