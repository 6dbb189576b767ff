#include "ablmg/mesher/defects.hpp"
#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace ablmg::mesher {
namespace {

/// y = Lᵀ d with M = L Lᵀ (Cholesky), so |y|² = dᵀ M d.
Vec2 toMetric(const Metric2& m, const Vec2& d) {
  const double a = std::sqrt(m.m11());
  const double b = m.m12() / a;
  const double c = std::sqrt(std::max(m.m22() - b * b, 0.0));
  return {a * d.x() + b * d.y(), c * d.y()};
}

struct CellVertex {
  Vec2 p;
  int label;  ///< the neighbour whose bisector carries the edge from p to the next vertex (−1: the square)
};

/// Voronoi cell of the origin among `pts` (Sutherland–Hodgman clipping of the square
/// [−2, 2]² by the half-planes y·p ≤ |y|²/2), counter-clockwise, each edge labelled, into
/// `poly`; `next` is scratch (both reused from node to node: no allocation once grown).
void voronoiCell(const std::vector<std::pair<Vec2, int>>& pts, std::vector<CellVertex>& poly,
                 std::vector<CellVertex>& next) {
  poly.assign({{{-2, -2}, -1}, {{2, -2}, -1}, {{2, 2}, -1}, {{-2, 2}, -1}});
  for (const auto& [y, id] : pts) {
    const double h = 0.5 * y.squaredNorm();
    next.clear();
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
      const CellVertex& a = poly[k];
      const CellVertex& b = poly[(k + 1) % n];
      const double fa = y.dot(a.p) - h, fb = y.dot(b.p) - h;
      const bool ina = fa <= 0, inb = fb <= 0;
      if (ina) next.push_back(a);
      if (ina != inb) next.push_back({a.p + (fa / (fa - fb)) * (b.p - a.p), ina ? id : a.label});
    }
    poly.swap(next);
    if (poly.empty()) break;
  }
}

}  // namespace

LocalTopology localTopology(std::span<const Vec2> x, std::span<const Metric2> m, std::span<const NodeKind> kinds,
                            const AdjacencyLists& adj, double minEdge, int stride) {
  const int n = adj.size();
  std::vector<std::vector<int>> rows;
  rows.resize(std::size_t(n));
  ParallelFailure failure;  // the cells allocate: rethrown after the region, the lowest node's
#pragma omp parallel if (n >= kMinParallelItems)
  {
    std::vector<std::pair<Vec2, int>> pts;  // per thread, reused
    std::vector<CellVertex> cell, scratch;
    std::vector<int> ring;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < n; ++i)
      failure.run(i, [&] {
        if (kinds[i] != NodeKind::Interior || i % stride != 0) return;
        pts.clear();
        for (int j : adj.neighbours(i)) pts.push_back({toMetric(m[i], x[j] - x[i]), j});
        voronoiCell(pts, cell, scratch);
        ring.clear();
        bool closed = !cell.empty();
        for (std::size_t k = 0; k < cell.size() && closed; ++k) {
          if (cell[k].label < 0)
            closed = false;
          else if ((cell[(k + 1) % cell.size()].p - cell[k].p).norm() >= minEdge)
            ring.push_back(cell[k].label);
        }
        if (closed) rows[std::size_t(i)] = ring;
      });
  }
  failure.rethrow();
  LocalTopology t;
  t.degree.assign(std::size_t(n), -1);
  t.offsets.reserve(std::size_t(n) + 1);
  for (int i = 0; i < n; ++i) {
    const auto& r = rows[std::size_t(i)];
    if (!r.empty()) t.degree[std::size_t(i)] = int(r.size());
    t.ids.insert(t.ids.end(), r.begin(), r.end());
    t.offsets.push_back(int(t.ids.size()));
  }
  return t;
}

DefectCounts countDefects(const LocalTopology& t) {
  DefectCounts c;
  for (int d : t.degree) {
    if (d < 0) continue;
    ++c.interior;
    c.five += d == 5;
    c.seven += d == 7;
    c.other += d != 5 && d != 6 && d != 7;
  }
  return c;
}

std::vector<char> defectNeighbourhood(const LocalTopology& t, int rings) {
  const std::size_t n = t.degree.size();
  std::vector<char> mask(n, 0);
  for (std::size_t i = 0; i < n; ++i) mask[i] = t.degree[i] >= 0 && t.degree[i] != 6;
  for (int r = 0; r < rings; ++r) {
    std::vector<char> next = mask;
    for (std::size_t i = 0; i < n; ++i)
      if (mask[i])
        for (int j : t.ring(int(i))) next[std::size_t(j)] = 1;
    mask.swap(next);
  }
  return mask;
}

long shakeNodes(BubbleSystem& sys, const DomainGeometry& geo, std::span<const char> flagged, double amplitude,
                int pass) {
  long moved = 0;
  for (int i = 0; i < sys.size(); ++i) {
    if (sys.nodes().kinds[i] != NodeKind::Interior || !flagged[std::size_t(i)]) continue;
    // splitmix64 of (id, pass): a direction that depends on nothing else.
    std::uint64_t h = std::uint64_t(i) * 0x9E3779B97F4A7C15ULL + std::uint64_t(pass + 1) * 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 31;
    h *= 0x94D049BB133111EBULL;
    h ^= h >> 29;
    const double angle = double(h >> 11) * (2 * std::numbers::pi / 9007199254740992.0);  // 2π·[0, 1)
    const Metric2& mi = sys.metrics()[i];
    const Vec2 u(std::cos(angle), std::sin(angle));
    const Vec2 target = sys.nodes().positions[i] + (amplitude / std::sqrt(mi.squaredLength(u))) * u;
    // The wall searches scan the bounding box of the metric ball of each threshold
    // (reachBox): the same answers as squares of the long size h1, far fewer cells for a thin ellipse.
    if (geo.metricDistanceToBoundary(sys.nodes().positions[i], mi, reachBox(mi, 1.5)) < 1.5)
      continue;  // first rows stay
    if (!geo.inside(target) || geo.metricDistanceToBoundary(target, mi, reachBox(mi, 0.5)) < 0.5) continue;
    moved += sys.displace(i, target);
  }
  return moved;
}

}  // namespace ablmg::mesher
