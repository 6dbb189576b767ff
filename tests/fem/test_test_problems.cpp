// Tests of fem/test_problems.hpp: f = −Δu and ∇u checked by finite differences; parameters.
#include "ablmg/fem/test_problems.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ablmg;
using namespace ablmg::fem;

TEST(TestProblems, RightHandSideIsMinusLaplacianAndGradientMatches) {
  const std::vector<Vec2> points = {{0.31, 0.47}, {0.72, 0.18}, {0.55, 0.91}, {0.12, 0.66}, {0.5, 0.52}};
  for (const auto& name : problemNames()) {
    // Moderate parameters so that a centred difference with step 1e-4 resolves the solution.
    std::map<std::string, double> params;
    if (name == "peak") params["alpha"] = 20;
    if (name == "tanhlayer") params["epsilon"] = 0.1;
    if (name == "multiple") params = {{"alpha_p", 20}, {"alpha_w", 5}, {"epsilon", 0.3}};
    const TestProblem p = makeProblem(name, params);
    for (Vec2 x : points) {
      if (name == "lshape" || name == "reentrant" || name == "linesing" || name == "multiple")
        x = 2 * x - Vec2(1, 1) + Vec2(-0.05, 0.03);  // stays in the L, away from 0
      if (!p.domain.contains(x)) continue;
      const double h = 1e-4;
      const double u0 = p.u(x.x(), x.y());
      const double uxp = p.u(x.x() + h, x.y()), uxm = p.u(x.x() - h, x.y());
      const double uyp = p.u(x.x(), x.y() + h), uym = p.u(x.x(), x.y() - h);
      const double lap = (uxp + uxm + uyp + uym - 4 * u0) / (h * h);
      const double f = p.f(x.x(), x.y());
      EXPECT_NEAR(-lap, f, 1e-4 * (1 + std::abs(f))) << name << " at " << x.transpose();
      const Vec2 g = p.grad(x.x(), x.y());
      const Vec2 gfd((uxp - uxm) / (2 * h), (uyp - uym) / (2 * h));
      EXPECT_NEAR((g - gfd).norm(), 0.0, 1e-6 * (1 + g.norm())) << name << " at " << x.transpose();
    }
  }
}

TEST(TestProblems, DefaultsAndDomains) {
  const TestProblem w = makeProblem("wavefront");
  EXPECT_EQ(w.params.at("alpha"), 20);
  EXPECT_EQ(w.params.at("xc"), -0.05);
  EXPECT_EQ(w.params.at("r0"), 0.7);
  EXPECT_NEAR(w.u(0.7 * std::sqrt(0.5) - 0.05, 0.7 * std::sqrt(0.5) - 0.05), 0.0, 1e-14);  // on the front
  EXPECT_NEAR(makeProblem("lshape").domain.area(), 3.0, 1e-14);
  EXPECT_NEAR(makeProblem("peak").u(0.5, 0.5), 1.0, 0);
  EXPECT_EQ(makeProblem("wavefront", {{"alpha", 1000}}).params.at("alpha"), 1000);
  // L-shape: u = 0 on the two edges at the reentrant corner (θ = 0 and θ = 3π/2).
  const TestProblem l = makeProblem("lshape");
  EXPECT_NEAR(l.u(0.5, 0), 0.0, 1e-15);
  EXPECT_NEAR(l.u(0, -0.5), 0.0, 1e-15);
  EXPECT_NEAR(l.u(-0.5, 0), std::pow(0.5, 2.0 / 3) * std::sin(2 * M_PI / 3), 1e-14);
}

