#include "ablmg/adapt/dual_weight.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace ablmg::adapt {

fem::PoissonProblem unitLoadDual(const fem::PoissonProblem& problem) {
  fem::PoissonProblem d;
  d.kappa = problem.kappa;
  d.kappaBySubdomain = problem.kappaBySubdomain;
  for (const auto& [ref, f] : problem.fBySubdomain) d.fBySubdomain[ref] = 1.0;
  d.f = 1.0;
  for (const auto& [tag, g] : problem.dirichlet) d.dirichlet[tag] = 0.0;
  if (problem.hasDirichletDefault) d.setDirichletEverywhere(0.0);
  // Tags with Neumann data stay Neumann (listed with zero flux, so the default Dirichlet skips them).
  for (const auto& [tag, g] : problem.neumann) d.neumann[tag] = 0.0;
  d.threadSafeFunctions = problem.threadSafeFunctions;
  return d;
}

namespace {
/// Per triangle: ‖G v − ∇v‖_T (3-vertex rule), G the area-weighted vertex mean of the gradients
/// of the triangles around the vertex with the same triangle ref (so that the gradient jump of a
/// κ jump across a material interface is not mistaken for an error).
std::vector<double> recoveryErrors(const Mesh2& mesh, std::span<const double> v) {
  const int nt = mesh.numTriangles();
  const bool refs = long(mesh.triangleRefs.size()) == long(nt);
  auto key = [&](int vertex, int t) {
    return (std::int64_t(vertex) << 32) | std::uint32_t(refs ? mesh.triangleRefs[std::size_t(t)] : 0);
  };
  std::vector<Vec2> grad(nt);
  std::unordered_map<std::int64_t, std::pair<Vec2, double>> acc;
  acc.reserve(std::size_t(mesh.numVertices()) * 2);
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec2 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    const Vec2 e1 = b - a, e2 = c - a;
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    const double d1 = v[tri[1]] - v[tri[0]], d2 = v[tri[2]] - v[tri[0]];
    grad[t] = Vec2(d1 * e2.y() - d2 * e1.y(), d2 * e1.x() - d1 * e2.x()) / det;
    const double area = 0.5 * std::abs(det);
    for (int k = 0; k < 3; ++k) {
      auto& [g, w] = acc.try_emplace(key(tri[k], t), Vec2::Zero(), 0.0).first->second;
      g += area * grad[t];
      w += area;
    }
  }
  std::vector<double> out(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const auto& [g, w] = acc.at(key(tri[k], t));
      s += (g / w - grad[t]).squaredNorm();
    }
    out[t] = std::sqrt(mesh.triangleArea(t) * s / 3);
  }
  return out;
}
}  // namespace

std::vector<double> recoveryErrorIndicators(const Mesh2& mesh, std::span<const double> u) {
  ABLMG_REQUIRE(long(u.size()) == long(mesh.numVertices()),
                "recoveryErrorIndicators: " << u.size() << " values for " << mesh.numVertices() << " vertices");
  return recoveryErrors(mesh, u);
}

std::vector<double> densityWeightScale(const Mesh2& mesh, std::span<const double> u, std::span<const double> z,
                                       double dualGamma, double h1Gamma) {
  ABLMG_REQUIRE(
      dualGamma >= 0 && h1Gamma >= 0 && dualGamma + h1Gamma > 0 && std::isfinite(dualGamma + h1Gamma),
      "densityWeightScale: exponents must be >= 0, not both 0 (got " << dualGamma << " and " << h1Gamma << ")");
  if (!(dualGamma > 0)) return dualWeightScale(mesh, recoveryErrorIndicators(mesh, u), h1Gamma);
  // η_T ε_T^(γ₁/γ), raised to γ by dualWeightScale: ε^(γ+γ₁) ε_z^γ.
  std::vector<double> eta = dualWeightedIndicators(mesh, u, z);
  if (h1Gamma > 0) {
    const std::vector<double> eu = recoveryErrors(mesh, u);
    for (std::size_t t = 0; t < eta.size(); ++t) eta[t] *= std::pow(eu[t], h1Gamma / dualGamma);
  }
  return dualWeightScale(mesh, eta, dualGamma);
}

std::vector<double> dualWeightedIndicators(const Mesh2& mesh, std::span<const double> u, std::span<const double> z) {
  ABLMG_REQUIRE(long(u.size()) == long(mesh.numVertices()) && long(z.size()) == long(mesh.numVertices()),
                "dualWeightedIndicators: " << u.size() << " and " << z.size() << " values for " << mesh.numVertices()
                                           << " vertices");
  std::vector<double> eta = recoveryErrors(mesh, u);
  const std::vector<double> ez = recoveryErrors(mesh, z);
  for (std::size_t t = 0; t < eta.size(); ++t) eta[t] *= ez[t];
  return eta;
}

std::vector<double> dualWeightScale(const Mesh2& mesh, std::span<const double> eta, double gamma) {
  ABLMG_REQUIRE(long(eta.size()) == long(mesh.numTriangles()),
                "dualWeightScale: " << eta.size() << " indicators for " << mesh.numTriangles() << " triangles");
  ABLMG_REQUIRE(gamma > 0 && std::isfinite(gamma), "dualWeightScale: gamma must be > 0 (got " << gamma << ")");
  std::vector<double> s(mesh.numVertices(), 1.0);
  const double top = eta.empty() ? 0.0 : *std::max_element(eta.begin(), eta.end());
  if (!(top > 0)) return s;
  double logMean = 0;
  std::vector<double> p(eta.size());
  for (std::size_t t = 0; t < eta.size(); ++t) {
    p[t] = std::log(std::max(eta[t], 1e-12 * top));
    logMean += p[t];
  }
  logMean /= double(eta.size());
  std::vector<double> sum(mesh.numVertices(), 0.0);
  std::vector<int> count(mesh.numVertices(), 0);
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const double w = std::exp(gamma * (p[t] - logMean));
    for (int v : mesh.triangles[t]) {
      sum[v] += w;
      ++count[v];
    }
  }
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (count[v] > 0) s[v] = sum[v] / count[v];
  for (double& x : s) x = std::clamp(x, 1 / kMaxFactor, kMaxFactor);
  return s;
}

}  // namespace ablmg::adapt
