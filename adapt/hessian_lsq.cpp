#include "ablmg/adapt/hessian_recovery.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <utility>

namespace ablmg::adapt {
namespace {
/// Below this many vertices the patch fits run on the calling thread: waking an OpenMP team
/// costs more than ~2000 small least-squares fits (and far more under OMP_WAIT_POLICY=passive).
/// Each vertex's fit is independent, so the result is the same for any team size.
constexpr int kMinParallelVertices = 2048;
}  // namespace

namespace detail {
void forEachVertex(int n, const std::function<void(int, std::vector<int>&, std::vector<int>&)>& fit) {
  ParallelFailure failure;  // exceptions must not leave the region: the lowest vertex's is rethrown
#pragma omp parallel if (n >= kMinParallelVertices)
  {
    std::vector<int> patch, mark(std::size_t(n), 0);
#pragma omp for schedule(dynamic, 256)
    for (int v = 0; v < n; ++v) failure.run(v, [&] { fit(v, patch, mark); });
  }
  failure.rethrow();
}

namespace {
/// The patch fit in the patch's principal frame, each axis scaled by the patch's extent along
/// it: (s, t) = T (x − x_v), T = diag(1/e₁, 1/e₂) Qᵀ with Q the eigenvectors of Σ d dᵀ. The
/// least-squares quadratic is the same in any affine frame (exactness for quadratics holds);
/// only the conditioning changes. Coefficients back in x: ∇ = Tᵀ ∇_st, H = Tᵀ H_st T.
/// Nothing (std::nullopt) if the scaled system still fails the |R_55| ≥ 1e-6 |R_00| test.
/// One fit per field of `fields` (the same patch and QR), into out[k]; false = nothing fitted.
bool anisotropicFit(const Mesh2& mesh, const std::vector<int>& patch, const Vec2& xv,
                    std::span<const std::span<const double>> fields, std::span<Eigen::Matrix<double, 6, 1>> out) {
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int w : patch) {
    const Vec2 d = mesh.vertices[w] - xv;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Matrix2d Q = eig.eigenvectors();
  double e1 = 0, e2 = 0;
  for (int w : patch) {
    const Vec2 p = Q.transpose() * (mesh.vertices[w] - xv);
    e1 = std::max(e1, std::abs(p.x()));
    e2 = std::max(e2, std::abs(p.y()));
  }
  if (!(e1 > 0 && e2 > 0)) return false;  // collinear: only growth can help
  const Eigen::Matrix2d T = Eigen::Vector2d(1 / e1, 1 / e2).asDiagonal() * Q.transpose();
  const int m = int(patch.size());
  Eigen::MatrixXd A(m, 6);
  for (int i = 0; i < m; ++i) {
    const Vec2 q = T * (mesh.vertices[patch[i]] - xv);
    A.row(i) << 1.0, q.x(), q.y(), q.x() * q.x(), q.x() * q.y(), q.y() * q.y();
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  const auto R = qr.matrixR();
  if (!(std::abs(R(5, 5)) >= 1e-6 * std::abs(R(0, 0)))) return false;
  Eigen::VectorXd b(m);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    for (int i = 0; i < m; ++i) b[i] = fields[k][std::size_t(patch[std::size_t(i)])];
    const Eigen::Matrix<double, 6, 1> c = qr.solve(b);
    const Vec2 grad = T.transpose() * Vec2(c[1], c[2]);
    Eigen::Matrix2d Hst;
    Hst << 2 * c[3], c[4], c[4], 2 * c[5];
    const Eigen::Matrix2d H = T.transpose() * Hst * T;
    out[k] << c[0], grad.x(), grad.y(), 0.5 * H(0, 0), 0.5 * (H(0, 1) + H(1, 0)), 0.5 * H(1, 1);
  }
  return true;
}
}  // namespace

void checkField(const Mesh2& mesh, std::span<const double> u, const char* where) {
  ABLMG_REQUIRE(long(u.size()) == long(mesh.numVertices()),
                where << ": " << u.size() << " values for " << mesh.numVertices() << " vertices");
  for (int v = 0; v < mesh.numVertices(); ++v)
    ABLMG_REQUIRE(std::isfinite(u[v]), where << ": value at vertex " << v << " is not finite (" << u[v] << ")");
}

VertexGraph vertexGraph(const Mesh2& mesh) {
  VertexGraph g;
  const int n = mesh.numVertices();
  const auto edges = mesh.edges();
  g.offsets.assign(n + 1, 0);
  for (const auto& e : edges) {
    ++g.offsets[e[0] + 1];
    ++g.offsets[e[1] + 1];
  }
  for (int v = 0; v < n; ++v) g.offsets[v + 1] += g.offsets[v];
  g.ids.resize(g.offsets[n]);
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (const auto& e : edges) {  // edges are sorted, so each list comes out sorted
    g.ids[fill[e[0]]++] = e[1];
    g.ids[fill[e[1]]++] = e[0];
  }
  for (int v = 0; v < n; ++v) std::sort(g.ids.begin() + g.offsets[v], g.ids.begin() + g.offsets[v + 1]);
  g.onBoundary.assign(n, 0);
  for (const auto& be : mesh.boundaryEdges) g.onBoundary[be.a] = g.onBoundary[be.b] = 1;
  return g;
}

Eigen::Matrix<double, 6, 1> patchQuadraticFit(const Mesh2& mesh, const VertexGraph& g, std::span<const double> u, int v,
                                              std::vector<int>& patch, std::vector<int>& mark) {
  Eigen::Matrix<double, 6, 1> a;
  const std::span<const double> fields[1] = {u};
  patchQuadraticFits(mesh, g, fields, v, patch, mark, std::span<Eigen::Matrix<double, 6, 1>>(&a, 1));
  return a;
}

void patchQuadraticFits(const Mesh2& mesh, const VertexGraph& g, std::span<const std::span<const double>> fields, int v,
                        std::vector<int>& patch, std::vector<int>& mark, std::span<Eigen::Matrix<double, 6, 1>> out) {
  // Ring-by-ring breadth-first growth; `mark[w] == v + 1` flags members (reset-free).
  patch.clear();
  patch.push_back(v);
  mark[v] = v + 1;
  std::size_t ringBegin = 0;
  const int minRings = g.onBoundary[v] ? 2 : 1;
  const Vec2 xv = mesh.vertices[v];
  for (int ring = 1;; ++ring) {
    const std::size_t ringEnd = patch.size();
    for (std::size_t k = ringBegin; k < ringEnd; ++k) {
      const int w = patch[k];
      for (int j = g.offsets[w]; j < g.offsets[w + 1]; ++j) {
        const int z = g.ids[j];
        if (mark[z] != v + 1) {
          mark[z] = v + 1;
          patch.push_back(z);
        }
      }
    }
    ringBegin = ringEnd;
    const bool grew = patch.size() > ringEnd;
    if (ring < minRings && grew) continue;
    if (patch.size() < 9 && grew) continue;
    // Scaled Vandermonde: columns 1, s, t, s², st, t² with (s, t) = (x − x_v) / r.
    double r = 0;
    for (int w : patch) r = std::max(r, (mesh.vertices[w] - xv).norm());
    ABLMG_REQUIRE(r > 0, "recoverHessians: isolated vertex " << v);
    const int m = int(patch.size());
    Eigen::MatrixXd A(m, 6);
    for (int i = 0; i < m; ++i) {
      const Vec2 d = (mesh.vertices[patch[i]] - xv) / r;
      A.row(i) << 1.0, d.x(), d.y(), d.x() * d.x(), d.x() * d.y(), d.y() * d.y();
    }
    if (m >= 6) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
      const auto R = qr.matrixR();
      const double r0 = std::abs(R(0, 0)), r5 = std::abs(R(5, 5));
      if (r5 >= 1e-6 * r0 || !grew) {
        ABLMG_REQUIRE(r5 > 1e-13 * r0, "recoverHessians: the patch of vertex " << v << " cannot determine a quadratic ("
                                                                               << m
                                                                               << " points, whole component used)");
        Eigen::VectorXd b(m);
        for (std::size_t k = 0; k < fields.size(); ++k) {
          for (int i = 0; i < m; ++i) b[i] = fields[k][std::size_t(patch[std::size_t(i)])];
          Eigen::Matrix<double, 6, 1>& a = out[k];
          a = qr.solve(b);
          a[1] /= r;
          a[2] /= r;
          a[3] /= r * r;
          a[4] /= r * r;
          a[5] /= r * r;
        }
        return;
      }
      // A thin patch (aspect ratio beyond ~10³: the t² column is ~1e-6 of the s² one) fails the
      // test above although its points determine a quadratic; growing it ring by ring would take
      // thousands of rings along a layer. Refit in the patch's principal frame instead.
      if (anisotropicFit(mesh, patch, xv, fields, out)) return;
    }
    ABLMG_REQUIRE(grew,
                  "recoverHessians: the connected piece of vertex " << v << " has only " << m << " vertices (< 6)");
  }
}

}  // namespace detail

