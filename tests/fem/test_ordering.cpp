// Tests of fem/ordering.hpp: a permutation, deterministic, and a fill-reducing one.
#include "ablmg/fem/ordering.hpp"

#include "ablmg/fem/assemble.hpp"
#include "ablmg/fem/solve.hpp"
#include "ablmg/core/domain.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <numeric>

using namespace ablmg;
using namespace ablmg::fem;

TEST(Ordering, IsADeterministicPermutation) {
  for (double p : {0.0, 0.2}) {
    const Mesh2 m = unitSquareMesh(40, p, 11);
    const LinearSystem sys = assemble(m, makeProblem("sine").poisson());
    for (int leaf : {1, 7, 64, 100000}) {
      std::vector<int> perm = geometricNestedDissection(sys.A, sys.dofPoints, leaf);
      EXPECT_EQ(perm, geometricNestedDissection(sys.A, sys.dofPoints, leaf));
      std::sort(perm.begin(), perm.end());
      std::vector<int> iota(sys.A.rows());
      std::iota(iota.begin(), iota.end(), 0);
      EXPECT_EQ(perm, iota) << "leaf " << leaf;
    }
  }
}

TEST(Ordering, ReducesFillBelowNaturalOrderAndNearCholmodsOwn) {
  const Mesh2 m = unitSquareMesh(120, 0.2, 5);
  const TestProblem tp = makeProblem("smooth");
  const LinearSystem sys = assemble(m, tp.poisson());
  SolveStats gnd, cholmod;
  const Eigen::VectorXd x1 = solveSystem(sys, &gnd, {Ordering::GeometricNestedDissection, 500});
  const Eigen::VectorXd x2 = solveSystem(sys, &cholmod, {Ordering::Cholmod, 500});
  EXPECT_LT((x1 - x2).norm(), 1e-10 * x2.norm());
  EXPECT_LT(gnd.residual, 1e-12);
  // Natural (row-by-row) order of a 119² grid: a band of width ≈ 120, i.e. lnz ≈ 120 · n.
  EXPECT_LT(gnd.factorNonZeros, 0.5 * 120 * sys.A.rows());
  EXPECT_LT(gnd.factorNonZeros, 1.6 * cholmod.factorNonZeros);
}

TEST(Ordering, SameForAnyThreadCount) {
  const Mesh2 m = unitSquareMesh(180, 0.2, 12);  // > 20000 unknowns: the parallel recursion
  const LinearSystem sys = assemble(m, makeProblem("sine").poisson());
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<int> one = geometricNestedDissection(sys.A, sys.dofPoints);
  omp_set_num_threads(2);
  const std::vector<int> two = geometricNestedDissection(sys.A, sys.dofPoints);
  omp_set_num_threads(saved);
  EXPECT_EQ(one, two);
}

// A stretched grid (20 × 2000 cells of the unit square, aspect 100, like an adapted layer):
// the bounding box is square, so the longer-axis rule may cut across the 2000 thin rows;
// the smallest-separator cut runs along them (≈ 21 vertices). Fill and flops must stay
// near METIS' graph ordering and far below the longer-axis rule's.
TEST(Ordering, StretchedGridCutAlongTheRows) {
  const Mesh2 m = structuredMesh(Domain::rectangle(0, 0, 1, 1), 20, 2000);
  const LinearSystem sys = assemble(m, makeProblem("smooth").poisson());
  SolveStats best, longer, metis;
  const Eigen::VectorXd x1 = solveSystem(sys, &best, {Ordering::GeometricNestedDissection, 500});
  solveSystem(sys, &longer, {Ordering::GeometricNestedDissection, 500, CutChoice::LongerAxis});
  const Eigen::VectorXd x3 = solveSystem(sys, &metis, {Ordering::Metis, 500});
  EXPECT_LT((x1 - x3).norm(), 1e-10 * x3.norm());
  EXPECT_LT(best.residual, 1e-12);
  EXPECT_LT(best.factorFlops, 1.5 * metis.factorFlops);
  EXPECT_LT(best.factorFlops, 0.5 * longer.factorFlops);
  EXPECT_LT(best.factorNonZeros, 1.3 * metis.factorNonZeros);
}

TEST(Ordering, MetisIsAPermutation) {
  const Mesh2 m = unitSquareMesh(30, 0.2, 3);
  const LinearSystem sys = assemble(m, makeProblem("sine").poisson());
  std::vector<int> perm = metisNestedDissection(sys.A);
  std::sort(perm.begin(), perm.end());
  std::vector<int> iota(sys.A.rows());
  std::iota(iota.begin(), iota.end(), 0);
  EXPECT_EQ(perm, iota);
}

// The first cut's separator is a vertex cover of the edges between the two sides (König's
// minimum one): no entry of A joins them, on a jittered grid where the straight cut line meets
// edges at every angle, and it is no larger than one grid row.
TEST(Ordering, FirstCutSeparatesTheSidesWithAMinimumCover) {
  for (double jitter : {0.0, 0.2}) {
    const Mesh2 m = unitSquareMesh(90, jitter, 7);
    const LinearSystem sys = assemble(m, makeProblem("sine").poisson());
    TopCut top;
    const std::vector<int> perm = geometricNestedDissection(sys.A, sys.dofPoints, 500, CutChoice::SmallestSeparator, &top);
    ASSERT_GT(top.lower, 0);
    ASSERT_GT(top.upper, 0);
    const int n = int(sys.A.rows());
    std::vector<int> side(static_cast<std::size_t>(n), 0);  // 1, 2: the sides; 0: the separator
    for (int k = 0; k < top.lower; ++k) side[std::size_t(perm[std::size_t(k)])] = 1;
    for (int k = top.lower; k < top.lower + top.upper; ++k) side[std::size_t(perm[std::size_t(k)])] = 2;
    long crossing = 0;
    for (int v = 0; v < n; ++v)
      for (Eigen::SparseMatrix<double>::InnerIterator it(sys.A, v); it; ++it)
        crossing += side[std::size_t(v)] * side[std::size_t(it.index())] == 2;
    EXPECT_EQ(crossing, 0) << "jitter " << jitter;
    const int separator = n - top.lower - top.upper;
    EXPECT_GT(separator, 0);
    // The interior grid is 89 × 89 unknowns, and the jittered grid has the regular one's
    // connectivity: one grid row (89) covers the edges a cut meets. Taking the whole of one
    // side's touching vertices instead gives 105 on the jittered grid.
    EXPECT_LE(separator, 89) << "jitter " << jitter;
  }
}
