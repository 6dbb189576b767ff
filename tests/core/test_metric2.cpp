#include "ablmg/core/error.hpp"
#include "ablmg/core/metric2.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace ablmg;

TEST(Metric2, SizesAngleRoundTrip) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> h(1e-3, 10.0), th(0.0, std::numbers::pi);
  for (int k = 0; k < 200; ++k) {
    double h1 = h(rng), h2 = h(rng), t = th(rng);
    if (h1 < h2) std::swap(h1, h2);
    if (h1 / h2 < 1.01) continue;  // angle is ill-defined for near-isotropic tensors
    const Metric2 m = Metric2::fromSizes(h1, h2, t);
    const MetricEigen e = m.eigen();
    EXPECT_NEAR(e.h1 / h1, 1.0, 1e-9);
    EXPECT_NEAR(e.h2 / h2, 1.0, 1e-9);
    const double dt = std::remainder(e.theta - t, std::numbers::pi);
    EXPECT_NEAR(dt, 0.0, 1e-7);
    const Metric2 back = Metric2::fromSizes(e.h1, e.h2, e.theta);
    EXPECT_NEAR(back.m11(), m.m11(), 1e-9 * std::abs(m.m11()));
    EXPECT_NEAR(back.m12(), m.m12(), 1e-9 * (std::abs(m.m11()) + std::abs(m.m22())));
  }
}

TEST(Metric2, LengthAlongEigenvectorIsOneOverH) {
  const double h1 = 0.5, h2 = 0.2, t = std::numbers::pi / 4;
  const Metric2 m = Metric2::fromSizes(h1, h2, t);
  const Vec2 e1(std::cos(t), std::sin(t)), e2(-std::sin(t), std::cos(t));
  EXPECT_NEAR(m.length(e1), 1.0 / h1, 1e-12);
  EXPECT_NEAR(m.length(e2), 1.0 / h2, 1e-12);
  EXPECT_NEAR(m.length(h1 * e1), 1.0, 1e-12);
}

TEST(Metric2, EllipseRadiusIsTheSemiAxisAlongEigenvectors) {
  const Metric2 m = Metric2::fromSizes(3.0, 0.5, 0.3);
  EXPECT_NEAR(m.ellipseRadius(Vec2(std::cos(0.3), std::sin(0.3))), 3.0, 1e-12);
  EXPECT_NEAR(m.ellipseRadius(Vec2(-std::sin(0.3), std::cos(0.3)) * 17.0), 0.5, 1e-12);
  // in any direction the boundary point r·d/|d| has unit metric length
  const Vec2 d(0.7, -1.9);
  EXPECT_NEAR(m.length(m.ellipseRadius(d) * d.normalized()), 1.0, 1e-12);
}

TEST(Metric2, RejectsNonSpdAndNonFinite) {
  EXPECT_THROW(Metric2::fromTensor(1, 2, 1), InputError);
  EXPECT_THROW(Metric2::fromTensor(-1, 0, 1), InputError);
  EXPECT_THROW(Metric2::fromTensor(NAN, 0, 1), InputError);
  EXPECT_THROW(Metric2::fromSizes(0.1, -0.1, 0), InputError);
  EXPECT_THROW(Metric2::fromSizes(INFINITY, 1, 0), InputError);
  try {
    Metric2::fromTensor(1, 2, 1, "nonspd.sol:12: vertex 7");
    FAIL();
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("nonspd.sol:12"), std::string::npos); }
}

TEST(Metric2, LogEuclideanMeanReproducesConstantAndStaysSpd) {
  const Metric2 a = Metric2::fromSizes(2.0, 0.01, 1.0);
  std::vector<Metric2> same{a, a, a};
  std::vector<double> w{0.2, 0.3, 0.5};
  const Metric2 m = logEuclideanMean(same, w);
  EXPECT_DOUBLE_EQ(m.m11(), a.m11());
  EXPECT_DOUBLE_EQ(m.m22(), a.m22());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> h(1e-4, 1e2), th(0, 3.2), u(0, 1);
  for (int k = 0; k < 500; ++k) {
    std::vector<Metric2> ms{Metric2::fromSizes(h(rng), h(rng), th(rng)), Metric2::fromSizes(h(rng), h(rng), th(rng)),
                            Metric2::fromSizes(h(rng), h(rng), th(rng))};
    std::vector<double> ww{u(rng), u(rng), u(rng) + 1e-3};
    EXPECT_TRUE(logEuclideanMean(ms, ww).isSpd());
  }
  // interpolating between isotropic sizes gives the geometric mean of the sizes
  std::vector<Metric2> iso{Metric2::isotropic(1.0), Metric2::isotropic(0.01)};
  std::vector<double> half{0.5, 0.5};
  EXPECT_NEAR(logEuclideanMean(iso, half).eigen().h1, 0.1, 1e-12);
}

