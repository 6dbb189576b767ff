#include "adapt/hessian_recovery.hpp"

#include "core/error.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace ablmg::adapt {
namespace {
/// Below this many vertices the patch fits run on the calling thread: waking an OpenMP team
/// costs more than ~2000 small least-squares fits (and far more under OMP_WAIT_POLICY=passive).
/// Each vertex's fit is independent, so the result is the same for any team size.
constexpr int kMinParallelVertices = 2048;
} // namespace

namespace detail {

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
    Eigen::VectorXd b(m);
    for (int i = 0; i < m; ++i) {
      const Vec2 d = (mesh.vertices[patch[i]] - xv) / r;
      A.row(i) << 1.0, d.x(), d.y(), d.x() * d.x(), d.x() * d.y(), d.y() * d.y();
      b[i] = u[patch[i]];
    }
    if (m >= 6) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
      const auto R = qr.matrixR();
      const double r0 = std::abs(R(0, 0)), r5 = std::abs(R(5, 5));
      if (r5 >= 1e-6 * r0 || !grew) {
        ABLMG_REQUIRE(r5 > 1e-13 * r0, "recoverHessians: the patch of vertex "
                                           << v << " cannot determine a quadratic (" << m << " points, whole component used)");
        Eigen::Matrix<double, 6, 1> a = qr.solve(b);
        a[1] /= r;
        a[2] /= r;
        a[3] /= r * r;
        a[4] /= r * r;
        a[5] /= r * r;
        return a;
      }
    }
    ABLMG_REQUIRE(grew, "recoverHessians: the connected piece of vertex " << v << " has only " << m << " vertices (< 6)");
  }
}

} // namespace detail

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
#pragma omp parallel if (n >= kMinParallelVertices)
  {
    std::vector<int> patch, mark(n, 0);
#pragma omp for schedule(dynamic, 256)
    for (int v = 0; v < n; ++v) {
      const auto a = detail::patchQuadraticFit(mesh, g, u, v, patch, mark);
      out[v] = Vec2(a[1], a[2]);
    }
  }
  return out;
}

namespace {
std::vector<Hessian2> lsqHessians(const Mesh2& mesh, std::span<const double> u) {
  const auto g = detail::vertexGraph(mesh);
  const int n = mesh.numVertices();
  std::vector<Hessian2> out(n);
#pragma omp parallel if (n >= kMinParallelVertices)
  {
    std::vector<int> patch, mark(n, 0);
#pragma omp for schedule(dynamic, 256)
    for (int v = 0; v < n; ++v) {
      const auto a = detail::patchQuadraticFit(mesh, g, u, v, patch, mark);
      out[v] << 2 * a[3], a[4], a[4], 2 * a[5];
    }
  }
  return out;
}
} // namespace

std::vector<Hessian2> recoverHessiansDouble(const Mesh2& mesh, std::span<const double> u);  // hessian_double_l2.cpp

std::vector<Hessian2> recoverHessians(const Mesh2& mesh, std::span<const double> u, HessianMethod method) {
  detail::checkField(mesh, u, "recoverHessians");
  return method == HessianMethod::LeastSquares ? lsqHessians(mesh, u) : recoverHessiansDouble(mesh, u);
}

} // namespace ablmg::adapt
