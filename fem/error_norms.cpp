#include "ablmg/fem/error_norms.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/fem/quadrature.hpp"

#include <cmath>
#include <limits>

namespace ablmg::fem {

Eigen::VectorXd interpolate(const Mesh2& mesh, const ScalarFn& u) {
  ABLMG_REQUIRE(bool(u), "interpolate: no function given");
  Eigen::VectorXd r(mesh.numVertices());
  for (int v = 0; v < mesh.numVertices(); ++v) r[v] = u(mesh.vertices[v].x(), mesh.vertices[v].y());
  return r;
}

ErrorReport computeErrors(const Mesh2& mesh, const Eigen::VectorXd& uh, const ExactSolution& exact, int degree) {
  ABLMG_REQUIRE(bool(exact.u), "computeErrors: the exact solution u is empty");
  ABLMG_REQUIRE(uh.size() == mesh.numVertices(), "computeErrors: " << uh.size() << " solution values for a mesh of "
                                                                   << mesh.numVertices() << " vertices");
  const TriangleRule& rule = triangleRule(degree);
  const bool withGrad = bool(exact.grad);
  const bool both = withGrad && bool(exact.valueAndGrad);
  ErrorReport r;
  const int nt = mesh.numTriangles();
  r.elementL2.resize(nt);
  if (withGrad) r.elementH1.resize(nt);
  const Eigen::VectorXd ui = interpolate(mesh, exact.u);
  std::vector<double> interpSq(nt);
  // Per-element squared errors, in parallel when allowed; summed serially in triangle order.
  // A throwing exact solution: the error of the lowest triangle is rethrown after the loop.
  ParallelFailure failure;
#pragma omp parallel for schedule(static) if (exact.threadSafe && nt > 4096)
  for (int t = 0; t < nt; ++t) {
    failure.run(t, [&] {
      const auto& tri = mesh.triangles[t];
      const Vec2 p[3] = {mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]};
      const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
      // ∇u_h = Σ_k u_k ∇λ_k, ∇λ_k = perp(opposite edge) / (2|T|)
      double gx = 0, gy = 0;
      for (int k = 0; k < 3; ++k) {
        const Vec2& a = p[(k + 1) % 3];
        const Vec2& b = p[(k + 2) % 3];
        gx += uh[tri[k]] * (a.y() - b.y()) / (2 * area);
        gy += uh[tri[k]] * (b.x() - a.x()) / (2 * area);
      }
      const Vec2 gradUh(gx, gy);
      double e0 = 0, e1 = 0, ei = 0;
      for (int q = 0; q < rule.size(); ++q) {
        const auto& l = rule.points[q];
        const Vec2 x = l[0] * p[0] + l[1] * p[1] + l[2] * p[2];
        Vec2 grad;
        const double u = both ? exact.valueAndGrad(x.x(), x.y(), grad) : exact.u(x.x(), x.y());
        if (withGrad && !both) grad = exact.grad(x.x(), x.y());
        const double uhq = l[0] * uh[tri[0]] + l[1] * uh[tri[1]] + l[2] * uh[tri[2]];
        const double uiq = l[0] * ui[tri[0]] + l[1] * ui[tri[1]] + l[2] * ui[tri[2]];
        e0 += rule.weights[q] * (u - uhq) * (u - uhq);
        ei += rule.weights[q] * (u - uiq) * (u - uiq);
        if (withGrad) e1 += rule.weights[q] * (grad - gradUh).squaredNorm();
      }
      r.elementL2[t] = area * e0;  // squared for now
      interpSq[t] = area * ei;
      if (withGrad) r.elementH1[t] = area * e1;
    });
  }
  failure.rethrow();
  double l2 = 0, h1 = 0, l2i = 0;
  for (int t = 0; t < nt; ++t) {
    l2 += r.elementL2[t];
    l2i += interpSq[t];
    r.elementL2[t] = std::sqrt(r.elementL2[t]);
    if (withGrad) {
      h1 += r.elementH1[t];
      r.elementH1[t] = std::sqrt(r.elementH1[t]);
    }
  }
  r.l2 = std::sqrt(l2);
  r.l2Interp = std::sqrt(l2i);
  r.h1 = withGrad ? std::sqrt(h1) : std::numeric_limits<double>::quiet_NaN();
  r.maxVertex = (ui - uh).cwiseAbs().maxCoeff();
  return r;
}

double interpolationErrorL2(const Mesh2& mesh, const ScalarFn& u, int degree) {
  return computeErrors(mesh, interpolate(mesh, u), ExactSolution{u, {}, false, {}}, degree).l2;
}

}  // namespace ablmg::fem
