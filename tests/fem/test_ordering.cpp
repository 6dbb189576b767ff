// Tests of fem/ordering.hpp: a permutation, deterministic, and a fill-reducing one.
#include "ablmg/fem/ordering.hpp"

#include "ablmg/fem/assemble.hpp"
#include "ablmg/fem/solve.hpp"
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
