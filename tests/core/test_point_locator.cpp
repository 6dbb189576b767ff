#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/core/point_locator.hpp"
#include "ablmg/core/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace ablmg;

namespace {
/// n×n grid of the unit square, diagonals alternating, interior vertices perturbed.
Mesh2 grid(int n, std::uint64_t seed) {
  Mesh2 m;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jit(-0.3 / n, 0.3 / n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Vec2 p(double(i) / n, double(j) / n);
      if (i > 0 && j > 0 && i < n && j < n) p += Vec2(jit(rng), jit(rng));
      m.vertices.push_back(p);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2) {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  for (int i = 0; i < n; ++i) {
    m.boundaryEdges.push_back({id(i, 0), id(i + 1, 0), 1});
    m.boundaryEdges.push_back({id(n, i), id(n, i + 1), 2});
    m.boundaryEdges.push_back({id(i + 1, n), id(i, n), 3});
    m.boundaryEdges.push_back({id(0, i + 1), id(0, i), 4});
  }
  return m;
}
}  // namespace

TEST(PointLocator, FindsContainingTriangleAndReproducesLinearFunctions) {
  const Mesh2 m = grid(40, 1);
  ASSERT_TRUE(m.validate(1.0).ok);
  const PointLocator loc(m);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  int hint = -1;
  for (int k = 0; k < 5000; ++k) {
    const Vec2 p(u(rng), u(rng));
    const auto l = loc.locate(p, k % 2 ? hint : -1);
    hint = l.triangle;
    ASSERT_TRUE(l.inside);
    Vec2 q = Vec2::Zero();
    for (int c = 0; c < 3; ++c) q += l.bary[c] * m.vertices[m.triangles[l.triangle][c]];
    EXPECT_NEAR((q - p).norm(), 0.0, 1e-12);
  }
  const auto out = loc.locate(Vec2(1.5, 0.5));
  EXPECT_FALSE(out.inside);
}

TEST(PointLocator, WalkAroundAReentrantCornerFromAFarHint) {
  // An L-shaped mesh (the grid without its lower-right quarter): the straight walk from a
  // lower-left hint to an upper-right point leaves the mesh through the notch; the locator
  // must still find the containing triangle (this once gave the adaptive loop wrong metrics).
  Mesh2 full = grid(8, 3), l;
  l.vertices = full.vertices;
  for (const auto& t : full.triangles) {
    const Vec2 c = (full.vertices[t[0]] + full.vertices[t[1]] + full.vertices[t[2]]) / 3.0;
    if (!(c.x() > 0.5 && c.y() < 0.5)) l.triangles.push_back(t);
  }
  const PointLocator locator(l);
  int hint = -1;
  for (int t = 0; t < l.numTriangles() && hint < 0; ++t) {
    const Vec2 c =
        (l.vertices[l.triangles[t][0]] + l.vertices[l.triangles[t][1]] + l.vertices[l.triangles[t][2]]) / 3.0;
    if (c.x() > 0.3 && c.x() < 0.45 && c.y() < 0.15) hint = t;
  }
  ASSERT_GE(hint, 0);
  const Vec2 p(0.9, 0.6);
  const auto loc = locator.locate(p, hint);
  EXPECT_TRUE(loc.inside);
  const auto& tr = l.triangles[loc.triangle];
  for (int k = 0; k < 3; ++k) EXPECT_GE(orient2d(l.vertices[tr[(k + 1) % 3]], l.vertices[tr[(k + 2) % 3]], p), 0);
  // A point inside the notch is outside the mesh.
  EXPECT_FALSE(locator.locate(Vec2(0.8, 0.2), hint).inside);
}

TEST(PointLocator, ExtremeAspectRatioAndFarPointsStayInTheGrid) {
  // Found by fuzz_medit_mesh: a valid two-triangle square with one vertex at x = 1.2e42 made
  // the grid's cell count ext.x / side ≈ 1e21, converted to int before it was clamped
  // (undefined behaviour, caught by UBSan); so did any query point far outside the mesh. On the
  // 4096 × 1 grid that follows, the start-triangle search then visited whole squares of cells
  // per ring, O(ring³): 5 s per located point; it must visit a few thousand cells.
  Mesh2 m;
  m.vertices = {{0, 0}, {1.2e42, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const PointLocator locator(m);
  for (const Vec2& p : {Vec2(0.5, 0.5), Vec2(1e300, -1e300), Vec2(-1e300, 1e300), Vec2(6e41, 0.1)}) {
    const auto loc = locator.locate(p);
    ASSERT_GE(loc.triangle, 0);
    ASSERT_LT(loc.triangle, m.numTriangles());
    EXPECT_NEAR(loc.bary[0] + loc.bary[1] + loc.bary[2], 1.0, 1e-9);
  }
}

TEST(BackgroundMetricField, ReproducesConstantAndInterpolatesLogEuclidean) {
  const Mesh2 m = grid(10, 3);
  const Metric2 c = Metric2::fromSizes(0.3, 0.01, 0.4);
  BackgroundMetricField constant(m, std::vector<Metric2>(m.vertices.size(), c));
  const Metric2 at = constant.at({0.37, 0.61});
  EXPECT_DOUBLE_EQ(at.m11(), c.m11());
  // sizes varying as exp(x): log-Euclidean interpolation reproduces log h linear in x exactly
  std::vector<Metric2> ms;
  for (const auto& v : m.vertices) ms.push_back(Metric2::isotropic(std::exp(-2.0 * v.x())));
  BackgroundMetricField graded(m, ms);
  EXPECT_NEAR(graded.at({0.42, 0.5}).eigen().h1, std::exp(-0.84), 1e-12);
  EXPECT_THROW(BackgroundMetricField(m, std::vector<Metric2>(3, c)), InputError);
}

TEST(BackgroundMetricField, SqrtDeterminantsMatchTheInterpolatedTensor) {
  // Anisotropic tensors turning across the mesh, at 5000 points (several parallel chunks, in
  // raster order and shuffled): exp(½ tr L) against √det of the interpolated tensor.
  const Mesh2 m = grid(12, 5);
  std::vector<Metric2> ms;
  for (const auto& v : m.vertices)
    ms.push_back(Metric2::fromSizes(0.2 * std::exp(v.x()), 0.01 + 0.05 * v.y(), 3.0 * v.x() * v.y()));
  const BackgroundMetricField field(m, ms);
  std::vector<Vec2> pts;
  for (int j = 0; j < 50; ++j)
    for (int i = 0; i < 100; ++i) pts.push_back({(i + 0.5) / 100, (j + 0.5) / 50});
  std::shuffle(pts.begin() + 2500, pts.end(), std::mt19937_64(7));
  std::vector<double> s(pts.size());
  field.sqrtDeterminants(pts, s);
  for (std::size_t k = 0; k < pts.size(); ++k) EXPECT_NEAR(s[k], std::sqrt(field.at(pts[k]).det()), 1e-12 * s[k]) << k;
  // The default (MetricField) is √det of evaluate().
  AnalyticMetricField f(AnalyticMetricField::Form::Sizes, "0.1+x", "0.05", "y");
  std::vector<double> a(3);
  const std::vector<Vec2> q = {{0.1, 0.2}, {0.5, 0.5}, {0.9, 0.3}};
  f.sqrtDeterminants(q, a);
  for (std::size_t k = 0; k < q.size(); ++k) EXPECT_DOUBLE_EQ(a[k], std::sqrt(f.at(q[k]).det()));
}

TEST(BackgroundMetricField, HintedEvaluationIsTheSameOneAtATimeAndInParallelChunks) {
  // 3000 shuffled points (12 chunks, evaluated in parallel) against one call per point (the
  // serial path of the lattice and the post-pass), each equal to at(): bit for bit.
  const Mesh2 m = grid(12, 9);
  std::vector<Metric2> ms;
  for (const auto& v : m.vertices) ms.push_back(Metric2::fromSizes(0.2 * std::exp(v.x()), 0.02 + 0.05 * v.y(), v.x()));
  const BackgroundMetricField field(m, ms);
  std::vector<Vec2> pts;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 100; ++i) pts.push_back({(i + 0.5) / 100, (j + 0.5) / 30});
  std::shuffle(pts.begin(), pts.end(), std::mt19937_64(11));
  std::vector<Metric2> all(pts.size());
  std::vector<int> hints(pts.size(), -1);
  field.evaluate(pts, all, hints);
  int hint = -1;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    Metric2 one;
    field.evaluate(std::span<const Vec2>(&pts[k], 1), std::span<Metric2>(&one, 1), std::span<int>(&hint, 1));
    const Metric2 ref = field.at(pts[k]);
    EXPECT_EQ(one.m11(), ref.m11()) << k;
    EXPECT_EQ(one.m12(), ref.m12()) << k;
    EXPECT_EQ(all[k].m22(), ref.m22()) << k;
    EXPECT_GE(hints[k], 0);
  }
}

TEST(AnalyticMetricField, EvaluatesAndReportsErrors) {
  AnalyticMetricField f(AnalyticMetricField::Form::Sizes, "0.15*abs(sqrt(x^2+y^2)-6)+0.2",
                        "0.5*(0.15*abs(sqrt(x^2+y^2)-6)+0.2)", "0");
  const Metric2 m = f.at({6, 0});
  EXPECT_NEAR(m.eigen().h1, 0.2, 1e-12);
  EXPECT_NEAR(m.eigen().h2, 0.1, 1e-12);
  EXPECT_THROW(AnalyticMetricField(AnalyticMetricField::Form::Sizes, "1+", "1", "0", "cfg.json: metric"), InputError);
  EXPECT_THROW(AnalyticMetricField(AnalyticMetricField::Form::Sizes, "z", "1", "0"), InputError);
  AnalyticMetricField neg(AnalyticMetricField::Form::Sizes, "x", "1", "0", "cfg.json: metric");
  try {
    neg.at({-1, 0});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cfg.json: metric at (-1, 0)"), std::string::npos) << e.what();
  }
}

// A graded, stretched mesh (rows 10⁻⁴ thick near y = 0.5, growing geometrically away from it;
// 8 columns): its grid cells hold dozens of thin triangles, found through the cells' k-d trees.
// Every point must land in a triangle that contains it, with and without hints.
TEST(PointLocator, CrowdedCellsOfAGradedStretchedMesh) {
  std::vector<double> ys{0.5};
  for (double h = 1e-4; ys.back() < 1; h *= 1.15) ys.push_back(std::min(1.0, ys.back() + h));
  const int half = int(ys.size()) - 1;
  std::vector<double> all;
  for (int k = half; k > 0; --k) all.push_back(1 - ys[std::size_t(k)]);
  all.insert(all.end(), ys.begin(), ys.end());
  Mesh2 m;
  const int nx = 8, ny = int(all.size()) - 1;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.vertices.push_back(Vec2(double(i) / nx, all[std::size_t(j)]));
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const PointLocator loc(m);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1), near(0.499, 0.501);
  int hint = -1;
  for (int k = 0; k < 4000; ++k) {
    const Vec2 p(u(rng), k % 3 ? near(rng) : u(rng));
    const auto l = loc.locate(p, k % 2 ? hint : -1);
    hint = l.triangle;
    ASSERT_TRUE(l.inside) << p.transpose();
    const auto& t = m.triangles[l.triangle];
    for (int c = 0; c < 3; ++c) EXPECT_GE(orient2d(m.vertices[t[(c + 1) % 3]], m.vertices[t[(c + 2) % 3]], p), 0.0);
  }
}

