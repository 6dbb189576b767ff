#include "ablmg/adapt/gradation.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ablmg::adapt {

double maxGeneralisedEigenvalue(const Metric2& a, const Metric2& b) {
  // Eigenvalues of B⁻¹A solve det(A − μB) = 0: det(B) μ² − (a11 b22 + a22 b11 − 2 a12 b12) μ + det(A) = 0.
  const double db = b.det(), da = a.det();
  const double tr = a.m11() * b.m22() + a.m22() * b.m11() - 2 * a.m12() * b.m12();
  const double disc = std::max(tr * tr - 4 * db * da, 0.0);
  return (tr + std::sqrt(disc)) / (2 * db);
}

GradationStats limitGradation(const Mesh2& mesh, std::vector<Metric2>& metrics, const GradationOptions& o) {
  ABLMG_REQUIRE(o.hgrad > 1 && std::isfinite(o.hgrad), "gradation: hgrad must be > 1 (got " << o.hgrad << ")");
  ABLMG_REQUIRE(o.tolerance >= 0 && o.tolerance < 1,
                "gradation: tolerance must be in [0, 1) (got " << o.tolerance << ")");
  ABLMG_REQUIRE(long(metrics.size()) == long(mesh.numVertices()),
                "gradation: " << metrics.size() << " metrics for " << mesh.numVertices() << " vertices");
  const auto edges = mesh.edges();
  const double logBeta = std::log(o.hgrad);
  GradationStats stats;
  // Corrects M_j by M_i along i→j; returns true if M_j changed.
  auto relax = [&](int i, int j) {
    const Metric2& mi = metrics[i];
    const Vec2 e = mesh.vertices[j] - mesh.vertices[i];
    const double g = 1.0 + mi.length(e) * logBeta;
    const Metric2 grown = (1.0 / (g * g)) * mi;
    if (maxGeneralisedEigenvalue(grown, metrics[j]) <= 1.0 / (1.0 - o.tolerance)) return false;
    metrics[j] = intersect(metrics[j], grown);
    return true;
  };
  // An edge whose two metrics are unchanged since both its tests last failed would fail them
  // again (relax is a function of the two metrics): it is skipped, which leaves every result,
  // and the sweep count, as without the skip. clock counts the edges tested.
  const long m = long(edges.size());
  std::vector<long> changedAt(std::size_t(mesh.numVertices()), -1), testedAt(std::size_t(m), -2);
  long clock = 0;
  for (int sweep = 0; sweep < o.maxSweeps; ++sweep) {
    long changed = 0;
    for (long k = 0; k < m; ++k) {
      const std::size_t i = std::size_t(sweep % 2 == 0 ? k : m - 1 - k);
      const auto& e = edges[i];
      if (testedAt[i] > changedAt[std::size_t(e[0])] && testedAt[i] > changedAt[std::size_t(e[1])]) continue;
      ++clock;
      if (relax(e[0], e[1])) {
        changedAt[std::size_t(e[1])] = clock;
        ++changed;
      }
      if (relax(e[1], e[0])) {
        changedAt[std::size_t(e[0])] = clock;
        ++changed;
      }
      testedAt[i] = clock;
    }
    stats.sweeps = sweep + 1;
    stats.corrections += changed;
    if (changed == 0) {
      stats.converged = true;
      break;
    }
  }
  return stats;
}

}  // namespace ablmg::adapt
