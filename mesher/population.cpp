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

namespace {

/// The metric distance (eq. 3, averaged tensor) from each node to its nearest list member.
std::vector<double> nearestDistances(const BubbleSystem& sys, const AdjacencyLists& adj) {
  const int n = sys.size();
  const auto& x = sys.nodes().positions;
  const auto& ms = sys.metrics();
  std::vector<double> nearest(std::size_t(n), std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i)
    for (int j : adj.neighbours(i)) {
      const Vec2 d = x[j] - x[i];
      nearest[i] = std::min(nearest[i], std::sqrt(0.5 * (ms[i].squaredLength(d) + ms[j].squaredLength(d))));
    }
  return nearest;
}

/// The thresholds and edit budgets of one pass: the eq. (9) ones, relaxed while steering
/// towards the aim (1 + targetMargin)·N* (population.hpp).
struct PassRules {
  bool steerUp = false, steerDown = false;
  double insBelow = 0, delAbove = 0, minGap = 0;
  long delBudget = 0, insBudget = 0;

  PassRules(const PopulationOptions& o, int n) {
    const double aim = (1.0 + o.targetMargin) * double(o.target);
    const long deficit = o.target >= 0 ? std::lround(aim) - n : 0;
    steerUp = o.target >= 0 && o.steerUp && deficit > 0;
    steerDown = o.target >= 0 && -deficit > o.steerTolerance * aim;
    insBelow = steerUp ? o.steerInsertBelow : o.insertBelow;
    delAbove = steerDown ? o.steerDeleteAbove : o.deleteAbove;
    minGap = steerUp ? o.steerMinGap : o.minGap;
    delBudget = steerDown ? -deficit : std::numeric_limits<long>::max();
    if (steerUp) delBudget = 0;  // never delete while short, except real overlaps
    insBudget = steerUp ? deficit : std::numeric_limits<long>::max();
    if (steerDown) insBudget = 0;
  }
};

/// One pass's working state: the per-node measures, the locks and the chosen edits.
struct Pass {
  const BubbleSystem& sys;
  const AdjacencyLists& adj;
  const PopulationOptions& o;
  PassRules rules;
  std::vector<double> alpha, nearest;
  std::vector<char> locked, kill;
  std::vector<std::pair<Vec2, Metric2>> added;

  Pass(const BubbleSystem& s, const AdjacencyLists& a, const PopulationOptions& opt)
      : sys(s),
        adj(a),
        o(opt),
        rules(opt, s.size()),
        alpha(overlapRatios(s.nodes().positions, s.metrics(), a)),
        nearest(nearestDistances(s, a)),
        locked(std::size_t(s.size()), 0),
        kill(std::size_t(s.size()), 0) {}

