// Tests of fem/small_blas.hpp: each kernel against Eigen's dense products and factorisations on
// random blocks with padded leading dimensions (the padding, and the triangle a routine does
// not own, left untouched); LAPACK's info on a non-SPD block; and the BLAS entry points of
// fem/cholmod_threads.cpp, which take the small calls inside a CholmodScope only and hand every
// other call to the BLAS.
#include "ablmg/fem/small_blas.hpp"

#include "ablmg/fem/cholmod_threads.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <optional>
#include <random>

using namespace ablmg::fem;

extern "C" {
void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*, const double*, const int*,
            const double*, const int*, const double*, double*, const int*, std::size_t, std::size_t);
void dpotrf_(const char*, const int*, double*, const int*, int*, std::size_t);
}

namespace {

constexpr double kSentinel = -12345.0;  // what the padding holds before and must hold after

/// An m × n block inside a column-major buffer with leading dimension m + 3 (the 3 padding
/// rows hold kSentinel), random entries in [−1, 1].
struct Block {
  int m, n, ld;
  std::vector<double> data;
  Block(int rows, int cols, std::mt19937& rng)
      : m(rows), n(cols), ld(rows + 3), data(std::size_t(ld) * cols, kSentinel) {
    std::uniform_real_distribution<double> u(-1, 1);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) at(i, j) = u(rng);
  }
  double& at(int i, int j) { return data[std::size_t(j) * ld + i]; }
  Eigen::MatrixXd dense() {
    Eigen::MatrixXd d(m, n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) d(i, j) = at(i, j);
    return d;
  }
  bool paddingIntact() {
    for (int j = 0; j < n; ++j)
      for (int i = m; i < ld; ++i)
        if (at(i, j) != kSentinel) return false;
    return true;
  }
};

/// A random SPD n × n block (B Bᵀ + n I), the strict upper part kSentinel.
Block spdBlock(int n, std::mt19937& rng) {
  Block b(n, n, rng);
  const Eigen::MatrixXd r = b.dense();
  const Eigen::MatrixXd s = r * r.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) b.at(i, j) = i >= j ? s(i, j) : kSentinel;
  return b;
}

/// max |d_ij| (0 for an empty block).
double maxAbs(const Eigen::MatrixXd& d) { return d.size() ? d.cwiseAbs().maxCoeff() : 0.0; }

const int kSizes[][3] = {{1, 1, 1}, {3, 2, 5}, {7, 4, 3}, {16, 16, 16}, {25, 9, 14}, {0, 3, 2}, {4, 0, 2}, {5, 3, 0}};

}  // namespace

TEST(SmallBlas, GemmNTIsABTransposed) {
  std::mt19937 rng(1);
  for (const auto& s : kSizes) {
    Block A(s[0], s[2], rng), B(s[1], s[2], rng), C(s[0], s[1], rng);
    smallblas::gemmNT(s[0], s[1], s[2], A.data.data(), A.ld, B.data.data(), B.ld, C.data.data(), C.ld);
    const Eigen::MatrixXd expected = A.dense() * B.dense().transpose();
    EXPECT_LT(maxAbs(C.dense() - expected), 1e-13) << s[0] << "×" << s[1] << "×" << s[2];
    EXPECT_TRUE(C.paddingIntact());
  }
}

TEST(SmallBlas, SyrkLowerWritesTheLowerTriangleOnly) {
  std::mt19937 rng(2);
  for (const auto& s : kSizes) {
    const int n = s[0], k = s[2];
    Block A(n, k, rng), C(n, n, rng);
    const Eigen::MatrixXd before = C.dense();
    smallblas::syrkLower(n, k, A.data.data(), A.ld, C.data.data(), C.ld);
    const Eigen::MatrixXd expected = A.dense() * A.dense().transpose(), got = C.dense();
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (i >= j)
          EXPECT_NEAR(got(i, j), expected(i, j), 1e-13);
        else
          EXPECT_EQ(got(i, j), before(i, j));  // the strict upper part is not the routine's
    EXPECT_TRUE(C.paddingIntact());
  }
}

TEST(SmallBlas, TrsmSolvesXLTransposedEqualsB) {
  std::mt19937 rng(3);
  for (const auto& s : kSizes) {
    const int m = s[0], n = s[1];
    Block L = spdBlock(n, rng);
    Eigen::MatrixXd l = L.dense().triangularView<Eigen::Lower>();
    Block B(m, n, rng);
    const Eigen::MatrixXd b = B.dense();
    smallblas::trsmRightLowerT(m, n, L.data.data(), L.ld, B.data.data(), B.ld);
    EXPECT_LT(maxAbs(B.dense() * l.transpose() - b), 1e-12) << m << "×" << n;
    EXPECT_TRUE(B.paddingIntact());
  }
}

