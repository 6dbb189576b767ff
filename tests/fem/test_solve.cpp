// Tests of fem/assemble.hpp + fem/solve.hpp: patch test, Neumann data, lifting, errors on
// singular or non-SPD systems; CHOLMOD's OpenMP loops kept to the calling thread.
#include "ablmg/fem/solve.hpp"

#include "ablmg/core/domain.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <limits>
#include <string>

using namespace ablmg;
using namespace ablmg::fem;

namespace {
double linearU(double x, double y) { return 1 + 2 * x - 3 * y; }

double maxNodalError(const Mesh2& m, const Eigen::VectorXd& u, const ScalarFn& exact) {
  double e = 0;
  for (int v = 0; v < m.numVertices(); ++v)
    e = std::max(e, std::abs(u[v] - exact(m.vertices[v].x(), m.vertices[v].y())));
  return e;
}
}  // namespace

TEST(Solve, PatchTestLinearSolutionOnUnstructuredMesh) {
  const Mesh2 m = unitSquareMesh(13, 0.2, 42);
  PoissonProblem p;
  p.kappa = 2.5;
  p.f = 0.0;
  p.setDirichletEverywhere(ScalarFn(linearU));
  const PoissonSolution s = solvePoisson(m, p);
  EXPECT_LT(maxNodalError(m, s.u, linearU), 1e-12);
  const ErrorReport e = computeErrors(m, s.u, makeProblem("linear").exact());
  EXPECT_LT(e.l2, 1e-12);
  EXPECT_LT(e.h1, 1e-11);
  EXPECT_EQ(s.stats.unknowns, 12 * 12);
  EXPECT_GT(s.stats.nonZeros, 5L * s.stats.unknowns);
  EXPECT_LT(s.stats.residual, 1e-12);
}

TEST(Solve, PatchTestWithNeumannEdgesAndVariableKappa) {
  // u = 1 + 2x − 3y, κ = 1 + x²: −∇·(κ∇u) = −∂x(κ)·2 = −4x. Neumann on top (κ ∂u/∂y = −3κ)
  // and left (−κ ∂u/∂x = −2κ); Dirichlet on bottom and right.
  const Mesh2 m = unitSquareMesh(10, 0.15, 7);
  PoissonProblem p;
  p.kappa = ScalarFn([](double x, double) { return 1 + x * x; });
  p.f = ScalarFn([](double x, double) { return -4 * x; });
  p.dirichlet[1] = ScalarFn(linearU);
  p.dirichlet[2] = ScalarFn(linearU);
  p.neumann[3] = ScalarFn([](double x, double) { return -3 * (1 + x * x); });
  p.neumann[4] = ScalarFn([](double x, double) { return -2 * (1 + x * x); });
  const PoissonSolution s = solvePoisson(m, p);
  // u ∈ V_h and the quadratures integrate κ (degree 2) and f φ (degree 2) exactly, so by
  // Galerkin orthogonality u_h = u to round-off, although κ varies.
  EXPECT_LT(maxNodalError(m, s.u, linearU), 1e-12);
}

TEST(Solve, ConstantKappaNeumannPatchIsExact) {
  const Mesh2 m = unitSquareMesh(9, 0.2, 3);
  PoissonProblem p;
  p.dirichlet[1] = ScalarFn(linearU);
  p.neumann[2] = 2.0;   // right: ∂u/∂x
  p.neumann[3] = -3.0;  // top: ∂u/∂y
  p.neumann[4] = -2.0;  // left: −∂u/∂x
  EXPECT_LT(maxNodalError(m, solvePoisson(m, p).u, linearU), 1e-12);
}

TEST(Solve, PerVertexDataMatchFunctions) {
  const Mesh2 m = unitSquareMesh(6);
  PoissonProblem a, b;
  a.f = 3.0;
  a.setDirichletEverywhere(ScalarFn(linearU));
  b.f = ScalarData::values(std::vector<double>(m.numVertices(), 3.0));
  const Eigen::VectorXd g = interpolate(m, linearU);
  b.setDirichletEverywhere(ScalarData::values(std::vector<double>(g.data(), g.data() + g.size())));
  EXPECT_LT((solvePoisson(m, a).u - solvePoisson(m, b).u).norm(), 1e-12);
}

