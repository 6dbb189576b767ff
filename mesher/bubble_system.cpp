#include "ablmg/mesher/bubble_system.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/mesher/bubble_force.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace ablmg::mesher {
namespace {

/// The midpoint of arcs a ≤ b as both nodes of a pair compute it (same operands, same
/// rounding): a ≤ chainMidpoint(a, b) ≤ b in floating point.
double chainMidpoint(double a, double b) { return a + 0.5 * (b - a); }

/// Ids i in [0, n) with pred(i), ascending, collected in parallel: contiguous blocks per
/// thread, each copied to its offset in `out` (the result does not depend on the thread count).
/// `visit(i)` runs first for every i (the caller's per-bubble work fused into the same pass);
/// returns the largest value visit returned (0 if none is larger).
template <class Pred, class Visit>
double collectIf(int n, std::vector<int>& out, std::vector<std::vector<int>>& parts, Pred&& pred, Visit&& visit) {
  constexpr std::size_t kPad = 8;  // one cache line per thread's maximum (no false sharing)
  parts.resize(std::size_t(omp_get_max_threads()));
  std::vector<std::size_t> offset(parts.size() + 1, 0);
  std::vector<double> best(kPad * parts.size(), 0.0);
  // push_back and resize may throw (and pred, visit): rethrown after the region, the block of
  // the lowest ids first; every thread still meets the barrier.
  ParallelFailure failure;
#pragma omp parallel if (n >= kMinParallelItems)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int lo = int(long(n) * t / threads), hi = int(long(n) * (t + 1) / threads);
    auto& v = parts[std::size_t(t)];
    v.clear();
    failure.run(lo, [&] {
      double m = 0;
      for (int i = lo; i < hi; ++i) {
        const double x = visit(i);
        m = x > m ? x : m;
        if (pred(i)) v.push_back(i);
      }
      best[kPad * std::size_t(t)] = m;
    });
    offset[std::size_t(t) + 1] = v.size();
#pragma omp barrier
#pragma omp single
    failure.run(n, [&] {
      for (std::size_t k = 1; k < offset.size(); ++k) offset[k] += offset[k - 1];
      out.resize(offset.back());
    });
    if (!failure.failed()) std::copy(v.begin(), v.end(), out.begin() + std::ptrdiff_t(offset[std::size_t(t)]));
  }
  failure.rethrow();
  return *std::max_element(best.begin(), best.end());
}
template <class Pred>
void collectIf(int n, std::vector<int>& out, Pred&& pred) {
  std::vector<std::vector<int>> parts;
  collectIf(n, out, parts, pred, [](int) { return 0.0; });
}

}  // namespace

BubbleSystem::BubbleSystem(const DomainGeometry& geo, NodeSet nodes, std::vector<double> arcLength)
    : geo_(&geo), nodes_(std::move(nodes)), s_(std::move(arcLength)) {
  s_.resize(std::size_t(nodes_.size()), 0.0);
  vel_.assign(std::size_t(nodes_.size()), Vec2::Zero());
  force_.assign(std::size_t(nodes_.size()), Vec2::Zero());
  metrics_.resize(std::size_t(nodes_.size()));
  setBounds();
}

void BubbleSystem::setBounds() {
  const int n = nodes_.size();
  sLo_.assign(n, -std::numeric_limits<double>::infinity());
  sHi_.assign(n, std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    if (nodes_.kinds[i] != NodeKind::Segment) continue;
    const auto& poly = geo_->loops()[nodes_.loops[i]];
    if (poly.corners.empty()) continue;
    const double L = poly.length;
    const double s = geo_->wrap(nodes_.loops[i], s_[i]);
    std::vector<double> cs;
    for (int c : poly.corners) cs.push_back(poly.cum[c]);
    const auto it = std::upper_bound(cs.begin(), cs.end(), s);
    double lo, hi;
    if (it == cs.begin()) {
      lo = cs.back() - L;
      hi = cs.front();
    } else if (it == cs.end()) {
      lo = cs.back();
      hi = cs.front() + L;
    } else {
      lo = *(it - 1);
      hi = *it;
    }
    double su = s;
    if (su < lo) su += L;
    if (su > hi) su -= L;
    sLo_[i] = lo;
    sHi_[i] = hi;
    s_[i] = su;
  }
  linkChains();
}