HessianMethod parseHessianMethod(const std::string& name) {
  if (name == "lsq") return HessianMethod::LeastSquares;
  if (name == "double") return HessianMethod::DoubleRecovery;
  ABLMG_REQUIRE(false, "unknown Hessian recovery method '" << name << "' (valid: lsq, double)");
  return HessianMethod::LeastSquares;
}

std::string toString(HessianMethod m) { return m == HessianMethod::LeastSquares ? "lsq" : "double"; }

std::vector<Vec2> recoverGradients(const Mesh2& mesh, std::span<const double> u) {
  detail::checkField(mesh, u, "recoverGradients");
  const auto g = detail::vertexGraph(mesh);
  const int n = mesh.numVertices();
  std::vector<Vec2> out(n);
  const auto fit = [&](int v, std::vector<int>& patch, std::vector<int>& mark) {
    const auto a = detail::patchQuadraticFit(mesh, g, u, v, patch, mark);
    out[v] = Vec2(a[1], a[2]);
  };
  detail::forEachVertex(n, fit);
  return out;
}

namespace {
/// The least-squares Hessians of each field (one patch and QR per vertex for all of them).
template <std::size_t K>
std::array<std::vector<Hessian2>, K> lsqHessians(const Mesh2& mesh, const std::span<const double> (&fields)[K]) {
  const auto g = detail::vertexGraph(mesh);
  const int n = mesh.numVertices();
  std::array<std::vector<Hessian2>, K> out;
  for (auto& h : out) h.resize(std::size_t(n));
  const auto fit = [&](int v, std::vector<int>& patch, std::vector<int>& mark) {
    Eigen::Matrix<double, 6, 1> a[K];
    detail::patchQuadraticFits(mesh, g, fields, v, patch, mark, a);
    for (std::size_t k = 0; k < K; ++k) out[k][std::size_t(v)] << 2 * a[k][3], a[k][4], a[k][4], 2 * a[k][5];
  };
  detail::forEachVertex(n, fit);
  return out;
}

std::vector<Hessian2> lsqHessians(const Mesh2& mesh, std::span<const double> u) {
  const std::span<const double> fields[1] = {u};
  return std::move(lsqHessians(mesh, fields)[0]);
}
}  // namespace

