#include "ablmg/mesher/quality.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

namespace ablmg::mesher {
namespace {

void requireOnePerVertex(const Mesh2& mesh, std::span<const Metric2> metrics, const char* what) {
  ABLMG_REQUIRE(long(metrics.size()) == long(mesh.numVertices()),
                what << ": " << metrics.size() << " metrics for " << mesh.numVertices() << " vertices");
}

/// min/mean/max of a non-empty range into s.
template <class Stats>
void minMeanMax(std::span<const double> x, Stats& s) {
  s.count = long(x.size());
  if (x.empty()) return;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  s.min = *lo;
  s.max = *hi;
  double sum = 0;
  for (double v : x) sum += v;
  s.mean = sum / double(x.size());
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100 * fraction);
  return buf;
}

}  // namespace

std::vector<double> edgeMetricLengths(const Mesh2& mesh, std::span<const Metric2> metrics) {
  requireOnePerVertex(mesh, metrics, "edgeMetricLengths");
  std::vector<double> l;
  for (const auto& [a, b] : mesh.edges())
    l.push_back(average(metrics[a], metrics[b]).length(mesh.vertices[b] - mesh.vertices[a]));  // eq. (3)
  return l;
}

double metricJumpShare(const Mesh2& mesh, std::span<const Metric2> metrics, double ratio) {
  requireOnePerVertex(mesh, metrics, "metricJumpShare");
  long jumps = 0;
  for (const auto& [i, j, k] : mesh.triangles)
    for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, k}, std::pair{k, i}}) {
      const Vec2 e = mesh.vertices[std::size_t(b)] - mesh.vertices[std::size_t(a)];
      const double la = metrics[std::size_t(a)].length(e), lb = metrics[std::size_t(b)].length(e);
      jumps += std::max(la, lb) > ratio * std::min(la, lb);
    }
  return mesh.triangles.empty() ? 0.0 : double(jumps) / (3.0 * double(mesh.triangles.size()));
}

double triangleQuality(const Vec2& a, const Vec2& b, const Vec2& c, const Metric2& m) {
  const double areaM = 0.5 * cross(b - a, c - a) * std::sqrt(m.det());
  const double sumL2 = m.squaredLength(b - a) + m.squaredLength(c - b) + m.squaredLength(a - c);
  return sumL2 > 0 ? 4 * std::sqrt(3.0) * areaM / sumL2 : 0.0;
}

std::vector<double> elementQualities(const Mesh2& mesh, std::span<const Metric2> metrics) {
  requireOnePerVertex(mesh, metrics, "elementQualities");
  const int nt = mesh.numTriangles();
  std::vector<double> q(static_cast<std::size_t>(nt));
  // Each q depends on its own triangle only: the same values for any team size.
#pragma omp parallel for schedule(static) if (nt >= kMinParallelItems)
  for (int t = 0; t < nt; ++t) {
    const auto& [i, j, k] = mesh.triangles[std::size_t(t)];
    const Metric2 m = (1.0 / 3.0) * (metrics[i] + metrics[j] + metrics[k]);
    q[std::size_t(t)] = triangleQuality(mesh.vertices[i], mesh.vertices[j], mesh.vertices[k], m);
  }
  return q;
}

std::vector<double> leeAlphas(const Mesh2& mesh, std::span<const Metric2> metrics) {
  ABLMG_REQUIRE(long(metrics.size()) == long(mesh.numVertices()),
                "leeAlphas: " << metrics.size() << " metrics for " << mesh.numVertices() << " vertices");
  std::vector<double> alpha;
  alpha.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Vec2 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    double best = triangleQuality(a, b, c, metrics[t[0]]);
    best = std::min(best, triangleQuality(a, b, c, metrics[t[1]]));
    alpha.push_back(std::min(best, triangleQuality(a, b, c, metrics[t[2]])));
  }
  return alpha;
}

EdgeLengthStats edgeLengthStats(std::span<const double> lengths, double e) {
  ABLMG_REQUIRE(e > 0, "edgeLengthStats: bin width e = " << e << " must be > 0");
  EdgeLengthStats s;
  s.e = e;
  minMeanMax(lengths, s);
  if (lengths.empty()) return s;
  const double n = double(lengths.size());
  for (double l : lengths) {
    s.inSqrt2 += (l >= 1 / std::numbers::sqrt2 && l <= std::numbers::sqrt2) / n;
    s.within10 += (std::abs(l - 1) <= 0.1) / n;
    const double eps = std::abs(l - 1.0);  // eq. (13) with l0 = 1
    int bin = 5;
    for (int k = 0; k < 5; ++k)
      if (eps <= (k + 1) * e) {
        bin = k;
        break;
      }
    s.deviation[bin] += 1 / n;
  }
  return s;
}