void BubbleSystem::linkChains() {
  const int n = nodes_.size();
  chainPrev_.assign(std::size_t(n), -1);
  chainNext_.assign(std::size_t(n), -1);
  chainShift_.assign(std::size_t(n), 0.0);
  segmentIds_.clear();
  for (int l = 0; l < int(geo_->loops().size()); ++l) {
    std::vector<int> ids;
    for (int i = 0; i < n; ++i)
      if (nodes_.loops[i] == l && nodes_.kinds[i] != NodeKind::Interior) ids.push_back(i);
    if (ids.empty()) continue;
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) { return geo_->wrap(l, s_[a]) < geo_->wrap(l, s_[b]); });
    const bool cornerless = geo_->loops()[l].corners.empty();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const int i = ids[k], j = ids[(k + 1) % ids.size()];
      chainNext_[i] = j;
      chainPrev_[j] = i;
      // A corner-less loop's arc is kept in one turn, [0, L), except for its drift: the pair
      // that closes the loop compares j's arc one turn on.
      if (cornerless) {
        if (k == 0) s_[i] = geo_->wrap(l, s_[i]);
        if (k + 1 < ids.size()) s_[j] = geo_->wrap(l, s_[j]);
        chainShift_[i] = k + 1 == ids.size() ? geo_->loops()[l].length : 0.0;
      }
    }
    for (int i : ids)
      if (nodes_.kinds[i] == NodeKind::Segment) segmentIds_.push_back(i);
  }
  std::sort(segmentIds_.begin(), segmentIds_.end());
  sStart_ = s_;
}

bool BubbleSystem::canSlideTo(int i, double s) const {
  const int j = chainNext_[i], k = chainPrev_[i];
  if (j < 0 || j == i) return true;  // alone on its loop
  const bool upOk =
      nodes_.kinds[j] == NodeKind::Vertex ? s < sHi_[i] : s < chainMidpoint(sStart_[i], sStart_[j] + chainShift_[i]);
  if (!upOk) return false;
  return nodes_.kinds[k] == NodeKind::Vertex
             ? s > sLo_[i]
             : s + chainShift_[k] > chainMidpoint(sStart_[k], sStart_[i] + chainShift_[k]);
}

bool BubbleSystem::sameChain(int i, int j) const {
  const int l = nodes_.loops[i];
  if (nodes_.loops[j] != l) return false;
  if (!std::isfinite(sLo_[i])) return true;  // corner-less loop: one closed chain
  if (nodes_.kinds[j] == NodeKind::Segment) return sLo_[j] == sLo_[i];
  if (nodes_.kinds[j] != NodeKind::Vertex) return false;
  const double sj = geo_->wrap(l, s_[j]);
  const double tol = 1e-9 * geo_->loops()[l].length;
  return std::abs(sj - geo_->wrap(l, sLo_[i])) < tol || std::abs(sj - geo_->wrap(l, sHi_[i])) < tol;
}

double BubbleSystem::arcLength(int i) const { return nodes_.loops[i] < 0 ? -1.0 : geo_->wrap(nodes_.loops[i], s_[i]); }