TEST(TestProblems, ReentrantCornerForSeveralAngles) {
  // ω = 3π/2 is the L-shape (same domain, tags and solution); 5π/4 and 7π/4 cut the square's
  // corner off at (−1,−1) and (1,−1): areas 2.5 and 3.5. u = 0 on both edges at the corner.
  const TestProblem l = makeProblem("lshape"), r = makeProblem("reentrant", {{"omega", 1.5 * M_PI}});
  ASSERT_EQ(r.domain.outer().points.size(), l.domain.outer().points.size());
  for (std::size_t k = 0; k < l.domain.outer().points.size(); ++k) {
    EXPECT_EQ(r.domain.outer().points[k], l.domain.outer().points[k]) << k;
    EXPECT_EQ(r.domain.outer().tags[k], l.domain.outer().tags[k]) << k;
  }
  EXPECT_NEAR(r.u(-0.3, 0.4), l.u(-0.3, 0.4), 1e-15);
  for (const auto& [omega, area] : {std::pair{1.25 * M_PI, 2.5}, std::pair{1.75 * M_PI, 3.5}}) {
    const TestProblem p = makeProblem("reentrant", {{"omega", omega}});
    EXPECT_NEAR(p.domain.area(), area, 1e-12) << omega;
    EXPECT_NEAR(p.u(0.5, 0), 0.0, 1e-15);
    EXPECT_NEAR(p.u(0.5 * std::cos(omega), 0.5 * std::sin(omega)), 0.0, 1e-14) << omega;
    EXPECT_GT(p.u(-0.5, 0.1), 0.0);
  }
  EXPECT_EQ(makeProblem("reentrant").params.at("omega"), 1.75 * M_PI);
  const TestProblem slit = makeProblem("reentrant", {{"omega", 2 * M_PI}});  // the slit: a zero-width gap
  EXPECT_TRUE(slit.domain.hasSlits());
  EXPECT_NEAR(slit.domain.area(), 4.0, 1e-15);
  EXPECT_NEAR(slit.u(0.25, 1e-300), 0.0, 1e-14);  // u = 0 on both lips
  EXPECT_NEAR(slit.u(0.25, -1e-300), 0.0, 1e-14);
  EXPECT_NEAR(slit.u(-0.25, 0), 0.5, 1e-14);  // sqrt(r) at θ = π
  EXPECT_THROW(makeProblem("reentrant", {{"omega", 2 * M_PI + 1e-6}}), InputError);
  EXPECT_THROW(makeProblem("reentrant", {{"omega", 3.0}}), InputError);
}

TEST(TestProblems, CornerSolutionIsContinuousAcrossRoundOffBelowTheEdgeThetaZero) {
  // A point of the edge θ = 0 computed with y = −1e−17 (round-off) is on the edge, not at θ ≈ 2π
  // of the excluded sector: u ≈ 0 there and ∇u as just above the edge.
  for (const auto& [name, params] : {std::pair<std::string, std::map<std::string, double>>{"lshape", {}},
                                     {"reentrant", {{"omega", 1.25 * M_PI}}},
                                     {"reentrant", {}},
                                     {"multiple", {{"alpha_p", 20}, {"alpha_w", 5}, {"epsilon", 0.3}}}}) {
    const TestProblem p = makeProblem(name, params);
    for (const double x : {1e-6, 0.3, 0.9}) {
      EXPECT_NEAR(p.u(x, -1e-17), p.u(x, 0.0), 1e-12) << name << " x " << x;
      EXPECT_NEAR((p.grad(x, -1e-17) - p.grad(x, 1e-17)).norm(), 0.0, 1e-9 * p.grad(x, 1e-17).norm()) << name;
    }
    // Just past the other edge θ = ω, likewise.
    const double omega = name == "reentrant" ? p.params.at("omega") : 1.5 * M_PI, t = omega + 1e-15;
    EXPECT_NEAR(p.u(0.5 * std::cos(t), 0.5 * std::sin(t)), p.u(0.5 * std::cos(omega), 0.5 * std::sin(omega)), 1e-12)
        << name;
  }
}

TEST(TestProblems, LineSingularityAndMultipleDifficulties) {
  const TestProblem s = makeProblem("linesing");
  EXPECT_NEAR(s.domain.area(), 4.0, 1e-14);
  // Left of the line x = β(y + 1) u is cos(πy/2); right of it the singular term adds s^α.
  EXPECT_NEAR(s.u(0.0, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(s.u(1.0, 0.0), 1.0 + std::pow(0.4, 2.5), 1e-14);
  EXPECT_THROW(makeProblem("linesing", {{"alpha", 1.0}}), InputError);
  const TestProblem m = makeProblem("multiple");
  EXPECT_NEAR(m.domain.area(), 3.0, 1e-14);
  // At the peak's centre: the corner term + 1 + the front + the layer.
  const double xp = -std::sqrt(5.0) / 4, yp = -0.25;
  const double r = std::hypot(xp, yp), th = std::atan2(yp, xp) + 2 * M_PI;
  const double expect = std::pow(r, 2.0 / 3) * std::sin(2 * th / 3) + 1 +
                        std::atan(200 * (std::hypot(xp, yp + 0.75) - 0.75)) + std::exp(-(1 + yp) / 0.01);
  EXPECT_NEAR(m.u(xp, yp), expect, 1e-13);
  EXPECT_THROW(makeProblem("multiple", {{"epsilon", 0}}), InputError);
}

TEST(TestProblems, BadNamesAndParametersAreInputErrorsListingTheValidOnes) {
  try {
    makeProblem("wavefrnt");
    FAIL();
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("wavefront"), std::string::npos) << e.what(); }
  try {
    makeProblem("wavefront", {{"eps", 1}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("r0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(makeProblem("lshape", {{"alpha", 1}}), InputError);
  EXPECT_THROW(makeProblem("tanhlayer", {{"epsilon", 0}}), InputError);
}