// An L-shaped mesh whose triangles above the re-entrant corner come first: the start triangle
// of a grid cell straddling the corner (its lowest id) then lies across the notch from points
// of the lower-left part, and the straight walk from it leaves the mesh through the notch. Such
// points are inside and must be found inside (the walk's exit edge, next to the corner, once gave
// them the corner's metric: sizes 10× too small over a band around an L-shape's corner, 15 % more
// nodes and a remesh 100× slower). Points of the notch stay outside, located on the nearest
// boundary edge's side of the corner.
TEST(PointLocator, InsidePointsAcrossTheNotchOfAReentrantCorner) {
  for (const int n : {8, 16, 40}) {
    Mesh2 full = grid(n, 5), l;
    for (int k = 0; k <= n / 2; ++k) {  // the notch's edges straight: x = 0.5, y ≤ 0.5 and y = 0.5, x ≥ 0.5
      full.vertices[std::size_t(k * (n + 1) + n / 2)] = Vec2(0.5, double(k) / n);
      full.vertices[std::size_t(n / 2 * (n + 1) + n / 2 + k)] = Vec2(0.5 + double(k) / n, 0.5);
    }
    l.vertices = full.vertices;
    std::vector<std::array<int, 3>> first, rest;
    for (const auto& t : full.triangles) {
      const Vec2 c = (full.vertices[t[0]] + full.vertices[t[1]] + full.vertices[t[2]]) / 3.0;
      if (c.x() > 0.5 && c.y() < 0.5) continue;
      (c.y() > 0.5 ? first : rest).push_back(t);
    }
    l.triangles = first;
    l.triangles.insert(l.triangles.end(), rest.begin(), rest.end());
    const PointLocator locator(l);
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> u(0.5 - 3.0 / n, 0.5 + 3.0 / n);
    int hint = -1, found = 0;
    for (int k = 0; k < 4000; ++k) {
      const Vec2 p(u(rng), u(rng));
      const bool inNotch = p.x() >= 0.5 && p.y() <= 0.5;
      const auto loc = locator.locate(p, k % 2 ? hint : -1);
      hint = loc.triangle;
      if (inNotch) {
        EXPECT_FALSE(loc.inside) << n << ": " << p.transpose();
        // Clamped into a boundary triangle next to the nearest boundary point (the clamp of
        // barycentrics is not the orthogonal projection: within a triangle's size of it).
        Vec2 q = Vec2::Zero();
        for (int c = 0; c < 3; ++c) q += loc.bary[c] * l.vertices[l.triangles[loc.triangle][c]];
        EXPECT_LT((q - p).norm(), std::min(p.x() - 0.5, 0.5 - p.y()) + 1.5 / n) << n << ": " << p.transpose();
        continue;
      }
      ASSERT_TRUE(loc.inside) << n << ": " << p.transpose();
      const auto& t = l.triangles[loc.triangle];
      for (int c = 0; c < 3; ++c) EXPECT_GE(orient2d(l.vertices[t[(c + 1) % 3]], l.vertices[t[(c + 2) % 3]], p), 0.0);
      ++found;
    }
    EXPECT_GT(found, 2000) << n;
  }
}