ElementQualityStats elementQualityStats(std::span<const double> q) {
  ElementQualityStats s;
  minMeanMax(q, s);
  for (double v : q) {
    const double upper[4] = {0.2, 0.4, 0.6, 0.8};
    s.bins[std::upper_bound(upper, upper + 4, v) - upper] += 1 / double(q.size());  // [lo, hi)
  }
  return s;
}

MeshQuality meshQuality(const Mesh2& mesh, std::span<const Metric2> metrics, double e) {
  MeshQuality r;
  r.dimension = 2;
  r.vertices = mesh.numVertices();
  r.triangles = mesh.numTriangles();
  const MeshValidation v = mesh.validate();
  r.valid = v.ok;
  r.firstProblem = v.firstProblem;
  const auto l = edgeMetricLengths(mesh, metrics);
  r.edges = long(l.size());
  r.edgeLengths = edgeLengthStats(l, e);
  r.elements = elementQualityStats(elementQualities(mesh, metrics));
  r.leeAlpha = elementQualityStats(leeAlphas(mesh, metrics));
  return r;
}

MeshQuality surfaceQuality(const SurfaceMesh& mesh, const Metric3Field& m3, double e) {
  MeshQuality r;
  r.dimension = 3;
  r.vertices = long(mesh.vertices.size());
  r.triangles = long(mesh.triangles.size());
  r.firstProblem = checkManifold(mesh);
  r.valid = r.firstProblem.empty();
  const auto l = surfaceEdgeLengths(mesh, m3);
  r.edges = long(l.size());
  r.edgeLengths = edgeLengthStats(l, e);
  r.elements = elementQualityStats(leeQuality(mesh, m3));
  r.leeAlpha = r.elements;
  return r;
}

std::string toText(const MeshQuality& q) {
  const auto& l = q.edgeLengths;
  const auto& el = q.elements;
  char buf[256];
  std::string s;
  std::snprintf(buf, sizeof buf, "%ldD mesh: %ld vertices, %ld triangles, %ld edges; valid: %s\n", long(q.dimension),
                q.vertices, q.triangles, q.edges, q.valid ? "yes" : "no");
  s += buf;
  if (!q.valid) s += "  first problem: " + q.firstProblem + "\n";
  std::snprintf(buf, sizeof buf, "edge length l:   min %.4g  mean %.4g  max %.4g\n", l.min, l.mean, l.max);
  s += buf;
  s += "  l in [1/sqrt2, sqrt2]: " + percent(l.inSqrt2) + "   |l-1| <= 0.1: " + percent(l.within10) + "\n";
  std::snprintf(buf, sizeof buf, "  deviation eps = |l-1| (eq. 13), e = %g:\n", l.e);
  s += buf;
  s += "    <=e " + percent(l.deviation[0]);
  for (int k = 1; k < 5; ++k)
    s += "  " + (k == 1 ? std::string() : std::to_string(k)) + "e-" + std::to_string(k + 1) + "e " +
         percent(l.deviation[k]);
  s += "  >5e " + percent(l.deviation[5]) + "\n";
  std::snprintf(buf, sizeof buf, "element quality %s:   min %.4g  mean %.4g  max %.4g\n",
                q.dimension == 2 ? "q" : "alpha (Lee)", el.min, el.mean, el.max);
  s += buf;
  const auto bins = [&](const ElementQualityStats& st) {
    s += "   ";
    for (int k = 0; k < 5; ++k) {
      std::snprintf(buf, sizeof buf, " %.1f-%.1f %s", 0.2 * k, 0.2 * (k + 1), percent(st.bins[k]).c_str());
      s += buf;
    }
    s += "\n";
  };
  bins(el);
  if (q.dimension == 2) {
    std::snprintf(buf, sizeof buf, "alpha (Lee, eqs. 19-20, vertex metrics):   min %.4g  mean %.4g  max %.4g\n",
                  q.leeAlpha.min, q.leeAlpha.mean, q.leeAlpha.max);
    s += buf;
    bins(q.leeAlpha);
  }
  return s;
}

}  // namespace ablmg::mesher