void BubbleSystem::updateMetrics(const MetricField& field, bool all, double lazyDistance) {
  metrics_.resize(std::size_t(nodes_.size()));
  if (field.isConstant()) {
    if (!metricsConstant_ || metrics_.empty()) {
      std::fill(metrics_.begin(), metrics_.end(), field.at(nodes_.size() ? nodes_.positions[0] : Vec2::Zero()));
      metricsConstant_ = true;
    } else {
      std::fill(metrics_.begin(), metrics_.end(), metrics_.front());
    }
    return;
  }
  const int n = nodes_.size();
  hint_.resize(std::size_t(n), -1);
  if (all || int(evalPos_.size()) != n) {
    field.evaluate(nodes_.positions, metrics_, hint_);
    evalPos_ = nodes_.positions;
    return;
  }
  std::vector<int> stale;
  const double t2 = lazyDistance * lazyDistance;
  collectIf(n, stale, [&](int i) { return metrics_[i].squaredLength(nodes_.positions[i] - evalPos_[i]) > t2; });
  if (stale.empty()) return;
  std::vector<Vec2> pts(stale.size());
  std::vector<Metric2> ms(stale.size());
  std::vector<int> hs(stale.size());
  for (std::size_t k = 0; k < stale.size(); ++k) {
    pts[k] = nodes_.positions[stale[k]];
    hs[k] = hint_[stale[k]];
  }
  field.evaluate(pts, ms, hs);
  for (std::size_t k = 0; k < stale.size(); ++k) {
    metrics_[stale[k]] = ms[k];
    evalPos_[stale[k]] = pts[k];
    hint_[stale[k]] = hs[k];
  }
}

[[gnu::always_inline]] inline bool BubbleSystem::pairTerm(const Vec2& xi, const Metric2& mi, int j,
                                                          const DynamicsParams& p, Vec2& term) const {
  const Vec2 d = nodes_.positions[j] - xi;
  const double a2 = mi.squaredLength(d), b2 = metrics_[j].squaredLength(d);
  // w > 1.5 (no force) once a² + b² > 2·1.5² (averaged) or min(a², b²) > 1.5² (harmonic,
  // which is ≥ min(a, b)); also d = 0.
  const bool harmonic = p.pairDistance == PairDistance::Harmonic;
  if (!(a2 > 0 && b2 > 0) || (harmonic ? std::min(a2, b2) > 2.25 : a2 + b2 > 4.5)) return false;
  const double w = pairDistance(a2, b2, p.pairDistance);  // bubble_force.hpp: eq. (8) by default
  const double fw = interBubbleForce(w, p.k0);
  if (fw == 0.0) return false;
  // The rest length l0 = l/w (one metric unit along d), so the pair force fw·l0·d/l = (fw/w)·d
  // needs neither l = |d| nor l0.
  term = (fw / w) * d;
  return true;
}

[[gnu::always_inline]] inline bool BubbleSystem::feels(int i, int j) const {
  return nodes_.kinds[i] != NodeKind::Segment || sameChain(i, j);  // Segment: 1D packing along the loop piece
}

Vec2 BubbleSystem::finishForce(int i, Vec2 f) const {
  if (nodes_.kinds[i] == NodeKind::Segment) {
    const Vec2 t = geo_->tangentAt(nodes_.loops[i], s_[i]);
    f = f.dot(t) * t;
  }
  return f;
}

Vec2 BubbleSystem::netForce(int i, const AdjacencyLists& adj, const DynamicsParams& p) const {
  Vec2 f = Vec2::Zero();
  const Metric2& mi = metrics_[i];
  const Vec2 xi = nodes_.positions[i];
  Vec2 term;
  for (int j : adj.neighbours(i))
    if (feels(i, j) && pairTerm(xi, mi, j, p, term)) f -= term;
  return finishForce(i, f);
}

