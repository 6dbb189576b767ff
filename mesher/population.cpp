#include "ablmg/mesher/population.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include "ablmg/core/bucket_grid.hpp"
#include "ablmg/mesher/adjacency.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace ablmg::mesher {

std::vector<double> overlapRatios(std::span<const Vec2> x, std::span<const Metric2> m, const AdjacencyLists& adj) {
  const int n = adj.size();
  std::vector<double> alpha(std::size_t(n), 0.0);
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int j : adj.neighbours(i)) {
      const Vec2 d = x[j] - x[i];
      if (!(d.squaredNorm() > 0)) {
        s += 3;  // coincident bubbles: full overlap (limit of 2 + a/b − 2a as a, b → 0)
        continue;
      }
      const double a = std::sqrt(m[i].squaredLength(d)), b = std::sqrt(m[j].squaredLength(d));
      s += std::max(0.0, 2.0 + a / b - 2.0 * a);  // eq. (9) term
    }
    alpha[i] = s;
  }
  return alpha;
}

PopulationChange adjustPopulation(BubbleSystem& sys, const AdjacencyLists& adj, const DomainGeometry& geo,
                                  const MetricField& metric, const PopulationOptions& o) {
  PopulationChange change;
  const int n = sys.size();
  const auto& nodes = sys.nodes();
  const auto& ms = sys.metrics();
  const std::vector<double> alpha = overlapRatios(nodes.positions, ms, adj);

  std::vector<double> nearest(std::size_t(n), std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i)
    for (int j : adj.neighbours(i)) {
      const Vec2 d = nodes.positions[j] - nodes.positions[i];
      nearest[i] = std::min(nearest[i], std::sqrt(0.5 * (ms[i].squaredLength(d) + ms[j].squaredLength(d))));
    }
  const double aim = (1.0 + o.targetMargin) * double(o.target);
  const long deficit = o.target >= 0 ? std::lround(aim) - n : 0;
  const bool steerUp = o.target >= 0 && o.steerUp && deficit > 0;
  const bool steerDown = o.target >= 0 && -deficit > o.steerTolerance * aim;
  const double insBelow = steerUp ? o.steerInsertBelow : o.insertBelow;
  const double delAbove = steerDown ? o.steerDeleteAbove : o.deleteAbove;
  const double minGap = steerUp ? o.steerMinGap : o.minGap;

  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<char> locked(n, 0), kill(n, 0);

  // Deletions, most overlapped first.
  std::vector<int> del;
  for (int i = 0; i < n; ++i)
    if (nodes.kinds[i] == NodeKind::Interior &&
        (alpha[i] > delAbove || (alpha[i] > o.squeezeAlpha && nearest[i] < o.squeezeBelow)))
      del.push_back(i);
  // Order: overlap ratio plus the number of neighbours closer than squeezeBelow, so that an
  // interstitial (three close neighbours) goes before the lattice nodes it squeezes (one).
  std::vector<double> score(n, 0.0);
  for (int i : del) {
    score[i] = alpha[i];
    for (int j : adj.neighbours(i)) {
      const Vec2 d = nodes.positions[j] - nodes.positions[i];
      score[i] += std::sqrt(0.5 * (ms[i].squaredLength(d) + ms[j].squaredLength(d))) < o.squeezeBelow;
    }
  }
  std::stable_sort(del.begin(), del.end(), [&](int a, int b) { return score[a] > score[b]; });
  long delBudget = steerDown ? -deficit : std::numeric_limits<long>::max();
  if (steerUp) delBudget = 0;  // never delete while short, except real overlaps below
  for (int i : del) {
    if (locked[i]) continue;
    if (delBudget <= 0 && alpha[i] <= o.deleteAbove && nearest[i] >= o.squeezeBelow) continue;
    kill[i] = 1;
    locked[i] = 1;
    for (int j : adj.neighbours(i)) locked[j] = 1;
    ++change.deleted;
    --delBudget;
  }

  // Insertions, emptiest first.
  std::vector<int> ins;
  for (int i = 0; i < n; ++i)
    if (nodes.kinds[i] == NodeKind::Interior && alpha[i] < insBelow) ins.push_back(i);
  std::stable_sort(ins.begin(), ins.end(), [&](int a, int b) { return alpha[a] < alpha[b]; });
  long insBudget = steerUp ? deficit : std::numeric_limits<long>::max();
  if (steerDown) insBudget = 0;
  std::vector<std::pair<Vec2, Metric2>> added;
  const auto [blo, bhi] = geo.boundingBox();
  BucketGrid addedGrid(blo, bhi, std::sqrt((bhi - blo).prod() / std::max(n, 1)), 4L * n + 16);
  addedGrid.clearIncremental();
  // The twelve candidate points around each insertion site, tested against the site's
  // neighbours and the boundary in parallel (these tests do not depend on other insertions);
  // the greedy pass below adds only the distances to points inserted before.
  constexpr int kCand = 12;
  const int nIns = int(ins.size());
  std::vector<Vec2> candPos(std::size_t(nIns) * kCand);
  std::vector<double> candGap(std::size_t(nIns) * kCand,
                              -1.0);  // −1: outside, or too close to the boundary or a neighbour
#pragma omp parallel for schedule(dynamic, 64) if (nIns >= kMinParallelItems)
  for (int q = 0; q < nIns; ++q) {
    const int i = ins[std::size_t(q)];
    if (locked[i]) continue;
    const Vec2 xi = nodes.positions[i];
    const Metric2& mi = ms[i];
    const MetricEigen e = mi.eigen();
    const double c = std::cos(e.theta), s = std::sin(e.theta);
    for (int k = 0; k < kCand; ++k) {
      const double t = k * std::numbers::pi / 6;
      const Vec2 u(std::cos(t) * e.h1, std::sin(t) * e.h2);
      const Vec2 cand = xi + Vec2(c * u.x() - s * u.y(), s * u.x() + c * u.y());
      const std::size_t slot = std::size_t(q) * kCand + std::size_t(k);
      candPos[slot] = cand;
      // The gap to the site's neighbours first: a candidate closer than minGap to one of them
      // can never be chosen (an insertion needs the best gap ≥ minGap), so most candidates
      // are dropped before the boundary tests, which cost ~10× more.
      double dmin2 = std::numeric_limits<double>::infinity();
      for (int j : adj.neighbours(i)) dmin2 = std::min(dmin2, mi.squaredLength(nodes.positions[j] - cand));
      const double dmin = std::sqrt(std::max(0.0, dmin2));  // = min of Metric2::length
      if (dmin < minGap) continue;
      if (!geo.inside(cand) || geo.metricDistanceToBoundary(cand, mi, reachBox(mi, 0.5)) < 0.5) continue;
      candGap[slot] = dmin;
    }
  }
  for (int q = 0; q < nIns; ++q) {
    const int i = ins[std::size_t(q)];
    if (locked[i]) continue;
    if (insBudget <= 0 && alpha[i] >= o.insertBelow) continue;
    const Metric2& mi = ms[i];
    const double h1 = mi.eigen().h1;
    Vec2 best = nodes.positions[i];
    double bestD = -1;
    for (int k = 0; k < kCand; ++k) {
      const std::size_t slot = std::size_t(q) * kCand + std::size_t(k);
      if (candGap[slot] < 0) continue;
      const Vec2 cand = candPos[slot];
      double dmin = candGap[slot];
      addedGrid.forEachIncremental(cand, minGap * h1,
                                   [&](int a) { dmin = std::min(dmin, mi.length(added[a].first - cand)); });
      if (dmin > bestD) {
        bestD = dmin;
        best = cand;
      }
    }
    if (bestD < minGap) continue;
    addedGrid.insert(int(added.size()), best);
    added.push_back({best, mi});
    locked[i] = 1;
    for (int j : adj.neighbours(i)) locked[j] = 1;
    ++change.inserted;
    --insBudget;
  }

  for (int i = 0; i < n; ++i)  // wake the neighbourhood of every deletion
    if (kill[i])
      for (int j : adj.neighbours(i)) sys.kick(j);
  if (change.deleted) change.map = sys.remove(kill);
  change.firstNew = sys.size();
  if (!added.empty()) {
    std::vector<Vec2> pts;
    for (const auto& a : added) pts.push_back(a.first);
    std::vector<Metric2> am(pts.size());
    if (metric.isConstant())
      std::fill(am.begin(), am.end(), added.front().second);
    else
      metric.evaluate(pts, am);
    for (std::size_t k = 0; k < pts.size(); ++k) sys.addInterior(pts[k], am[k]);
  }
  return change;
}

}  // namespace ablmg::mesher
