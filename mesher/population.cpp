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

/// eq. (9) (as overlapRatios) and the metric distance (eq. 3, averaged tensor) to the nearest
/// list member, of every node, in one pass over the lists.
void overlapAndNearest(const BubbleSystem& sys, const AdjacencyLists& adj, std::vector<double>& alpha,
                       std::vector<double>& nearest) {
  const int n = sys.size();
  const auto& x = sys.nodes().positions;
  const auto& m = sys.metrics();
  alpha.assign(std::size_t(n), 0.0);
  nearest.assign(std::size_t(n), std::numeric_limits<double>::infinity());
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) {
    double s = 0, near = std::numeric_limits<double>::infinity();
    for (int j : adj.neighbours(i)) {
      const Vec2 d = x[j] - x[i];
      const double a2 = m[i].squaredLength(d), b2 = m[j].squaredLength(d);
      near = std::min(near, std::sqrt(0.5 * (a2 + b2)));
      if (!(d.squaredNorm() > 0)) {
        s += 3;  // coincident bubbles: full overlap (as overlapRatios)
        continue;
      }
      const double a = std::sqrt(a2), b = std::sqrt(b2);
      s += std::max(0.0, 2.0 + a / b - 2.0 * a);  // eq. (9) term
    }
    alpha[std::size_t(i)] = s;
    nearest[std::size_t(i)] = near;
  }
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
    // eq. (9) finds holes everywhere in a metric no packing fits (a long size turning faster
    // than it spans: h1 = 0.5 along θ = 3y): its insertions grew such counts 4-9x past N*,
    // and the adjacency with them (minutes for 10⁴ nodes). Past kMaxOvershoot × the aim, none.
    capped = o.target >= 0 && double(n) > kMaxOvershoot * aim;
  }
  static constexpr double kMaxOvershoot = 1.5;
  bool capped = false;  ///< no insertion at all this pass
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
      : sys(s), adj(a), o(opt), rules(opt, s.size()), locked(std::size_t(s.size()), 0), kill(std::size_t(s.size()), 0) {
    overlapAndNearest(s, a, alpha, nearest);
  }

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
  std::vector<double> h1;  ///< per site: M_i's long size (MetricEigen::h1)
};

/// cos and sin of the candidates' angles kπ/6 (the same values as computing them per site).
struct CandidateDirections {
  double c[Candidates::kPerSite], s[Candidates::kPerSite];
  CandidateDirections() {
    for (int k = 0; k < Candidates::kPerSite; ++k) {
      const double t = k * std::numbers::pi / 6;
      c[k] = std::cos(t);
      s[k] = std::sin(t);
    }
  }
};

Candidates insertionCandidates(const Pass& pass, const std::vector<int>& sites, const DomainGeometry& geo) {
  const auto& nodes = pass.sys.nodes();
  const auto& ms = pass.sys.metrics();
  constexpr int kCand = Candidates::kPerSite;
  static const CandidateDirections dir;
  const int nIns = int(sites.size());
  Candidates c{std::vector<Vec2>(std::size_t(nIns) * kCand), std::vector<double>(std::size_t(nIns) * kCand, -1.0),
               std::vector<double>(std::size_t(nIns), 0.0)};
  // A candidate with a neighbour closer than minGap is dropped whatever the others give: the
  // scan of the neighbours stops at the first one below this (just under minGap², so that the
  // drops are exactly those of the full minimum). On a packing most candidates fall near a
  // neighbour (half of the twelve on a lattice node), so most scans stop early.
  const double dropBelow2 = pass.rules.minGap * pass.rules.minGap * (1 - 1e-12);
#pragma omp parallel if (nIns >= kMinParallelItems)
  {
    std::vector<Vec2> near;  // the site's neighbours' positions, gathered once for 12 scans
#pragma omp for schedule(dynamic, 64)
    for (int q = 0; q < nIns; ++q) {
      const int i = sites[std::size_t(q)];
      if (pass.locked[i]) continue;
      const Vec2 xi = nodes.positions[i];
      const Metric2& mi = ms[i];
      const MetricEigen e = mi.eigen();
      c.h1[std::size_t(q)] = e.h1;
      const double cs = std::cos(e.theta), sn = std::sin(e.theta);
      near.clear();
      for (int j : pass.adj.neighbours(i)) near.push_back(nodes.positions[j]);
      for (int k = 0; k < kCand; ++k) {
        const Vec2 u(dir.c[k] * e.h1, dir.s[k] * e.h2);
        const Vec2 cand = xi + Vec2(cs * u.x() - sn * u.y(), sn * u.x() + cs * u.y());
        const std::size_t slot = std::size_t(q) * kCand + std::size_t(k);
        c.pos[slot] = cand;
        // The gap to the site's neighbours first: a candidate closer than minGap to one of them
        // can never be chosen (an insertion needs the best gap ≥ minGap), so most candidates
        // are dropped before the boundary tests, which cost ~10× more.
        double dmin2 = std::numeric_limits<double>::infinity();
        for (const Vec2& xj : near) {
          dmin2 = std::min(dmin2, mi.squaredLength(xj - cand));
          if (dmin2 < dropBelow2) break;
        }
        const double dmin = std::sqrt(std::max(0.0, dmin2));  // = min of Metric2::length
        if (dmin < pass.rules.minGap) continue;
        if (!geo.inside(cand) || geo.metricDistanceToBoundary(cand, mi, reachBox(mi, 0.5)) < 0.5) continue;
        c.gap[slot] = dmin;
      }
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
  for (int i = 0; i < n && !rules.capped; ++i)
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
    const double h1 = cand.h1[std::size_t(q)];
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