double BubbleSystem::computeForcesPairwise(const AdjacencyLists& adj, const DynamicsParams& p) {
  const int n = nodes_.size();
  need_.assign(std::size_t(n), 0);
  for (int i : list_) need_[std::size_t(i)] = 1;
  double residual = 0;
#pragma omp parallel reduction(max : residual) if (n >= kMinParallelItems)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int lo = int(long(n) * t / threads), hi = int(long(n) * (t + 1) / threads);
    // force_[i] accumulates i's terms in the order of its row (ascending partner ids), as
    // netForce() does: partners below the block first (computed here, their owner does not
    // see this block), then partners in the block below i (added by them in the sweep), then
    // i's own partners above it.
    for (int i = lo; i < hi; ++i) {
      Vec2 f = Vec2::Zero();
      if (need_[std::size_t(i)]) {
        const Vec2 xi = nodes_.positions[i];
        Vec2 term;
        for (int j : adj.neighbours(i)) {
          if (j >= lo) break;
          if (feels(i, j) && pairTerm(xi, metrics_[i], j, p, term)) f -= term;
        }
      }
      force_[i] = f;
    }
    for (int i = lo; i < hi; ++i) {
      const bool needI = need_[std::size_t(i)] != 0;
      const Vec2 xi = nodes_.positions[i];
      const Metric2& mi = metrics_[i];
      Vec2 f = force_[i], term;
      for (int j : adj.neighbours(i)) {
        if (j <= i) continue;
        const bool forI = needI && feels(i, j);
        const bool forJ = j < hi && need_[std::size_t(j)] && feels(j, i);
        if (!(forI || forJ) || !pairTerm(xi, mi, j, p, term)) continue;
        // The pair term is antisymmetric bit for bit: from j's side d is −d exactly, a and b
        // swap, and w = 2ab/(a+b) rounds the same (2a·b = 2b·a exactly).
        if (forI) f -= term;
        if (forJ) force_[j] += term;
      }
      if (!needI) continue;
      force_[i] = finishForce(i, f);
      res_[i] = std::sqrt(mi.squaredLength(force_[i]));
      residual = std::max(residual, res_[i]);
    }
  }
  return residual;
}

double BubbleSystem::computeForces(const AdjacencyLists& adj, const DynamicsParams& p) {
  const int n = nodes_.size();
  // force_ and res_ are written for the awake bubbles only and read only for them (advance(),
  // updateActivity()), so asleep bubbles keep stale values: no clearing pass per step.
  if (resetForces_ || int(force_.size()) != n || int(res_.size()) != n) {
    force_.assign(std::size_t(n), Vec2::Zero());
    res_.assign(std::size_t(n), 0.0);
    resetForces_ = false;
  }
  active_.resize(std::size_t(n), 1);
  // The awake list: from updateActivity() when it is current, else from the flags.
  if (nextList_.valid && int(nextList_.ids.size()) <= n) {
    list_.swap(nextList_.ids);
  } else {
    collectIf(n, list_, [&](int i) { return active_[i] && nodes_.kinds[i] != NodeKind::Vertex; });
  }
  nextList_.valid = false;
  const int m = int(list_.size());
  // Mostly awake: each pair once (Newton's third law), same sums bit for bit.
  if (2 * m >= n) return computeForcesPairwise(adj, p);
  double residual = 0;
#pragma omp parallel for schedule(static) reduction(max : residual) if (m >= kMinParallelItems)
  for (int k = 0; k < m; ++k) {
    const int i = list_[k];
    force_[i] = netForce(i, adj, p);
    res_[i] = std::sqrt(metrics_[i].squaredLength(force_[i]));
    residual = std::max(residual, res_[i]);
  }
  return residual;
}

