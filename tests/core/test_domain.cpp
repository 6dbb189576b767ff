#include "ablmg/core/domain.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

using namespace ablmg;

namespace {
BoundaryLoop square(double x0, double y0, double s, bool ccw = true) {
  BoundaryLoop l;
  l.points = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
  if (!ccw) std::reverse(l.points.begin(), l.points.end());
  return l;
}
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) { return e.what(); }
  return "";
}
}  // namespace

TEST(Domain, AreaWithHoleAndOrientation) {
  const Domain d(square(0, 0, 4, /*ccw=*/false), {square(1, 1, 1, /*ccw=*/true)});
  EXPECT_DOUBLE_EQ(d.area(), 15.0);
  EXPECT_TRUE(d.contains({0.5, 0.5}));
  EXPECT_FALSE(d.contains({1.5, 1.5}));  // in the hole
  EXPECT_TRUE(d.contains({1.0, 1.5}));   // on the hole's boundary
  EXPECT_TRUE(d.contains({4.0, 2.0}));   // on the outer boundary
  EXPECT_FALSE(d.contains({4.0001, 2.0}));
  EXPECT_NEAR(d.distanceToBoundary({0.5, 2.0}), 0.5, 1e-15);
}

// Far from the origin the shoelace sum about (0, 0) cancels (a unit square at 10⁹ had area 0
// and was refused; at 10¹² its area was 1.3e8): the area and the orientation are exact there.
TEST(Domain, AreaFarFromTheOrigin) {
  for (double o : {1e5, 1e9, 1e12}) {
    const Domain d(square(o, o, 1, /*ccw=*/false), {square(o + 0.25, o + 0.25, 0.5)});
    EXPECT_DOUBLE_EQ(d.area(), 0.75) << "offset " << o;
    EXPECT_TRUE(d.contains({o + 0.1, o + 0.1}));
    EXPECT_FALSE(d.contains({o + 0.5, o + 0.5}));
  }
}

TEST(Domain, TagsFollowReorientation) {
  BoundaryLoop l = square(0, 0, 1, false);  // clockwise: (0,0) (0,1) (1,1) (1,0)
  l.tags = {3, 2, 1, 4};                    // top, right, bottom, left
  const Domain d(l);
  const auto& o = d.outer();
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec2 mid = 0.5 * (o.points[k] + o.points[(k + 1) % 4]);
    const int expect = mid.y() == 0 ? 1 : mid.x() == 1 ? 2 : mid.y() == 1 ? 3 : 4;
    EXPECT_EQ(o.tags[k], expect) << "segment " << k;
  }
}

TEST(Domain, ValidationNamesTheProblem) {
  BoundaryLoop bow;  // self-intersecting bow tie
  bow.points = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  EXPECT_NE(errorOf([&] { Domain d(bow); }).find("intersects"), std::string::npos);
  BoundaryLoop dup = square(0, 0, 1);
  dup.points.insert(dup.points.begin() + 1, dup.points[1]);
  EXPECT_NE(errorOf([&] { Domain d(dup); }).find("zero length"), std::string::npos);
  EXPECT_NE(errorOf([&] { Domain d(square(0, 0, 1), {square(5, 5, 1)}); }).find("outside"), std::string::npos);
  EXPECT_NE(errorOf([&] { Domain d(square(0, 0, 4), {square(3, 1, 2)}); }).find("intersects"), std::string::npos);
  BoundaryLoop two;
  two.points = {{0, 0}, {1, 0}};
  EXPECT_NE(errorOf([&] { Domain d(two); }).find("at least 3"), std::string::npos);
  BoundaryLoop nan = square(0, 0, 1);
  nan.points[2].x() = NAN;
  EXPECT_NE(errorOf([&] { Domain d(nan); }).find("non-finite"), std::string::npos);
}

TEST(Domain, DiskIsSmoothWithoutCorners) {
  const Domain d = Domain::disk({0, 0}, 10.0, 1024);
  EXPECT_TRUE(d.corners(0).empty());
  EXPECT_NEAR(d.area(), 100 * std::numbers::pi, 100 * std::numbers::pi * 1e-4);
  EXPECT_EQ(Domain::rectangle(0, 0, 1, 1).corners(0).size(), 4u);
}

// The crossing check visits the pairs of segments through a grid: on random polygons (most of them
// self-intersecting) it must report the same first bad pair as testing every pair.
TEST(Domain, ValidationReportsTheFirstCrossingOfAllPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(0, 1);
  int crossing = 0;
  for (int trial = 0; trial < 200; ++trial) {
    BoundaryLoop l;
    const int n = 3 + trial % 40;
    for (int k = 0; k < n; ++k) l.points.push_back({coord(rng), coord(rng)});
    double area = 0;
    for (int k = 0; k < n; ++k) area += cross(l.points[k], l.points[(k + 1) % n]);
    if (area <= 0) continue;  // counter-clockwise only, so the loop keeps its numbering
    std::string expect;
    for (int i = 0; i < n && expect.empty(); ++i)
      for (int j = i + 1; j < n && expect.empty(); ++j) {
        const Vec2 &a = l.points[i], &b = l.points[(i + 1) % n], &c = l.points[j], &d = l.points[(j + 1) % n];
        const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
        if (neighbours ? segmentsCross(a, b, c, d) : segmentsIntersect(a, b, c, d))
          expect = "segment " + std::to_string(i) + " intersects outer loop 0 segment " + std::to_string(j) + " ";
      }
    const std::string got = errorOf([&] { Domain dom(l); });
    if (expect.empty()) {
      EXPECT_EQ(got, "") << "trial " << trial;
    } else {
      ++crossing;
      EXPECT_NE(got.find(expect), std::string::npos)
          << "trial " << trial << ": expected '" << expect << "', got '" << got << "'";
    }
  }
  EXPECT_GT(crossing, 50);
}

// Thousands of segments on one vertical side (a boundary taken from a graded mesh) are checked,
// and a spike that touches the opposite side is found.
TEST(Domain, ValidationOfADenseVerticalSide) {
  BoundaryLoop l;
  const int m = 4000;
  l.points = {{0, 0}, {1, 0}};
  for (int k = 1; k < m; ++k) l.points.push_back({1, double(k) / m});
  l.points.push_back({1, 1});
  l.points.push_back({0, 1});
  for (int k = m - 1; k > 0; --k) l.points.push_back({0, double(k) / m});
  EXPECT_EQ(errorOf([&] { Domain d(l); }), "");
  l.points[2 + m / 2].x() = -0.5;  // a spike from the right side through the left one
  EXPECT_NE(errorOf([&] { Domain d(l); }).find("intersects"), std::string::npos);
}

// Extents that underflow or overflow the crossing check's cell size (a subnormal square, a square
// of side 2·10³⁰⁸): an error or a valid domain, never a NaN converted to a cell index (UBSan).
TEST(Domain, ValidationOfExtremeExtents) {
  const double tiny = std::numeric_limits<double>::denorm_min(), huge = 1e308;
  for (const double s : {tiny, 4 * tiny, huge}) {
    BoundaryLoop l;
    l.points = {{-s, -s}, {s, -s}, {s, s}, {-s, s}, {0, 0.5 * s}};  // the last point folds back inside
    EXPECT_NO_THROW(errorOf([&] { Domain d(l); })) << s;
  }
}
