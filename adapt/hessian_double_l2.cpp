#include "ablmg/adapt/hessian_recovery.hpp"

#include "ablmg/core/error.hpp"

namespace ablmg::adapt {

std::vector<Vec2> areaWeightedGradients(const Mesh2& mesh, std::span<const double> u) {
  detail::checkField(mesh, u, "areaWeightedGradients");
  const int n = mesh.numVertices();
  std::vector<Vec2> sum(n, Vec2::Zero());
  std::vector<double> weight(n, 0.0);
  // Serial scatter in triangle order: deterministic sums.
  for (const auto& t : mesh.triangles) {
    const Vec2 &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]], &p2 = mesh.vertices[t[2]];
    const double twiceArea = cross(p1 - p0, p2 - p0);
    // ∇φ_i = n_i / (2|T|) with n_i = (−e_y, e_x) the inward normal of the opposite edge e_i
    // (CCW triangle), so 2|T| ∇u_h = Σ u_i n_i.
    const auto inward = [](const Vec2& e) { return Vec2(-e.y(), e.x()); };
    const Vec2 gradTimesTwiceArea = u[t[0]] * inward(p2 - p1) + u[t[1]] * inward(p0 - p2) + u[t[2]] * inward(p1 - p0);
    for (int k = 0; k < 3; ++k) {
      sum[t[k]] += 0.5 * gradTimesTwiceArea;  // |T| ∇u_h
      weight[t[k]] += 0.5 * twiceArea;
    }
  }
  for (int v = 0; v < n; ++v) {
    ABLMG_REQUIRE(weight[v] > 0, "areaWeightedGradients: vertex " << v << " is in no triangle");
    sum[v] /= weight[v];
  }
  return sum;
}

std::vector<Hessian2> recoverHessiansDouble(const Mesh2& mesh, std::span<const double> u) {
  const auto grad = recoverGradients(mesh, u);
  const int n = mesh.numVertices();
  std::vector<double> gx(n), gy(n);
  for (int v = 0; v < n; ++v) {
    gx[v] = grad[v].x();
    gy[v] = grad[v].y();
  }
  const auto hx = areaWeightedGradients(mesh, gx);  // (u_xx, u_xy)
  const auto hy = areaWeightedGradients(mesh, gy);  // (u_yx, u_yy)
  std::vector<Hessian2> out(n);
  for (int v = 0; v < n; ++v) {
    const double xy = 0.5 * (hx[v].y() + hy[v].x());
    out[v] << hx[v].x(), xy, xy, hy[v].y();
  }
  return out;
}

}  // namespace ablmg::adapt
