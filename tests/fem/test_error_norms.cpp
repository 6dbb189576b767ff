// Tests of fem/error_norms.hpp against known values.
#include "ablmg/fem/error_norms.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>

using namespace ablmg;
using namespace ablmg::fem;

TEST(ErrorNorms, KnownValuesForZeroDiscreteSolution) {
  // u_h = 0, u = x y on the unit square: ‖u‖_L2² = 1/9, |u|_H1² = ∫ y² + x² = 2/3.
  const Mesh2 m = unitSquareMesh(5, 0.2, 3);
  const ErrorReport e =
      computeErrors(m, Eigen::VectorXd::Zero(m.numVertices()),
                    {[](double x, double y) { return x * y; }, [](double x, double y) { return Vec2(y, x); }});
  EXPECT_NEAR(e.l2, std::sqrt(1.0 / 9), 1e-13);
  EXPECT_NEAR(e.h1, std::sqrt(2.0 / 3), 1e-13);
  EXPECT_NEAR(e.maxVertex, 1.0, 1e-15);
  double s = 0;
  for (double x : e.elementL2) s += x * x;
  EXPECT_NEAR(std::sqrt(s), e.l2, 1e-13);
}

TEST(ErrorNorms, InterpolationErrorOfQuadraticMatchesFormulaOnUniformMesh) {
  // For u = x² on a mesh of n×n cells, u − I_h u = x(h−x)-type bubbles per element edge in x:
  // it only depends on x, and on every triangle equals the 1D interpolation error of x²,
  // whose L2 norm over the square is h²/√30.
  for (int n : {4, 8}) {
    const Mesh2 m = unitSquareMesh(n);
    const double h = 1.0 / n;
    EXPECT_NEAR(interpolationErrorL2(m, [](double x, double) { return x * x; }), h * h / std::sqrt(30.0), 1e-12);
  }
}

TEST(ErrorNorms, SizeMismatchIsAnInputError) {
  const Mesh2 m = unitSquareMesh(2);
  EXPECT_THROW(computeErrors(m, Eigen::VectorXd::Zero(3), {[](double, double) { return 0.0; }, {}}), InputError);
}

TEST(ErrorNorms, ParallelIsBitwiseSerial) {
  const Mesh2 m = unitSquareMesh(60, 0.2, 4);  // > 4096 triangles: the parallel path
  ExactSolution ex{[](double x, double y) { return std::sin(7 * x) * std::cos(5 * y); },
                   [](double x, double y) -> Vec2 {
                     return Vec2(7 * std::cos(7 * x) * std::cos(5 * y), -5 * std::sin(7 * x) * std::sin(5 * y));
                   },
                   true};
  const Eigen::VectorXd uh = Eigen::VectorXd::Constant(m.numVertices(), 0.1);
  const ErrorReport a = computeErrors(m, uh, ex);
  ex.threadSafe = false;
  const ErrorReport b = computeErrors(m, uh, ex);
  EXPECT_EQ(a.l2, b.l2);
  EXPECT_EQ(a.h1, b.h1);
  EXPECT_EQ(a.l2Interp, b.l2Interp);
  EXPECT_EQ(a.elementH1, b.elementH1);
}

TEST(ErrorNorms, AnExactSolutionThrowingInTheParallelLoopGivesItsOwnError) {
  // > 4096 triangles and threadSafe: the parallel path. The exact solution fails (NaN) at the
  // quadrature points of a band x in (0.70, 0.72), never at a vertex (the vertex interpolant is
  // taken serially first), so the error arises inside the OpenMP region, on several threads'
  // triangles. It must come out as the callback's own InputError, the one of the lowest
  // triangle, the same on 1 and 2 threads and in the serial loop; never std::terminate.
  const Mesh2 m = unitSquareMesh(60, 0.2, 4);
  std::set<std::pair<double, double>> vertices;
  for (const Vec2& v : m.vertices) vertices.insert({v.x(), v.y()});
  ExactSolution ex{[&](double x, double y) {
                     const bool isVertex = vertices.count({x, y}) > 0;
                     ABLMG_REQUIRE(isVertex || !(x > 0.70 && x < 0.72),
                                   "exact solution: NaN at (" << x << ", " << y << ")");
                     return x * y;
                   },
                   {},
                   true};
  const Eigen::VectorXd uh = Eigen::VectorXd::Zero(m.numVertices());
  const auto message = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    std::string what;
    try {
      computeErrors(m, uh, ex);
    } catch (const InputError& e) { what = e.what(); }
    omp_set_num_threads(before);
    return what;
  };
  const std::string two = message(2);
  EXPECT_EQ(two.rfind("exact solution: NaN at (0.7", 0), 0u) << two;
  EXPECT_EQ(message(1), two);
  ex.threadSafe = false;
  EXPECT_EQ(message(2), two);
}

TEST(ErrorNorms, ValueAndGradientInOneCallGiveTheSameNorms) {
  // The corner solution's combined u and ∇u (one r and θ per point) against the two apart.
  const TestProblem p = makeProblem("lshape");
  const Mesh2 mesh = structuredMesh(p.domain, 10, 10, 0.2, 3);
  Eigen::VectorXd uh(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) uh[v] = 0.9 * p.u(mesh.vertices[v].x(), mesh.vertices[v].y());
  ExactSolution apart = p.exact();
  ASSERT_TRUE(bool(apart.valueAndGrad));
  apart.valueAndGrad = {};
  const ErrorReport a = computeErrors(mesh, uh, apart), b = computeErrors(mesh, uh, p.exact());
  EXPECT_GT(a.h1, 0);
  EXPECT_EQ(a.l2, b.l2);
  EXPECT_EQ(a.h1, b.h1);
  EXPECT_EQ(a.elementH1, b.elementH1);
}