TEST(BackgroundMetricField, GridSqrtDeterminantsAreTheLocatedOnes) {
  // The rasterised grid (a jittered mesh of the unit square, a grid reaching past it on every
  // side, a mask with holes) against the located centres of MetricField's default: the same
  // values (bits but for rounding at centres on a shared edge), the cells outside the mesh
  // extrapolated as sqrtDeterminants does, the unmasked cells untouched.
  const Mesh2 m = grid(14, 3);
  std::vector<Metric2> ms;
  for (const auto& v : m.vertices) ms.push_back(Metric2::fromSizes(0.1 * std::exp(v.x()), 0.01 + 0.05 * v.y(), v.x()));
  const BackgroundMetricField field(m, ms);
  const int gx = 70, gy = 50;
  const Vec2 lo(-0.05, -0.1), d(1.1 / gx, 1.2 / gy);
  std::vector<char> mask(std::size_t(gx * gy));
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = char(i % 7 != 3);
  std::vector<double> fast(mask.size(), -1.0), slow(mask.size(), -1.0);
  field.gridSqrtDeterminants(lo, d, gx, gy, mask, fast);
  field.MetricField::gridSqrtDeterminants(lo, d, gx, gy, mask, slow);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) {
      EXPECT_EQ(fast[i], -1.0) << i;
      continue;
    }
    EXPECT_GT(fast[i], 0) << i;
    EXPECT_NEAR(fast[i], slow[i], 1e-14 * slow[i]) << i;
  }
}