void BubbleSystem::advance(const DynamicsParams& p) {
  const int n = nodes_.size();
  const double dtm = p.dt / p.mass;
  active_.resize(std::size_t(n), 1);
  movement_.beginStep(n);
  clear_.resize(std::size_t(n), 0.0);
  for (int i : segmentIds_) sStart_[i] = s_[i];  // the chain bounds use the arcs before the step
  const int m = int(list_.size());
#pragma omp parallel for schedule(static) if (m >= kMinParallelItems)
  for (int k = 0; k < m; ++k) {
    const int i = list_[k];
    const Vec2 before = nodes_.positions[i];
    switch (nodes_.kinds[i]) {
      case NodeKind::Vertex:
        break;
      case NodeKind::Segment: {
        const int l = nodes_.loops[i];
        const Vec2 t = geo_->tangentAt(l, s_[i]);
        const double vt = vel_[i].dot(t) + dtm * (force_[i].dot(t) - p.damping * vel_[i].dot(t));
        double s = s_[i] + p.dt * vt;
        if (canSlideTo(i, s)) {
          vel_[i] = vt * t;
        } else {
          // Past the bound towards a neighbour (canSlideTo): halfway there if that is inside,
          // else stay; the nodes of a chain keep their order and stay distinct either way.
          const bool up = s > s_[i];
          const int nb = up ? chainNext_[i] : chainPrev_[i];
          double bound = up ? sHi_[i] : sLo_[i];
          if (nodes_.kinds[nb] != NodeKind::Vertex)
            bound = up ? chainMidpoint(sStart_[i], sStart_[nb] + chainShift_[i])
                       : chainMidpoint(sStart_[nb], sStart_[i] + chainShift_[nb]) - chainShift_[nb];
          s = 0.5 * (s_[i] + bound);
          if (!canSlideTo(i, s)) s = s_[i];
          vel_[i] = Vec2::Zero();
        }
        s_[i] = s;
        nodes_.positions[i] = geo_->pointAt(l, s);
        nodes_.arc[i] = geo_->indexArc(l, s);
        break;
      }
      case NodeKind::Interior: {
        const Vec2 v = vel_[i] + dtm * (force_[i] - p.damping * vel_[i]);
        const Vec2 xn = nodes_.positions[i] + p.dt * v;
        // clear_[i] is a lower bound of the distance to the boundary: a move shorter than it
        // stays inside without the test (which was ~15 % of a 10⁶-node run).
        const double step = (xn - nodes_.positions[i]).norm();
        bool in = step < clear_[i];
        if (in) {
          clear_[i] -= step;
        } else if (geo_->inside(xn)) {
          in = true;
          const Metric2& mi = metrics_[i];
          const double a = mi.m11(), b = mi.m12(), c = mi.m22();
          const double lmin = 0.5 * (a + c) - std::sqrt(0.25 * (a - c) * (a - c) + b * b);
          // Two largest bubble sizes h1, at most one segment-grid cell: a stretched bubble's h1
          // (anisotropy 10⁴) spans hundreds of cells of a finely cut boundary, and the scan of
          // their segments was 18 % of a boundary-layer remesh. Any radius gives a lower
          // bound; a smaller one only brings the next test nearer (the layer: 0.9·10⁵ tests of
          // 570 segments each at 2 h1, 3.0·10⁵ of 20 at one cell, 1.8·10⁵ of 83 at two).
          const double R = std::min(2.0 / std::sqrt(std::max(lmin, 1e-300)), geo_->segmentCellSize());
          clear_[i] = 0.999 * std::min(R, geo_->metricDistanceToBoundary(xn, Metric2(), R));
        }
        if (in) {
          nodes_.positions[i] = xn;
          vel_[i] = v;
        } else {
          vel_[i] = Vec2::Zero();
        }
        break;
      }
    }
    // Travel is tracked for every move, however small (creeping bubbles add up); only moves
    // above moveEps2_ count for the active set.
    const Vec2 step = nodes_.positions[i] - before;
    if (step.x() != 0 || step.y() != 0)
      movement_.recordMove(i, nodes_.positions[i], metrics_[i], metrics_[i].squaredLength(step) > moveEps2_);
  }
}

