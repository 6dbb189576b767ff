#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace ablmg;
__extension__ typedef __int128 i128;

TEST(Predicates, Orient2dBasicSigns) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {2, 2}), 0);
}

TEST(Predicates, Orient2dExactOnNearlyCollinearPoints) {
  // Points on the line y = x shifted by one ulp: the naive formula gets many of these wrong.
  const Vec2 a(0.5, 0.5), c(12.0, 12.0);
  int wrongNaive = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      const Vec2 b(std::nextafter(0.5, 1.0) + i * std::ldexp(1.0, -53), 0.5 + j * std::ldexp(1.0, -53));
      const int exact = orient2d(a, b, c);
      // exact: det = 11.5 (bx − by) = 11.5 (i + 1 − j) ulp
      EXPECT_EQ(exact, (i + 1 > j) - (i + 1 < j));
      EXPECT_EQ(exact, -orient2d(b, a, c));
      EXPECT_EQ(exact, orient2d(b, c, a));
      EXPECT_EQ(exact, orient2d(c, a, b));
      const double naive = (a.x() - c.x()) * (b.y() - c.y()) - (a.y() - c.y()) * (b.x() - c.x());
      if ((naive > 0) - (naive < 0) != exact) ++wrongNaive;
    }
  }
  // b = (0.5 + (i+1)u, 0.5 + j u): exactly collinear iff i+1 == j
  EXPECT_EQ(orient2d(a, Vec2(0.5 + 3 * std::ldexp(1.0, -53), 0.5 + 3 * std::ldexp(1.0, -53)), c), 0);
  EXPECT_GT(wrongNaive, 0);  // the test is hard enough to matter
}

TEST(Predicates, Orient2dMatchesIntegerArithmetic) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<long> coord(-(1L << 25), 1L << 25);
  for (int k = 0; k < 20000; ++k) {
    long p[6];
    for (auto& x : p) x = coord(rng);
    if (k % 3 == 0) {  // force near-collinearity
      p[4] = p[0] + 2 * (p[2] - p[0]) + (k % 2);
      p[5] = p[1] + 2 * (p[3] - p[1]);
    }
    const i128 det = (i128)(p[2] - p[0]) * (p[5] - p[1]) - (i128)(p[3] - p[1]) * (p[4] - p[0]);
    const int expect = (det > 0) - (det < 0);
    const double s = std::ldexp(1.0, -20);  // exact scaling to non-integers
    EXPECT_EQ(orient2d(Vec2(p[0] * s, p[1] * s), Vec2(p[2] * s, p[3] * s), Vec2(p[4] * s, p[5] * s)), expect);
  }
}

TEST(Predicates, SegmentsCrossCases) {
  EXPECT_TRUE(segmentsCross({0, 0}, {1, 1}, {0, 1}, {1, 0}));   // X
  EXPECT_FALSE(segmentsCross({0, 0}, {1, 1}, {1, 1}, {2, 0}));  // share an endpoint
  EXPECT_TRUE(segmentsCross({0, 0}, {2, 0}, {1, 0}, {1, 1}));   // T-junction
  EXPECT_TRUE(segmentsCross({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // collinear overlap
  EXPECT_FALSE(segmentsCross({0, 0}, {1, 0}, {1, 0}, {2, 0}));  // collinear, touching at an end
  EXPECT_FALSE(segmentsCross({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear, apart
  EXPECT_FALSE(segmentsCross({0, 0}, {1, 0}, {0, 1}, {1, 1}));  // parallel
  EXPECT_TRUE(segmentsIntersect({0, 0}, {1, 1}, {1, 1}, {2, 0}));
}