std::vector<Hessian2> recoverHessiansDouble(const Mesh2& mesh, std::span<const double> u);  // hessian_double_l2.cpp

std::array<std::vector<Hessian2>, 2> recoverHessians(const Mesh2& mesh, std::span<const double> u,
                                                     std::span<const double> z, HessianMethod method) {
  if (method != HessianMethod::LeastSquares || detail::hasSeveralSubdomains(mesh))
    return {recoverHessians(mesh, u, method), recoverHessians(mesh, z, method)};
  detail::checkField(mesh, u, "recoverHessians");
  detail::checkField(mesh, z, "recoverHessians");
  const std::span<const double> fields[2] = {u, z};
  return lsqHessians(mesh, fields);
}

namespace detail {
std::vector<Hessian2> recoverHessiansOneDomain(const Mesh2& mesh, std::span<const double> u, HessianMethod method) {
  return method == HessianMethod::LeastSquares ? lsqHessians(mesh, u) : recoverHessiansDouble(mesh, u);
}
}  // namespace detail

std::vector<Hessian2> recoverHessians(const Mesh2& mesh, std::span<const double> u, HessianMethod method) {
  detail::checkField(mesh, u, "recoverHessians");
  if (detail::hasSeveralSubdomains(mesh)) return detail::recoverPerSubdomain(mesh, u, method);
  return detail::recoverHessiansOneDomain(mesh, u, method);
}

}  // namespace ablmg::adapt