TEST(Solve, SingularOrNonSpdSystemsAreInputErrors) {
  const Mesh2 m = unitSquareMesh(4);
  PoissonProblem neumannOnly;
  neumannOnly.f = 1.0;
  try {
    solvePoisson(m, neumannOnly);
    FAIL() << "pure Neumann problem accepted";
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what(); }
  PoissonProblem negative;
  negative.kappa = -1.0;
  negative.setDirichletEverywhere(0.0);
  try {
    solvePoisson(m, negative);
    FAIL() << "negative kappa accepted";
  } catch (const InputError& e) { EXPECT_NE(std::string(e.what()).find("kappa"), std::string::npos) << e.what(); }
  PoissonProblem signChange;
  signChange.kappa = ScalarFn([](double x, double) { return x - 0.5; });
  signChange.setDirichletEverywhere(0.0);
  EXPECT_THROW(solvePoisson(m, signChange), InputError);
  PoissonProblem wrongSize;
  wrongSize.f = ScalarData::values({1.0, 2.0});
  wrongSize.setDirichletEverywhere(0.0);
  EXPECT_THROW(solvePoisson(m, wrongSize), InputError);
}

TEST(Solve, PieceWithoutDirichletVertexIsAnInputError) {
  // Two disjoint squares; Dirichlet only on tags of the first one.
  Mesh2 m = unitSquareMesh(3), m2 = unitSquareMesh(3);
  const int off = m.numVertices();
  for (auto v : m2.vertices) m.vertices.push_back(v + Vec2(2, 0));
  for (auto t : m2.triangles) m.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
  for (auto e : m2.boundaryEdges) m.boundaryEdges.push_back({e.a + off, e.b + off, e.ref + 10});
  PoissonProblem p;
  for (int tag = 1; tag <= 4; ++tag) p.dirichlet[tag] = 0.0;
  EXPECT_THROW(solvePoisson(m, p), InputError);
  for (int tag = 11; tag <= 14; ++tag) p.dirichlet[tag] = 0.0;
  EXPECT_NO_THROW(solvePoisson(m, p));
}

TEST(Assemble, ParallelElementLoopIsBitwiseSerial) {
  const Mesh2 m = unitSquareMesh(260, 0.2, 8);  // > 2 blocks of 16384 triangles
  PoissonProblem p = makeProblem("wavefront").poisson();
  p.threadSafeFunctions = true;
  const LinearSystem a = assemble(m, p);
  p.threadSafeFunctions = false;
  const LinearSystem b = assemble(m, p);
  ASSERT_EQ(a.A.nonZeros(), b.A.nonZeros());
  EXPECT_TRUE(std::equal(a.A.valuePtr(), a.A.valuePtr() + a.A.nonZeros(), b.A.valuePtr()));
  EXPECT_TRUE(a.b == b.b);
  // An error inside the parallel loop surfaces as the serial loop's InputError.
  p.threadSafeFunctions = true;
  p.kappa = ScalarFn([](double x, double) { return x < 0.9 ? 1.0 : -1.0; });
  EXPECT_THROW(assemble(m, p), InputError);
  // The error is the lowest triangle's (the serial loop's), on any thread count.
  const auto message = [&](bool parallel, int threads) {
    p.threadSafeFunctions = parallel;
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    std::string what;
    try {
      assemble(m, p);
    } catch (const InputError& e) { what = e.what(); }
    omp_set_num_threads(before);
    return what;
  };
  const std::string serial = message(false, 1);
  EXPECT_EQ(serial.rfind("assemble: kappa = -1 at (0.9", 0), 0u) << serial;
  EXPECT_EQ(message(true, 2), serial);
  EXPECT_EQ(message(true, 1), serial);
}

// Above 20000 unknowns the pattern and the scatter are split by rows across the threads.
TEST(Assemble, BitwiseSameOnOneAndTwoThreads) {
  const Mesh2 m = unitSquareMesh(260, 0.2, 9);
  const PoissonProblem p = makeProblem("tanhlayer").poisson();
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const LinearSystem one = assemble(m, p);
  omp_set_num_threads(2);
  const LinearSystem two = assemble(m, p);
  omp_set_num_threads(saved);
  ASSERT_GE(one.A.rows(), 20000);
  ASSERT_EQ(one.A.nonZeros(), two.A.nonZeros());
  EXPECT_TRUE(std::equal(one.A.outerIndexPtr(), one.A.outerIndexPtr() + one.A.rows() + 1, two.A.outerIndexPtr()));
  EXPECT_TRUE(std::equal(one.A.innerIndexPtr(), one.A.innerIndexPtr() + one.A.nonZeros(), two.A.innerIndexPtr()));
  EXPECT_TRUE(std::equal(one.A.valuePtr(), one.A.valuePtr() + one.A.nonZeros(), two.A.valuePtr()));
  EXPECT_TRUE(one.b == two.b);
}