  void lockAround(int i) {
    locked[i] = 1;
    for (int j : adj.neighbours(i)) locked[j] = 1;
  }
  long markDeletions();
  long chooseInsertions(const DomainGeometry& geo);
};

/// Deletions, most overlapped first; each locks its neighbours.
long Pass::markDeletions() {
  const int n = sys.size();
  const auto& nodes = sys.nodes();
  const auto& ms = sys.metrics();
  std::vector<int> del;
  for (int i = 0; i < n; ++i)
    if (nodes.kinds[i] == NodeKind::Interior &&
        (alpha[i] > rules.delAbove || (alpha[i] > o.squeezeAlpha && nearest[i] < o.squeezeBelow)))
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
  long deleted = 0;
  for (int i : del) {
    if (locked[i]) continue;
    if (rules.delBudget <= 0 && alpha[i] <= o.deleteAbove && nearest[i] >= o.squeezeBelow) continue;
    kill[i] = 1;
    lockAround(i);
    ++deleted;
    --rules.delBudget;
  }
  return deleted;
}

/// The twelve candidate points around each insertion site at metric distance 1, tested
/// against the site's neighbours and the boundary (these tests do not depend on other
/// insertions, so they run in parallel). gap[q·12 + k]: the candidate's metric distance to
/// the site's neighbours, −1 if outside, too close to the boundary or closer than minGap.
struct Candidates {
  static constexpr int kPerSite = 12;
  std::vector<Vec2> pos;
  std::vector<double> gap;
};

Candidates insertionCandidates(const Pass& pass, const std::vector<int>& sites, const DomainGeometry& geo) {
  const auto& nodes = pass.sys.nodes();
  const auto& ms = pass.sys.metrics();
  constexpr int kCand = Candidates::kPerSite;
  const int nIns = int(sites.size());
  Candidates c{std::vector<Vec2>(std::size_t(nIns) * kCand), std::vector<double>(std::size_t(nIns) * kCand, -1.0)};
#pragma omp parallel for schedule(dynamic, 64) if (nIns >= kMinParallelItems)
  for (int q = 0; q < nIns; ++q) {
    const int i = sites[std::size_t(q)];
    if (pass.locked[i]) continue;
    const Vec2 xi = nodes.positions[i];
    const Metric2& mi = ms[i];
    const MetricEigen e = mi.eigen();
    const double cs = std::cos(e.theta), sn = std::sin(e.theta);
    for (int k = 0; k < kCand; ++k) {
      const double t = k * std::numbers::pi / 6;
      const Vec2 u(std::cos(t) * e.h1, std::sin(t) * e.h2);
      const Vec2 cand = xi + Vec2(cs * u.x() - sn * u.y(), sn * u.x() + cs * u.y());
      const std::size_t slot = std::size_t(q) * kCand + std::size_t(k);
      c.pos[slot] = cand;
      // The gap to the site's neighbours first: a candidate closer than minGap to one of them
      // can never be chosen (an insertion needs the best gap ≥ minGap), so most candidates
      // are dropped before the boundary tests, which cost ~10× more.
      double dmin2 = std::numeric_limits<double>::infinity();
      for (int j : pass.adj.neighbours(i)) dmin2 = std::min(dmin2, mi.squaredLength(nodes.positions[j] - cand));
      const double dmin = std::sqrt(std::max(0.0, dmin2));  // = min of Metric2::length
      if (dmin < pass.rules.minGap) continue;
      if (!geo.inside(cand) || geo.metricDistanceToBoundary(cand, mi, reachBox(mi, 0.5)) < 0.5) continue;
      c.gap[slot] = dmin;
    }
  }
  return c;
}

/// Insertions, emptiest first: each site takes its candidate farthest from its neighbours and
/// from the points inserted before it (greedy, serial), if that is at least minGap; each
/// insertion locks the site's neighbours.
long Pass::chooseInsertions(const DomainGeometry& geo) {
  const int n = sys.size();
  const auto& nodes = sys.nodes();
  const auto& ms = sys.metrics();
  std::vector<int> ins;
  for (int i = 0; i < n; ++i)
    if (nodes.kinds[i] == NodeKind::Interior && alpha[i] < rules.insBelow) ins.push_back(i);
  std::stable_sort(ins.begin(), ins.end(), [&](int a, int b) { return alpha[a] < alpha[b]; });
  const auto [blo, bhi] = geo.boundingBox();
  BucketGrid addedGrid(blo, bhi, std::sqrt((bhi - blo).prod() / std::max(n, 1)), 4L * n + 16);
  addedGrid.clearIncremental();
  const Candidates cand = insertionCandidates(*this, ins, geo);
  long inserted = 0;
  for (int q = 0; q < int(ins.size()); ++q) {
    const int i = ins[std::size_t(q)];
    if (locked[i]) continue;
    if (rules.insBudget <= 0 && alpha[i] >= o.insertBelow) continue;
    const Metric2& mi = ms[i];
    const double h1 = mi.eigen().h1;
    Vec2 best = nodes.positions[i];
    double bestD = -1;
    for (int k = 0; k < Candidates::kPerSite; ++k) {
      const std::size_t slot = std::size_t(q) * Candidates::kPerSite + std::size_t(k);
      if (cand.gap[slot] < 0) continue;
      const Vec2 p = cand.pos[slot];
      double dmin = cand.gap[slot];
      addedGrid.forEachIncremental(p, rules.minGap * h1,
                                   [&](int a) { dmin = std::min(dmin, mi.length(added[a].first - p)); });
      if (dmin > bestD) {
        bestD = dmin;
        best = p;
      }
    }
    if (bestD < rules.minGap) continue;
    addedGrid.insert(int(added.size()), best);
    added.push_back({best, mi});
    lockAround(i);
    ++inserted;
    --rules.insBudget;
  }
  return inserted;
}

/// Applies the pass: wakes the neighbourhood of every deletion, removes, then appends the
/// insertions with their metrics evaluated at the new points.
void apply(const Pass& pass, BubbleSystem& sys, const MetricField& metric, PopulationChange& change) {
  const int n = sys.size();
  for (int i = 0; i < n; ++i)
    if (pass.kill[i])
      for (int j : pass.adj.neighbours(i)) sys.kick(j);
  if (change.deleted) change.map = sys.remove(pass.kill);
  change.firstNew = sys.size();
  if (pass.added.empty()) return;
  std::vector<Vec2> pts;
  for (const auto& a : pass.added) pts.push_back(a.first);
  std::vector<Metric2> am(pts.size());
  if (metric.isConstant())
    std::fill(am.begin(), am.end(), pass.added.front().second);
  else
    metric.evaluate(pts, am);
  sys.reserveInterior(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) sys.addInterior(pts[k], am[k]);
}

}  // namespace

PopulationChange adjustPopulation(BubbleSystem& sys, const AdjacencyLists& adj, const DomainGeometry& geo,
                                  const MetricField& metric, const PopulationOptions& o) {
  Pass pass(sys, adj, o);
  PopulationChange change;
  change.deleted = pass.markDeletions();
  change.inserted = pass.chooseInsertions(geo);
  apply(pass, sys, metric, change);
  return change;
}

}  // namespace ablmg::mesher