long BubbleSystem::updateActivity(const AdjacencyLists& adj, double sleepBelow, double dt) {
  const int n = nodes_.size();
  const double eps = 0.3 * sleepBelow * dt;  // a move this small (metric) wakes nobody
  moveEps2_ = eps * eps;
  // Since the last population edit (full pass), only the bubbles advanced in this step (list_,
  // unchanged since advance()) can have moved and nobody was kicked.
  const bool resized = movement_.coverStep(n);
  const bool full = resetActivity_ || resized || int(kicked_.size()) != n;
  kicked_.resize(std::size_t(n), 0);
  // Candidates: bubbles awake now, and the neighbours of every bubble that moved (or was kicked).
  next_.assign(std::size_t(n), 0);
  const auto moved = [&](int i) { return movement_.movedThisStep(i) || kicked_[i] != 0; };
  const int m = int(list_.size());
  if (full || 2 * m >= n) {
    // Most bubbles advanced: each reads its own row and stops at the first mover (the lists are
    // symmetric, so this is the set the marking below gives), without a store per list entry.
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
    for (int i = 0; i < n; ++i) {
      bool a = moved(i);
      for (auto it = adj.neighbours(i).begin(); !a && it != adj.neighbours(i).end(); ++it) a = moved(*it);
      next_[i] = char(a);
    }
  } else {
    // Few advanced: each mover marks its row, in parallel; concurrent stores of the same value
    // go through atomic_ref.
#pragma omp parallel for schedule(static) if (m >= kMinParallelItems)
    for (int k = 0; k < m; ++k) {
      const int i = list_[k];
      if (!moved(i)) continue;
      std::atomic_ref<char>(next_[i]).store(1, std::memory_order_relaxed);
      for (int j : adj.neighbours(i)) std::atomic_ref<char>(next_[j]).store(1, std::memory_order_relaxed);
    }
  }
  // One pass: the new flags, the awake ids in ascending order (for the next computeForces(),
  // instead of scanning the flags) and the largest travel since the last refresh.
  auto decide = [&](int i) {  // returns the bubble's travel
    if (nodes_.kinds[i] == NodeKind::Vertex) {
      next_[i] = 0;
    } else {
      bool a = next_[i] != 0;
      if (!a && active_[i]) a = res_[i] > sleepBelow || std::sqrt(metrics_[i].squaredLength(vel_[i])) > sleepBelow;
      if (!a && active_[i]) vel_[i] = Vec2::Zero();  // asleep: force and velocity small, neighbours still
      next_[i] = char(a);
    }
    return movement_.travel(i);
  };
  movement_.setMaxTravel(collectIf(
      n, nextList_.ids, parts_, [&](int i) { return next_[i] != 0; }, decide));
  active_.swap(next_);
  nextList_.valid = true;
  const long count = long(nextList_.ids.size());
  if (full) {
    kicked_.assign(std::size_t(n), 0);
    resetActivity_ = false;
  }
  return count;
}

void MovementRecord::beginStep(int n) {
  maxTravelValid_ = false;
  ++stamp_;
  if (resetStamps_ || int(stamps_.size()) != n) {
    stamps_.assign(std::size_t(n), 0);
    resetStamps_ = false;
  }
  sinceClear_.resize(std::size_t(n), 1);
  travel_.resize(std::size_t(n), 0.0);
}

bool MovementRecord::coverStep(int n) {
  if (int(stamps_.size()) == n) return false;
  resetStamps_ = true;
  stamps_.resize(std::size_t(n), stamp_);
  return true;
}

double MovementRecord::maxTravel() const {
  if (maxTravelValid_) return maxTravel_;
  double m = 0;
  const int n = int(travel_.size());
#pragma omp parallel for schedule(static) reduction(max : m) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) m = std::max(m, travel_[i]);
  return m;
}

std::vector<int> MovementRecord::travellers(double threshold) const {
  std::vector<int> ids;
  collectIf(int(travel_.size()), ids, [&](int i) { return travel_[i] > threshold; });
  return ids;
}

void MovementRecord::resetTravel(std::span<const int> ids, const std::vector<Vec2>& positions) {
  maxTravelValid_ = false;
  for (int i : ids) {
    travel_[i] = 0.0;
    if (i < int(ref_.size())) ref_[i] = positions[i];
  }
}

void MovementRecord::clear(const std::vector<Vec2>& positions) {
  sinceClear_.assign(positions.size(), 0);
  travel_.assign(positions.size(), 0.0);
  maxTravel_ = 0;
  maxTravelValid_ = true;
  ref_ = positions;
}