TEST(PoissonProblem, LambdasConvertToScalarData) {
  PoissonProblem p;
  p.f = [](double x, double y) { return x + y; };
  p.dirichlet[2] = [](double, double) { return 1.0; };
  p.kappa = 2;
  EXPECT_TRUE(p.f.isFunction());
  EXPECT_EQ(p.f.fn(1, 2), 3.0);
  EXPECT_TRUE(p.dirichlet[2].isFunction());
  EXPECT_TRUE(p.kappa.isConstant());
  EXPECT_EQ(p.kappa.constant, 2.0);
}

TEST(Solve, BitwiseSameForAnyThreadCount) {
  const Mesh2 m = unitSquareMesh(220, 0.2, 21);  // large enough for threaded BLAS and OpenMP paths
  const PoissonProblem p = makeProblem("wavefront").poisson();
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Eigen::VectorXd one = solvePoisson(m, p).u;
  omp_set_num_threads(2);
  const Eigen::VectorXd two = solvePoisson(m, p).u;
  omp_set_num_threads(saved);
  EXPECT_TRUE(one == two);
}

TEST(Solve, CholmodScopeRunsRegionsSeriallyAndRestoresTheLevel) {
  const int saved = omp_get_max_active_levels();
  auto teamSize = [] {
    int n = 0;
#pragma omp parallel num_threads(4)  // CHOLMOD's fixed team size
#pragma omp atomic
    ++n;
    return n;
  };
  {
    const CholmodScope serial;
    EXPECT_EQ(teamSize(), 1);
  }
  EXPECT_EQ(omp_get_max_active_levels(), saved);
  EXPECT_EQ(teamSize(), saved > 0 ? 4 : 1);
}

// CHOLMOD's OpenMP regions inside a CholmodScope on a thread in no parallel region run
// without a team (fem/cholmod_threads.hpp); inside a parallel region they go to the runtime.
// Both give the same bits, and the first path is the one a top-level solve takes.
TEST(Solve, CholmodRegionsWithoutATeamGiveTheSameBits) {
  const Mesh2 m = unitSquareMesh(220, 0.2, 5);  // split factorisation, supernodal sides
  const PoissonProblem p = makeProblem("wavefront").poisson();
  const long before = teamlessRegionCount();
  const Eigen::VectorXd top = solvePoisson(m, p).u;
  const long teamless = teamlessRegionCount() - before;
  EXPECT_GT(teamless, 1000);  // the calling thread's side: a few regions per supernode
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);  // inside the region below: both sides on this thread
  Eigen::VectorXd nested;
  long nestedTeamless = -1;
#pragma omp parallel num_threads(1)
  {
    const long start = teamlessRegionCount();
    nested = solvePoisson(m, p).u;
    nestedTeamless = teamlessRegionCount() - start;
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(nestedTeamless, 0);
  EXPECT_TRUE(top == nested);
}

// CHOLMOD's per-supernode BLAS calls on small blocks run the loops of fem/small_blas.hpp
// (fem/cholmod_threads.hpp): thousands of them on the calling thread's side of a 220² grid,
// and the solution is still the nodal interpolant's neighbour (the check that the loops'
// products are the factorisation's).
TEST(Solve, SmallBlasCallsOfTheFactorisationRunInline) {
  const Mesh2 m = unitSquareMesh(220, 0.2, 5);
  const PoissonProblem p = makeProblem("smooth").poisson();
  const long before = smallBlasCallCount();
  const PoissonSolution s = solvePoisson(m, p);
  EXPECT_GT(smallBlasCallCount() - before, 1000);
  EXPECT_LT(s.stats.residual, 1e-12);
  EXPECT_LT(maxNodalError(m, s.u, makeProblem("smooth").u), 1e-3);
}

// Above splitMinUnknowns the two sides of the first cut are factorised apart
// (fem/split_cholesky.hpp): the same solution as one factorisation, to rounding, with a
// small residual, on a uniform grid (supernodal sides) and on a stretched one (simplicial).
TEST(Solve, SplitFactorisationMatchesOneFactorisation) {
  const Mesh2 meshes[] = {unitSquareMesh(150, 0.2, 4), structuredMesh(Domain::rectangle(0, 0, 1, 1), 12, 2000)};
  for (const Mesh2& m : meshes) {
    const LinearSystem sys = assemble(m, makeProblem("wavefront").poisson());
    ASSERT_GE(sys.A.rows(), 20000);
    SolveOptions whole;
    whole.splitMinUnknowns = std::numeric_limits<int>::max();
    SolveStats ss, sw;
    const Eigen::VectorXd xs = solveSystem(sys, &ss), xw = solveSystem(sys, &sw, whole);
    EXPECT_FALSE(xs == xw);  // the split path ran: other rounding
    EXPECT_LT((xs - xw).norm(), 1e-11 * xw.norm());
    EXPECT_LT(ss.residual, 1e-12);
    EXPECT_NEAR(ss.factorNonZeros, sw.factorNonZeros, 0.05 * sw.factorNonZeros);
  }
}

