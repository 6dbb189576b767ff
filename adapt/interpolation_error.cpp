#include "ablmg/adapt/interpolation_error.hpp"

#include "ablmg/core/error.hpp"

#include <array>
#include <cmath>

namespace ablmg::adapt {
namespace {

/// ∫_T λ_i λ_j λ_k λ_l / |T| for vertex indices i, j, k, l ∈ {0, 1, 2}: 2 p! q! r! / 6!.
double quarticMoment(int i, int j, int k, int l) {
  int count[3] = {0, 0, 0};
  ++count[i], ++count[j], ++count[k], ++count[l];
  constexpr double factorial[5] = {1, 1, 2, 6, 24};
  return 2 * factorial[count[0]] * factorial[count[1]] * factorial[count[2]] / 720.0;
}

}  // namespace

InterpolationErrorEstimate estimateInterpolationError(const Mesh2& mesh, std::span<const Hessian2> hessians) {
  ABLMG_REQUIRE(
      long(hessians.size()) == long(mesh.numVertices()),
      "estimateInterpolationError: " << hessians.size() << " Hessians for " << mesh.numVertices() << " vertices");
  constexpr std::array<std::array<int, 2>, 3> kEdges{{{0, 1}, {0, 2}, {1, 2}}};
  std::array<std::array<double, 3>, 3> moment{};  // moment[e][f] = ∫ λ_i λ_j λ_k λ_l / |T|
  for (int e = 0; e < 3; ++e)
    for (int f = 0; f < 3; ++f) moment[e][f] = quarticMoment(kEdges[e][0], kEdges[e][1], kEdges[f][0], kEdges[f][1]);

  InterpolationErrorEstimate out;
  out.elementL2.resize(std::size_t(mesh.numTriangles()));
  double sum = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tri = mesh.triangles[std::size_t(t)];
    const Hessian2 h = (hessians[tri[0]] + hessians[tri[1]] + hessians[tri[2]]) / 3.0;
    std::array<double, 3> a{};
    for (int e = 0; e < 3; ++e) {
      const Vec2 d = mesh.vertices[tri[kEdges[e][1]]] - mesh.vertices[tri[kEdges[e][0]]];
      a[e] = d.dot(h * d);
    }
    const Vec2 &p = mesh.vertices[tri[0]], &q = mesh.vertices[tri[1]], &r = mesh.vertices[tri[2]];
    const double area = 0.5 * std::abs(cross(q - p, r - p));
    double s = 0;
    for (int e = 0; e < 3; ++e)
      for (int f = 0; f < 3; ++f) s += a[e] * a[f] * moment[e][f];
    const double e2 = 0.25 * area * s;
    out.elementL2[std::size_t(t)] = std::sqrt(std::max(e2, 0.0));
    sum += e2;
  }
  out.l2 = std::sqrt(sum);
  return out;
}

}  // namespace ablmg::adapt