void MovementRecord::keep(int from, int to) {
  if (from < int(sinceClear_.size())) sinceClear_[to] = sinceClear_[from];
  if (from < int(travel_.size())) travel_[to] = travel_[from];
  if (from < int(ref_.size())) ref_[to] = ref_[from];
}

void MovementRecord::truncate(int m) {
  sinceClear_.resize(std::size_t(m), 1);
  travel_.resize(std::size_t(m), 0.0);
  if (int(ref_.size()) > m) ref_.resize(std::size_t(m));
}

void MovementRecord::append(const Vec2& x, std::size_t n) {
  sinceClear_.resize(n - 1, 1);
  sinceClear_.push_back(1);
  travel_.resize(n - 1, 0.0);
  travel_.push_back(0.0);
  if (ref_.size() + 1 == n) ref_.push_back(x);  // travel counts from here
}

void MovementRecord::displaced(int i, const Vec2& x, const Metric2& m) {
  if (std::size_t(i) < sinceClear_.size()) sinceClear_[i] = 1;
  if (std::size_t(i) < travel_.size() && std::size_t(i) < ref_.size())
    travel_[i] = std::sqrt(m.squaredLength(x - ref_[i]));
}

double BubbleSystem::maxTravelSinceRefresh() const { return movement_.maxTravel(); }

std::vector<int> BubbleSystem::travellers(double threshold) const { return movement_.travellers(threshold); }

void BubbleSystem::resetTravel(std::span<const int> ids) { movement_.resetTravel(ids, nodes_.positions); }

void BubbleSystem::clearMoved() { movement_.clear(nodes_.positions); }

void BubbleSystem::wakeAll() {
  active_.assign(std::size_t(nodes_.size()), 1);
  nextList_.valid = false;
}

void BubbleSystem::structureChanged() {
  resetForces_ = resetActivity_ = true;
  movement_.structureChanged();
  nextList_.valid = false;
}

std::vector<int> BubbleSystem::remove(const std::vector<char>& kill, bool segmentsToo) {
  structureChanged();
  const int n = nodes_.size();
  std::vector<int> map(n, -1);
  int m = 0;
  bool relink = false;
  for (int i = 0; i < n; ++i) {
    const bool segment = nodes_.kinds[i] == NodeKind::Segment;
    if (kill[i] && (nodes_.kinds[i] == NodeKind::Interior || (segmentsToo && segment))) {
      relink = relink || segment;
      continue;
    }
    map[i] = m;
    nodes_.positions[m] = nodes_.positions[i];
    nodes_.kinds[m] = nodes_.kinds[i];
    nodes_.loops[m] = nodes_.loops[i];
    nodes_.arc[m] = nodes_.arc[i];
    s_[m] = s_[i];
    sLo_[m] = sLo_[i];
    sHi_[m] = sHi_[i];
    vel_[m] = vel_[i];
    force_[m] = force_[i];
    metrics_[m] = metrics_[i];
    if (i < int(evalPos_.size())) evalPos_[m] = evalPos_[i];
    if (i < int(hint_.size())) hint_[m] = hint_[i];
    if (i < int(active_.size())) active_[m] = active_[i];
    if (i < int(kicked_.size())) kicked_[m] = kicked_[i];
    movement_.keep(i, m);
    if (i < int(clear_.size())) clear_[m] = clear_[i];
    chainPrev_[m] = chainPrev_[i];
    chainNext_[m] = chainNext_[i];
    chainShift_[m] = chainShift_[i];
    sStart_[m] = sStart_[i];
    ++m;
  }
  for (int i = 0; i < m; ++i) {
    if (chainPrev_[i] >= 0) chainPrev_[i] = map[chainPrev_[i]];
    if (chainNext_[i] >= 0) chainNext_[i] = map[chainNext_[i]];
  }
  for (int& i : segmentIds_) i = map[i];
  nodes_.positions.resize(m);
  nodes_.kinds.resize(m);
  nodes_.loops.resize(m);
  nodes_.arc.resize(m);
  s_.resize(m);
  sLo_.resize(m);
  sHi_.resize(m);
  vel_.resize(m);
  force_.resize(m);
  metrics_.resize(m);
  if (int(evalPos_.size()) > m) evalPos_.resize(m);
  if (int(hint_.size()) > m) hint_.resize(m);
  active_.resize(m, 1);
  kicked_.resize(m, 1);
  movement_.truncate(m);
  clear_.resize(m, 0.0);
  chainPrev_.resize(m);
  chainNext_.resize(m);
  chainShift_.resize(m);
  sStart_.resize(m);
  if (relink) linkChains();
  return map;
}