// Each side's factorisation and the separator's Schur complement reject a non-SPD matrix.
TEST(Solve, SplitFactorisationRejectsNonSpdMatrices) {
  LinearSystem sys = assemble(unitSquareMesh(150), makeProblem("smooth").poisson());
  LinearSystem negated = sys;
  negated.A = -sys.A;
  EXPECT_THROW(solveSystem(negated), InputError);
  // A negative diagonal entry on a separator unknown (the last of the order): an error, not
  // a crash or a wrong answer.
  std::vector<int> order = geometricNestedDissection(sys.A, sys.dofPoints);
  sys.A.coeffRef(order.back(), order.back()) = -1e3;
  try {
    solveSystem(sys);
    FAIL() << "indefinite matrix accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos) << e.what();
  }
}

TEST(Solve, SplitFactorisationBitwiseSameOnOneAndTwoThreads) {
  const LinearSystem sys = assemble(unitSquareMesh(150, 0.2, 8), makeProblem("tanhlayer").poisson());
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Eigen::VectorXd one = solveSystem(sys);
  omp_set_num_threads(2);
  const Eigen::VectorXd two = solveSystem(sys);
  omp_set_num_threads(saved);
  EXPECT_TRUE(one == two);
}

// A kept factorisation solves other right-hand sides with the same bits as a fresh solve, on
// the split path, the whole one and CHOLMOD's own ordering; the unit-load dual's solve reuses
// the primal's factor (no ordering or factorisation), and a system with another matrix is
// factorised anew.
TEST(Solve, KeptFactorisationSolvesFurtherRightHandSides) {
  const Mesh2 m = unitSquareMesh(70, 0.2, 6);
  const LinearSystem sys = assemble(m, makeProblem("wavefront").poisson());
  const Eigen::VectorXd b2 = Eigen::VectorXd::LinSpaced(sys.A.rows(), -1.0, 2.0);
  LinearSystem other = sys;
  other.b = b2;
  SolveOptions split, whole, cholmod;
  split.splitMinUnknowns = 1000;  // the split path at this size
  ASSERT_GE(sys.A.rows(), split.splitMinUnknowns);
  whole.splitMinUnknowns = std::numeric_limits<int>::max();
  cholmod.ordering = Ordering::Cholmod;
  EXPECT_FALSE(solveSystem(sys, nullptr, split) == solveSystem(sys, nullptr, whole));  // other paths ran
  for (const SolveOptions& o : {split, whole, cholmod}) {
    Factorisation f(sys, o);
    EXPECT_TRUE(f.solve(sys.b) == solveSystem(sys, nullptr, o));
    EXPECT_TRUE(f.solve(b2) == solveSystem(other, nullptr, o));
    EXPECT_TRUE(f.sameMatrix(sys.A));
    EXPECT_THROW(f.solve(Eigen::VectorXd::Ones(3)), InputError);
  }
  PoissonProblem primal;
  primal.kappa = 2.0;
  primal.f = ScalarFn([](double x, double y) { return std::sin(3 * x) + y; });
  primal.setDirichletEverywhere(ScalarFn(linearU));
  PoissonProblem dual = primal;
  dual.f = 1.0;
  dual.setDirichletEverywhere(0.0);
  std::unique_ptr<Factorisation> factor;
  const PoissonSolution u = solvePoisson(m, primal, {}, factor);
  ASSERT_TRUE(factor);
  const Factorisation* kept = factor.get();
  const PoissonSolution z = solvePoisson(m, dual, {}, factor);
  EXPECT_EQ(factor.get(), kept);
  EXPECT_EQ(z.stats.orderingSeconds, 0.0);
  EXPECT_EQ(z.stats.numericSeconds, 0.0);
  EXPECT_EQ(z.stats.factorFlops, u.stats.factorFlops);
  EXPECT_LT(z.stats.residual, 1e-12);
  EXPECT_TRUE(u.u == solvePoisson(m, primal).u);
  EXPECT_TRUE(z.u == solvePoisson(m, dual).u);
  PoissonProblem stiffer = dual;
  stiffer.kappa = 3.0;
  const PoissonSolution w = solvePoisson(m, stiffer, {}, factor);
  EXPECT_GT(w.stats.factorFlops, 0.0);
  EXPECT_TRUE(factor->sameMatrix(assemble(m, stiffer).A));
  EXPECT_FALSE(factor->sameMatrix(sys.A));
  EXPECT_TRUE(w.u == solvePoisson(m, stiffer).u);
}