TEST(Metric2, IntersectionTakesTheSmallerSizeInEveryDirection) {
  const Metric2 a = Metric2::fromSizes(1.0, 0.1, 0.0), b = Metric2::fromSizes(1.0, 0.1, std::numbers::pi / 2);
  const Metric2 c = intersect(a, b);
  EXPECT_NEAR(c.eigen().h1, 0.1, 1e-12);
  EXPECT_NEAR(c.eigen().h2, 0.1, 1e-12);
  const Metric2 d = intersect(a, a);
  EXPECT_NEAR(d.m11(), a.m11(), 1e-9);
  EXPECT_NEAR(d.m22(), a.m22(), 1e-9);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> h(1e-2, 1e1), th(0, 3.2), ang(0, 6.3);
  for (int k = 0; k < 200; ++k) {
    const Metric2 x = Metric2::fromSizes(h(rng), h(rng), th(rng)), y = Metric2::fromSizes(h(rng), h(rng), th(rng));
    const Metric2 z = intersect(x, y), z2 = intersect(y, x);
    EXPECT_NEAR(z.m11(), z2.m11(), 1e-8 * z.m11());
    const Vec2 v(std::cos(ang(rng)), std::sin(ang(rng)));
    EXPECT_GE(z.length(v) * (1 + 1e-9), std::max(x.length(v), y.length(v)));
  }
}

TEST(Metric2, EdgeLengthOfConstantMetricIsEquation3) {
  const Metric2 m = Metric2::fromSizes(0.5, 0.2, 0.7);
  const Vec2 a(1, 2), b(1.3, 1.6);
  EXPECT_NEAR(edgeLength(a, m, b, m), m.length(b - a), 1e-12);
  // sizes h and 2h at the ends: exact ∫ dt / h(t) with h linear = ln 2 / h
  const Metric2 m1 = Metric2::isotropic(1.0), m2 = Metric2::isotropic(2.0);
  EXPECT_NEAR(edgeLength(Vec2(0, 0), m1, Vec2(1, 0), m2), std::log(2.0), 1e-12);
}

TEST(Metric2, ExpOfLogIsTheIdentityUpToAnisotropy1e5) {
  // expm is a closed form (cosh/sinh of the traceless part), logm an eigen-decomposition:
  // the two must agree on sizes and directions, from isotropic tensors (δ = 0 branch) to a
  // size ratio of 1e5 (eigenvalue ratio 1e10, the hostile-input bound).
  for (double ratio : {1.0, 1.0 + 1e-9, 2.0, 50.0, 1e5})
    for (double theta : {0.0, 0.3, 1.2, 2.9}) {
      const Metric2 m = Metric2::fromSizes(0.7 * ratio, 0.7, theta);
      const Metric2 r = m.logm().expm();
      const MetricEigen a = m.eigen(), b = r.eigen();
      // The entries m11, m12, m22 of a tensor with eigenvalue ratio ratio² carry its small
      // eigenvalue only to ≈ ratio² · 1e-16 (relative), whatever computed them.
      const double tol = std::max(1e-9, 1e-15 * ratio * ratio);
      EXPECT_NEAR(b.h1 / a.h1, 1.0, tol) << ratio << " " << theta;
      EXPECT_NEAR(b.h2 / a.h2, 1.0, tol) << ratio << " " << theta;
      if (ratio > 1.01) { EXPECT_NEAR(std::sin(b.theta - a.theta), 0.0, 1e-9) << ratio << " " << theta; }
      EXPECT_TRUE(r.isSpd());
    }
  // exp of a diagonal log: the exponentials of the entries.
  const Metric2 d = Metric2::raw(std::log(4.0), 0.0, std::log(0.25)).expm();
  EXPECT_NEAR(d.m11(), 4.0, 1e-14);
  EXPECT_NEAR(d.m22(), 0.25, 1e-15);
  EXPECT_EQ(d.m12(), 0.0);
}