void MovementRecord::reserve(std::size_t n) {
  ref_.reserve(n);
  travel_.reserve(n);
  sinceClear_.reserve(n);
  stamps_.reserve(n);
}

void BubbleSystem::reserveInterior(std::size_t extra) {
  const std::size_t need = metrics_.size() + extra;
  if (metrics_.capacity() >= need) return;
  const std::size_t n = need + need / 16;
  nodes_.positions.reserve(n);
  nodes_.kinds.reserve(n);
  nodes_.loops.reserve(n);
  nodes_.arc.reserve(n);
  for (auto* v : {&s_, &sLo_, &sHi_, &chainShift_, &sStart_, &res_, &clear_}) v->reserve(n);
  for (auto* v : {&chainPrev_, &chainNext_, &hint_}) v->reserve(n);
  for (auto* v : {&vel_, &force_, &evalPos_}) v->reserve(n);
  for (auto* v : {&active_, &kicked_, &need_, &next_}) v->reserve(n);
  metrics_.reserve(n);
  movement_.reserve(n);
}

void BubbleSystem::addInterior(const Vec2& x, const Metric2& m) {
  structureChanged();
  nodes_.positions.push_back(x);
  nodes_.kinds.push_back(NodeKind::Interior);
  nodes_.loops.push_back(-1);
  nodes_.arc.push_back(-1.0);
  s_.push_back(-1.0);
  sLo_.push_back(-std::numeric_limits<double>::infinity());
  sHi_.push_back(std::numeric_limits<double>::infinity());
  chainPrev_.push_back(-1);
  chainNext_.push_back(-1);
  chainShift_.push_back(0.0);
  sStart_.push_back(-1.0);
  vel_.push_back(Vec2::Zero());
  force_.push_back(Vec2::Zero());
  metrics_.push_back(m);
  if (evalPos_.size() + 1 == metrics_.size()) evalPos_.push_back(x);
  const std::size_t n = metrics_.size();
  active_.resize(n - 1, 1);
  kicked_.resize(n - 1, 0);
  active_.push_back(1);
  kicked_.push_back(1);
  movement_.append(x, n);
  clear_.resize(n, 0.0);
}

bool BubbleSystem::displace(int i, const Vec2& x) {
  if (nodes_.kinds[i] != NodeKind::Interior || !geo_->inside(x)) return false;
  nodes_.positions[i] = x;
  vel_[i] = Vec2::Zero();
  if (std::size_t(i) < clear_.size()) clear_[i] = 0;  // unknown: the next move tests the boundary
  movement_.displaced(i, x, metrics_[i]);
  kick(i);
  return true;
}

void BubbleSystem::kick(int i) {
  structureChanged();
  active_.resize(std::size_t(nodes_.size()), 1);
  kicked_.resize(std::size_t(nodes_.size()), 0);
  active_[i] = 1;
  kicked_[i] = 1;
}

PairDistance parsePairDistance(const std::string& name) {
  if (name == "eq8") return PairDistance::Harmonic;
  if (name == "averaged") return PairDistance::Averaged;
  ABLMG_REQUIRE(false, "pair distance: expected eq8 or averaged, got '" << name << "'");
  return PairDistance::Harmonic;
}

const char* pairDistanceName(PairDistance kind) { return kind == PairDistance::Averaged ? "averaged" : "eq8"; }

}  // namespace ablmg::mesher