TEST(SmallBlas, PotrfFactorisesAnSpdBlockAndReportsTheFirstBadPivot) {
  std::mt19937 rng(4);
  for (const int n : {0, 1, 2, 5, 13, 20}) {
    Block A = spdBlock(n, rng);
    const Eigen::MatrixXd a = A.dense().selfadjointView<Eigen::Lower>();
    ASSERT_EQ(smallblas::potrfLower(n, A.data.data(), A.ld), 0) << n;
    const Eigen::MatrixXd l = A.dense().triangularView<Eigen::Lower>();
    EXPECT_LT(maxAbs(l * l.transpose() - a), 1e-12 * (n + 1));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < j; ++i) EXPECT_EQ(A.at(i, j), kSentinel);
    EXPECT_TRUE(A.paddingIntact());
  }
  // diag(4, 1, −1, 9): the third pivot (index 2) fails, LAPACK's info = 3.
  Block D(4, 4, rng);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) D.at(i, j) = 0;
  D.at(0, 0) = 4, D.at(1, 1) = 1, D.at(2, 2) = -1, D.at(3, 3) = 9;
  EXPECT_EQ(smallblas::potrfLower(4, D.data.data(), D.ld), 3);
  EXPECT_EQ(D.at(0, 0), 2);
  D.at(2, 2) = std::numeric_limits<double>::quiet_NaN();  // a NaN pivot is not positive either
  EXPECT_EQ(smallblas::potrfLower(4, D.data.data(), D.ld), 3);
}

TEST(SmallBlas, TrsvSolvesWithLAndItsTranspose) {
  std::mt19937 rng(5);
  for (const int n : {1, 4, 31}) {
    Block L = spdBlock(n, rng);
    const Eigen::MatrixXd l = L.dense().triangularView<Eigen::Lower>();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2);
    for (const bool transposed : {false, true}) {
      Eigen::VectorXd x = b;
      smallblas::trsvLower(transposed, n, L.data.data(), L.ld, x.data());
      const Eigen::VectorXd r = (transposed ? Eigen::MatrixXd(l.transpose()) : l) * x - b;
      EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12) << n << (transposed ? " transposed" : "");
    }
  }
}

TEST(SmallBlas, GemvAddsAlphaAxOrAlphaATransposedX) {
  std::mt19937 rng(6);
  Block A(9, 4, rng);
  const Eigen::MatrixXd a = A.dense();
  const Eigen::VectorXd x9 = Eigen::VectorXd::LinSpaced(9, 1, 2), x4 = Eigen::VectorXd::LinSpaced(4, -1, 1);
  Eigen::VectorXd y9 = Eigen::VectorXd::Ones(9), y4 = Eigen::VectorXd::Ones(4);
  smallblas::gemvAdd(false, 9, 4, -1.0, A.data.data(), A.ld, x4.data(), y9.data());
  smallblas::gemvAdd(true, 9, 4, 2.0, A.data.data(), A.ld, x9.data(), y4.data());
  EXPECT_LT(maxAbs(y9 - (Eigen::VectorXd::Ones(9) - a * x4)), 1e-14);
  EXPECT_LT(maxAbs(y4 - (Eigen::VectorXd::Ones(4) + 2 * a.transpose() * x9)), 1e-14);
}

// The entry points: a small dgemm_ inside a CholmodScope runs the loops (the count moves), the
// same call outside a scope, one with β ≠ 0 and one above kSmallWork go to the BLAS; every
// result is the product. A non-SPD dpotrf_ reports LAPACK's info either way.
TEST(SmallBlas, EntryPointsTakeSmallCallsInsideAScopeOnly) {
  std::mt19937 rng(7);
  const auto product = [&](int m, int n, int k, double beta, bool scoped) {
    Block A(m, k, rng), B(n, k, rng), C(m, n, rng);
    const Eigen::MatrixXd c0 = C.dense();
    const double one = 1;
    const long before = smallBlasCallCount();
    std::optional<CholmodScope> scope;
    if (scoped) scope.emplace();
    dgemm_("N", "T", &m, &n, &k, &one, A.data.data(), &A.ld, B.data.data(), &B.ld, &beta, C.data.data(), &C.ld, 1, 1);
    scope.reset();
    const Eigen::MatrixXd expected = A.dense() * B.dense().transpose() + beta * c0;
    EXPECT_LT(maxAbs(C.dense() - expected), 1e-12) << m << "×" << n << "×" << k;
    return smallBlasCallCount() - before;
  };
  EXPECT_EQ(product(8, 6, 5, 0.0, true), 1);
  EXPECT_EQ(product(8, 6, 5, 0.0, false), 0);
  EXPECT_EQ(product(8, 6, 5, 1.0, true), 0);
  EXPECT_EQ(product(40, 30, 20, 0.0, true), 0);  // 24 000 multiply-adds > kSmallWork
  static_assert(40L * 30 * 20 > smallblas::kSmallWork && 8L * 6 * 5 <= smallblas::kSmallWork);
  for (const bool scoped : {true, false}) {
    Block D = spdBlock(3, rng);
    D.at(1, 1) = -1;
    int n = 3, info = 0;
    std::optional<CholmodScope> scope;
    if (scoped) scope.emplace();
    dpotrf_("L", &n, D.data.data(), &D.ld, &info, 1);
    EXPECT_EQ(info, 2) << (scoped ? "scoped" : "unscoped");
  }
}
