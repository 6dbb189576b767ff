#include "ablmg/mesher/initial_placement.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace ablmg::mesher {
namespace {

/// Does segment ab meet the axis-aligned box [lo, hi]? (conservative: true if unsure)
bool segmentTouchesBox(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  if (std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x()) return false;
  if (std::max(a.y(), b.y()) < lo.y() || std::min(a.y(), b.y()) > hi.y()) return false;
  const Vec2 d = b - a;
  const Vec2 c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  int pos = 0, neg = 0;
  for (const auto& q : c) {
    const double s = cross(d, q - a);
    pos += s >= 0;
    neg += s <= 0;
  }
  return pos > 0 && neg > 0;
}

/// Half-open crossing of pq with ab: vertices on the line pq count on its positive side, so
/// a path through a shared polyline vertex is counted exactly once or not at all.
bool crossesHalfOpen(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  const bool sa = orient2d(p, q, a) >= 0, sb = orient2d(p, q, b) >= 0;
  if (sa == sb) return false;
  const int op = orient2d(a, b, p), oq = orient2d(a, b, q);
  return op * oq < 0;
}

/// The lattice map L = M^{-1/2} Q(φ): the unit hexagonal lattice, rotated by φ in metric
/// space, onto the unit-metric ellipse. With M = R(θ) diag(h1⁻², h2⁻²) R(θ)ᵀ,
/// L = R(θ) diag(h1, h2) R(φ − θ); φ = 0 is the symmetric root (lattice rows along the images
/// of the x axis), φ = θ puts a row along e1 (the long size), φ = θ + π/2 along e2. A hexagonal
/// lattice repeats every 60°, so φ is blended on the 6φ circle from 0 (isotropic, where θ is
/// noise) to the eigenframe (ratio h1/h2 ≥ alignRatio); θ's own period π is a multiple of 60°.
/// A field's lattice row w (cos 2α, sin 2α) (MetricField::latticeRow) with w ≥ ½ replaces φ by
/// φ_t = arg(M^{1/2} t), t = (cos α, sin α) (L maps the row direction (1, 0) onto t). A switch,
/// not a blend: a lattice turned part of the way is worse than either end (on saddles of ratio
/// 0.65–0.75, shape and rows both ramped with the weight had 9–14 % more H1² than the better
/// end; scripts/saddle_triangle_shape.py), so the rows meet in a seam where the interpolated
/// weight crosses ½.
/// Auto: the eigenframe is blended in from ratio kAutoAlignFrom to kAutoAlignRatio instead.
Eigen::Matrix2d latticeMap(const MetricEigen& e, LatticeOrientation orientation, double alignRatio,
                           const Vec2& row = Vec2::Zero()) {
  double phi = 0;
  if (orientation != LatticeOrientation::Axes) {
    const double target = e.theta + (orientation == LatticeOrientation::LongAxis ? 0.0 : std::numbers::pi / 2);
    const bool automatic = orientation == LatticeOrientation::Auto;
    const double from = automatic ? kAutoAlignFrom : 1.0, full = automatic ? kAutoAlignRatio : alignRatio;
    const double w = std::clamp((e.h1 / e.h2 - from) / std::max(full - from, 1e-12), 0.0, 1.0);
    phi = std::atan2(w * std::sin(6 * target), (1 - w) + w * std::cos(6 * target)) / 6;
  }
  const double c = std::cos(e.theta), s = std::sin(e.theta);
  if (row.norm() >= 0.5) {
    const double alpha = 0.5 * std::atan2(row.y(), row.x());
    // M^{1/2} t in the eigenframe: components (t·e1 / h1, t·e2 / h2), then back by R(θ).
    const double t1 = c * std::cos(alpha) + s * std::sin(alpha), t2 = -s * std::cos(alpha) + c * std::sin(alpha);
    const double phiRow = e.theta + std::atan2(t2 / e.h2, t1 / e.h1);
    const double sixty = std::numbers::pi / 3;
    const double diff = phiRow - phi - sixty * std::round((phiRow - phi) / sixty);
    phi += diff;
  }
  const double cp = std::cos(phi - e.theta), sp = std::sin(phi - e.theta);
  Eigen::Matrix2d r, q;
  r << c, -s, s, c;
  q << cp, -sp, sp, cp;
  return r * Eigen::Vector2d(e.h1, e.h2).asDiagonal() * q;
}

}  // namespace

DomainGeometry::DomainGeometry(const Domain& domain) {
  const auto& dl = domain.loops();
  long nseg = 0;
  lo_ = Vec2(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  hi_ = -lo_;
  for (int l = 0; l < int(dl.size()); ++l) {
    LoopPolyline p;
    p.points = dl[l].points;
    const int n = int(p.points.size());
    p.tags = dl[l].tags.empty() ? std::vector<int>(n, 1) : dl[l].tags;
    p.corners = domain.corners(l);
    p.kept = dl[l].keptSegments;
    p.cum.assign(n + 1, 0.0);
    for (int k = 0; k < n; ++k) {
      p.cum[k + 1] = p.cum[k] + (p.points[(k + 1) % n] - p.points[k]).norm();
      lo_ = lo_.cwiseMin(p.points[k]);
      hi_ = hi_.cwiseMax(p.points[k]);
      segs_.push_back({l, k});
    }
    p.length = p.cum[n];
    nseg += n;
    loops_.push_back(std::move(p));
  }
  const double diag = (hi_ - lo_).norm();
  lo_ -= Vec2::Constant(1e-9 * diag);
  hi_ += Vec2::Constant(1e-9 * diag);
  const double boxArea = std::max((hi_ - lo_).prod(), 1e-300);
  const double target = std::clamp(4.0 * double(nseg), 256.0, 4.0e6);
  grid_ = BucketGrid(lo_, hi_, std::sqrt(boxArea / target), long(target) * 2);

  std::vector<std::pair<int, int>> pairs;
  for (int id = 0; id < int(segs_.size()); ++id) {
    const auto& p = loops_[segs_[id].first];
    const Vec2& a = p.points[segs_[id].second];
    const Vec2& b = p.points[(segs_[id].second + 1) % p.points.size()];
    const int x0 = grid_.cellX(std::min(a.x(), b.x())), x1 = grid_.cellX(std::max(a.x(), b.x()));
    const int y0 = grid_.cellY(std::min(a.y(), b.y())), y1 = grid_.cellY(std::max(a.y(), b.y()));
    const double cs = grid_.cellSize(), eps = 1e-9 * cs;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 clo = grid_.lo() + Vec2(x * cs - eps, y * cs - eps), chi = clo + Vec2(cs + 2 * eps, cs + 2 * eps);
        if (segmentTouchesBox(a, b, clo, chi)) pairs.push_back({y * grid_.nx() + x, id});
      }
  }
  grid_.buildFromPairs(pairs);

  // Cell-centre status: one horizontal scanline per grid row, crossing parity from the left.
  centreInside_.assign(std::size_t(grid_.numCells()), 0);
  std::vector<std::vector<double>> rowX(std::size_t(grid_.ny()));
  const double cs = grid_.cellSize();
  for (const auto& [l, k] : segs_) {
    const auto& p = loops_[l];
    const Vec2& a = p.points[k];
    const Vec2& b = p.points[(k + 1) % p.points.size()];
    const double ylo = std::min(a.y(), b.y()), yhi = std::max(a.y(), b.y());
    const int r0 = std::max(0, int(std::ceil((ylo - lo_.y()) / cs - 0.5)) - 1);
    const int r1 = std::min(grid_.ny() - 1, int(std::floor((yhi - lo_.y()) / cs - 0.5)) + 1);
    for (int r = r0; r <= r1; ++r) {
      const double y = lo_.y() + (r + 0.5) * cs;
      if ((a.y() <= y && y < b.y()) || (b.y() <= y && y < a.y()))
        rowX[r].push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
  }
  for (int r = 0; r < grid_.ny(); ++r) {
    auto& xs = rowX[r];
    std::sort(xs.begin(), xs.end());
    std::size_t m = 0;
    for (int x = 0; x < grid_.nx(); ++x) {
      const double xc = lo_.x() + (x + 0.5) * cs;
      while (m < xs.size() && xs[m] < xc) ++m;
      centreInside_[std::size_t(r) * grid_.nx() + x] = char(m % 2);
    }
  }
}

bool DomainGeometry::inside(const Vec2& p) const {
  if (!(p.x() > lo_.x() && p.x() < hi_.x() && p.y() > lo_.y() && p.y() < hi_.y())) return false;
  const int c = grid_.cellOf(p);
  bool in = centreInside_[c] != 0;
  const Vec2 q = grid_.cellCentre(c);
  for (int id : grid_.cell(c)) {
    const auto& poly = loops_[segs_[id].first];
    const int k = segs_[id].second;
    if (crossesHalfOpen(p, q, poly.points[k], poly.points[(k + 1) % poly.points.size()])) in = !in;
  }
  return in;
}

double DomainGeometry::squaredMetricDistanceToSegment(int id, const Vec2& p, const Metric2& m) const {
  const auto& poly = loops_[segs_[id].first];
  const int k = segs_[id].second;
  const Vec2& a = poly.points[k];
  const Vec2 d = poly.points[(k + 1) % poly.points.size()] - a;
  const double t = std::clamp(m.dot(p - a, d) / m.squaredLength(d), 0.0, 1.0);
  return std::max(0.0, m.squaredLength(p - a - t * d));  // as Metric2::length clamps
}

double DomainGeometry::metricDistanceToBoundary(const Vec2& p, const Metric2& m, double searchRadius) const {
  double best = std::numeric_limits<double>::infinity();
  grid_.forEach(p, searchRadius, [&](int id) { best = std::min(best, squaredMetricDistanceToSegment(id, p, m)); });
  return std::sqrt(best);
}

double DomainGeometry::metricDistanceToBoundary(const Vec2& p, const Metric2& m, const Vec2& halfWidths) const {
  double best = std::numeric_limits<double>::infinity();
  grid_.forEachInBox(p, halfWidths.x(), halfWidths.y(),
                     [&](int id) { best = std::min(best, squaredMetricDistanceToSegment(id, p, m)); });
  return std::sqrt(best);
}

double DomainGeometry::wrap(int l, double s) const {
  const double L = loops_[l].length;
  if (s >= 0 && s < L) return s;  // what fmod returns there, exactly (2.4·10⁶ calls per layer remesh)
  s = std::fmod(s, L);
  if (s < 0) s += L;
  return s;
}

int DomainGeometry::segmentAt(int l, double s) const {
  const auto& p = loops_[l];
  s = wrap(l, s);
  const int n = int(p.points.size());
  const int k = int(std::upper_bound(p.cum.begin(), p.cum.end(), s) - p.cum.begin()) - 1;
  return std::clamp(k, 0, n - 1);
}

Vec2 DomainGeometry::pointAt(int l, double s) const {
  const auto& p = loops_[l];
  s = wrap(l, s);
  const int k = segmentAt(l, s);
  const Vec2& a = p.points[k];
  const Vec2& b = p.points[(k + 1) % p.points.size()];
  const double t = std::clamp((s - p.cum[k]) / (p.cum[k + 1] - p.cum[k]), 0.0, 1.0);
  return a + t * (b - a);
}

Vec2 DomainGeometry::tangentAt(int l, double s) const {
  const auto& p = loops_[l];
  const int k = segmentAt(l, s);
  return (p.points[(k + 1) % p.points.size()] - p.points[k]).normalized();
}

double DomainGeometry::indexArc(int l, double s) const {
  const auto& p = loops_[l];
  s = wrap(l, s);
  const int k = segmentAt(l, s);
  return k + std::clamp((s - p.cum[k]) / (p.cum[k + 1] - p.cum[k]), 0.0, 1.0 - 1e-15);
}

namespace {

/// Appends the samples of the piece [a, b) of a boundary edge (arc sa → sb, metrics ma, mb) to
/// `sub`/`subS`, halving it while it is longer than a quarter in the metric or its metric
/// length from the ends' metrics and from the halves' differ by more than 5 %: the end metrics
/// of a long edge can miss a layer that crosses it (a unit-square side crossed by a layer of
/// width 10⁻² got a tenth of the layer's boundary nodes, and the interior bubbles met the
/// boundary in slivers). At most kMaxHalvings halvings of a piece. `hint`: the last point
/// location (MetricField::evaluate with hints), carried along the boundary: under a stretched
/// background mesh a location from scratch walks across many thin triangles.
void sampleBoundaryPiece(const MetricField& metric, const Vec2& a, const Metric2& ma, double sa, const Vec2& b,
                         const Metric2& mb, double sb, int depth, int& hint, std::vector<Vec2>& sub,
                         std::vector<double>& subS) {
  constexpr int kMaxHalvings = 30;
  if (depth < kMaxHalvings) {
    const Vec2 c = 0.5 * (a + b);
    Metric2 mc;
    metric.evaluate(std::span<const Vec2>(&c, 1), std::span<Metric2>(&mc, 1), std::span<int>(&hint, 1));
    const double whole = edgeLength(a, ma, b, mb), halves = edgeLength(a, ma, c, mc) + edgeLength(c, mc, b, mb);
    if (halves > 0.25 || std::abs(halves - whole) > 0.05 * halves) {
      const double sc = 0.5 * (sa + sb);
      sampleBoundaryPiece(metric, a, ma, sa, c, mc, sc, depth + 1, hint, sub, subS);
      sampleBoundaryPiece(metric, c, mc, sc, b, mb, sb, depth + 1, hint, sub, subS);
      return;
    }
  }
  sub.push_back(a);
  subS.push_back(sa);
}

}  // namespace

void placeBoundaryNodes(const DomainGeometry& geo, const MetricField& metric, NodeSet& nodes,
                        std::vector<double>& arcLength) {
  for (int l = 0; l < int(geo.loops().size()); ++l) {
    const auto& poly = geo.loops()[l];
    const int n = int(poly.points.size());
    // Fine table (Euclidean arc, metric arc) along the closed loop.
    std::vector<Metric2> pm(n);
    metric.evaluate(poly.points, pm);
    std::vector<Vec2> sub;
    std::vector<double> subS;
    int hint = -1;
    for (int k = 0; k < n; ++k) {
      const Vec2& a = poly.points[k];
      const Vec2& b = poly.points[(k + 1) % n];
      sampleBoundaryPiece(metric, a, pm[k], poly.cum[k], b, pm[(k + 1) % n], poly.cum[k + 1], 0, hint, sub, subS);
    }
    sub.push_back(poly.points[0]);
    subS.push_back(poly.length);
    std::vector<Metric2> sm(sub.size());
    metric.evaluate(sub, sm);
    std::vector<double> sM(sub.size(), 0.0);
    for (std::size_t i = 1; i < sub.size(); ++i) sM[i] = sM[i - 1] + edgeLength(sub[i - 1], sm[i - 1], sub[i], sm[i]);
    const double LM = sM.back();
    auto metricAt = [&](double s) {  // Euclidean arc (in [0, L]) → metric arc
      const std::size_t i =
          std::clamp<std::size_t>(std::upper_bound(subS.begin(), subS.end(), s) - subS.begin(), 1, subS.size() - 1);
      const double t = (s - subS[i - 1]) / std::max(subS[i] - subS[i - 1], 1e-300);
      return sM[i - 1] + t * (sM[i] - sM[i - 1]);
    };
    auto euclidAt = [&](double t) {  // metric arc (wrapped) → Euclidean arc
      t = std::fmod(t, LM);
      if (t < 0) t += LM;
      const std::size_t i =
          std::clamp<std::size_t>(std::upper_bound(sM.begin(), sM.end(), t) - sM.begin(), 1, sM.size() - 1);
      const double f = (t - sM[i - 1]) / std::max(sM[i] - sM[i - 1], 1e-300);
      return subS[i - 1] + f * (subS[i] - subS[i - 1]);
    };
    auto push = [&](NodeKind kind, double s) {
      s = geo.wrap(l, s);
      nodes.positions.push_back(geo.pointAt(l, s));
      nodes.kinds.push_back(kind);
      nodes.loops.push_back(l);
      nodes.arc.push_back(geo.indexArc(l, s));
      arcLength.push_back(s);
    };
    if (poly.corners.empty()) {
      const int pieces = std::max(3, int(std::lround(LM)));
      double last = -1.0;
      Vec2 first{}, lastPoint{};
      for (int i = 0; i < pieces; ++i) {  // strictly increasing arcs, distinct points (as below)
        const double s = euclidAt(LM * i / pieces);
        const Vec2 x = geo.pointAt(l, s);
        if (i > 0 && (!(s > last) || x == lastPoint || x == first)) continue;
        if (i == 0) first = x;
        push(NodeKind::Segment, s);
        last = s;
        lastPoint = x;
      }
      continue;
    }
    const int nc = int(poly.corners.size());
    for (int c = 0; c < nc; ++c) {
      const double s0 = poly.cum[poly.corners[c]];
      const double s1 = c + 1 < nc ? poly.cum[poly.corners[c + 1]] : poly.cum[poly.corners[0]] + poly.length;
      const double m0 = metricAt(s0);
      const double m1 = s1 <= poly.length ? metricAt(s1) : metricAt(s1 - poly.length) + LM;
      const bool kept = !poly.kept.empty() && poly.kept[std::size_t(poly.corners[c])] &&
                        poly.corners[(c + 1) % nc] == (poly.corners[c] + 1) % n;  // one kept segment
      const int pieces = kept ? 1 : std::max(1, int(std::lround(m1 - m0)));
      push(NodeKind::Vertex, s0);
      // Strictly increasing arcs and distinct points, corners included: where the metric size
      // falls below the resolution of the tables (or of the coordinates), a node that would
      // coincide with its predecessor or with the next corner is not placed.
      double last = s0;
      Vec2 lastPoint = geo.pointAt(l, s0);
      const Vec2 endPoint = geo.pointAt(l, s1);
      for (int i = 1; i < pieces; ++i) {
        double s = euclidAt(m0 + (m1 - m0) * i / pieces);
        if (s < s0) s += poly.length;  // the piece that wraps past the loop's start
        const Vec2 x = geo.pointAt(l, s);
        if (!(s > last && s < s1) || x == lastPoint || x == endPoint) continue;
        push(NodeKind::Segment, s);
        last = s;
        lastPoint = x;
      }
    }
  }
}

LatticeOrientation parseLatticeOrientation(const std::string& name) {
  if (name == "axes") return LatticeOrientation::Axes;
  if (name == "long") return LatticeOrientation::LongAxis;
  if (name == "short") return LatticeOrientation::ShortAxis;
  if (name == "auto") return LatticeOrientation::Auto;
  ABLMG_REQUIRE(false, "lattice orientation: expected axes, short, long or auto, got '" << name << "'");
  return LatticeOrientation::Axes;
}

const char* latticeOrientationName(LatticeOrientation orientation) {
  switch (orientation) {
    case LatticeOrientation::LongAxis:
      return "long";
    case LatticeOrientation::ShortAxis:
      return "short";
    case LatticeOrientation::Auto:
      return "auto";
    default:
      return "axes";
  }
}

namespace {

/// One breadth-first growth of the metric-hexagonal lattice (placeInteriorNodes) over the
/// band of the plane y ∈ [y0, y1): candidates outside it are dropped. The nodes it must keep
/// clear of (the boundary nodes, a neighbour band's lattice) come first as context; the band's
/// own nodes follow them. `margin`: how far beyond the band the context reaches; a candidate
/// whose spacing box is taller than that could miss a node outside, and sets `tooTall` (the
/// caller then grows the lattice in one piece). The whole plane with an infinite margin is the
/// serial growth.
class LatticeGrower {
 public:
  LatticeGrower(const DomainGeometry& geo, const MetricField& metric, const InteriorPlacementOptions& options, Vec2 lo,
                Vec2 hi, double spacing, double y0, double y1, double margin, std::size_t capacity)
      : geo_(geo),
        metric_(metric),
        o_(options),
        y0_(y0),
        y1_(y1),
        margin_(margin),
        constant_(metric.isConstant()),
        rows_(!constant_ && metric.hasLatticeRows()),
        m0_(metric.at(0.5 * (lo + hi))),
        grid_(lo, hi, std::max(spacing, 1e-12 * (hi - lo).norm()), 1L << 23) {
    // Reserved above glibc's mmap threshold (4 MB, fixed by the ablmg program) even for int
    // arrays: mapped, untouched pages cost no memory, and released arrays go back to the
    // system. Grown below it, the bands' arrays left heap holes that stayed resident (the
    // 10⁶-triangle refinement's peak: 200–204 MB against 184–186 MB grown in one piece).
    capacity = std::max(capacity, std::size_t(4 << 20) / sizeof(int) + 1);
    grid_.clearIncremental(int(capacity));
    pos_.reserve(capacity);
    ms_.reserve(capacity);
    triangles_.reserve(capacity);
    links_.reserve(capacity);
    queue_.reserve(capacity);
    for (int k = 0; k < 6; ++k)
      dirs_.emplace_back(std::cos(k * std::numbers::pi / 3), std::sin(k * std::numbers::pi / 3));
  }
  /// A node placed before (boundary, neighbour band): kept clear of, never moved.
  int addContext(const Vec2& p, const Metric2& m) {
    ++firstOwn_;
    return add(p, m);
  }
  /// Takes point c (metric m) if it passes the tests: its id, else −1.
  /// `triangle`: the background triangle holding c (−1: unknown), where its lattice row is read.
  int take(const Vec2& c, const Metric2& m, int triangle = -1) { return acceptable(c, m) ? add(c, m, triangle) : -1; }
  /// Takes point c (metric m) if it passes the tests, and grows the lattice from it.
  void seed(const Vec2& c, const Metric2& m, int triangle = -1) {
    const int id = take(c, m, triangle);
    if (id < 0) return;
    queue_.assign(1, id);
    grow();
  }
  void seed(const Vec2& c) {
    const Metric2 m = metricAt(c);
    seed(c, m, hint_);
  }
  /// Grows from the given nodes (ids of this grower) first, then from what they add.
  void growFrom(std::vector<int> ids) {
    queue_ = std::move(ids);
    grow();
  }
  /// The band's own nodes and their metrics (positions()[firstOwn() ...]).
  const std::vector<Vec2>& positions() const { return pos_; }
  const std::vector<Metric2>& metrics() const { return ms_; }
  int firstOwn() const { return firstOwn_; }
  bool tooTall() const { return tooTall_; }
  /// Frees the nodes, the grid and the queue (after the caller has taken the nodes).
  void release() {
    pos_ = {};
    ms_ = {};
    triangles_ = {};
    links_ = {};
    queue_ = {};
    grid_ = BucketGrid();
  }

 private:
  /// Located from the previous candidate's triangle (lattice candidates come in neighbouring
  /// runs; MetricField::evaluate falls back on its own start when that one is far).
  Metric2 metricAt(const Vec2& p) {
    if (constant_) return m0_;
    Metric2 m;
    metric_.evaluate(std::span<const Vec2>(&p, 1), std::span<Metric2>(&m, 1), std::span<int>(&hint_, 1));
    return m;
  }
  // A candidate c (metric m) is kept if it is far enough from every node, inside, and far
  // enough from the walls; the cheapest test first (most lattice candidates land on a node
  // placed before). Both searches scan the bounding box of the metric ball (reachBox), not
  // the square of its long half-axis h1: on a boundary-layer metric (anisotropy up to 10⁴)
  // the square held ~10³ cells and this test took 0.4 s of a 1.8 s remesh.
  // A candidate proposed by node `from` (−1: a seed) is most often blocked by a lattice
  // neighbour of `from` or of theirs (links_), which are checked first, within the box the grid
  // scans: the same answer as the grid's alone, without walking its cells, which in a boundary
  // layer (anisotropy 10⁴) hold hundreds of nodes each. blocker_: the node found, or −1.
  bool acceptable(const Vec2& c, const Metric2& m, int from = -1) {
    blocker_ = -1;
    if (!(c.y() >= y0_ && c.y() < y1_)) return false;
    const double r2 = o_.minNodeDistance * o_.minNodeDistance;
    const Vec2 reach = reachBox(m, o_.minNodeDistance);
    if (reach.y() > margin_) tooTall_ = true;
    const auto blocks = [&](int q) {
      if (!(m.squaredLength(pos_[q] - c) < r2)) return false;
      blocker_ = q;
      return true;
    };
    const bool taken =
        (from >= 0 && linkedBlocker(from, c, reach, blocks)) || grid_.anyIncremental(c, reach.x(), reach.y(), blocks);
    if (taken || !geo_.inside(c)) return false;
    return geo_.metricDistanceToBoundary(c, m, reachBox(m, o_.minWallDistance)) >= o_.minWallDistance;
  }
  /// Whether `blocks` holds for a node linked to `from` or to one of those, among the nodes in
  /// the box c ± reach (compared as the grid's cell range is computed, so each lies in a cell
  /// anyIncremental visits).
  template <class Blocks>
  bool linkedBlocker(int from, const Vec2& c, const Vec2& reach, Blocks&& blocks) const {
    const double x0 = c.x() - reach.x(), x1 = c.x() + reach.x(), y0 = c.y() - reach.y(), y1 = c.y() + reach.y();
    const auto test = [&](int q) {
      const Vec2& xq = pos_[std::size_t(q)];
      return xq.x() >= x0 && xq.x() <= x1 && xq.y() >= y0 && xq.y() <= y1 && blocks(q);
    };
    for (int a : links_[std::size_t(from)]) {
      if (a < 0) break;
      if (test(a)) return true;
      for (int b : links_[std::size_t(a)]) {
        if (b < 0) break;
        if (b != from && test(b)) return true;
      }
    }
    return false;
  }
  void link(int a, int b) {
    const auto one = [](std::array<int, kLinks>& l, int v) {
      for (int& slot : l) {
        if (slot == v) return;
        if (slot < 0) {
          slot = v;
          return;
        }
      }
    };
    one(links_[std::size_t(a)], b);
    one(links_[std::size_t(b)], a);
  }
  int add(const Vec2& c, const Metric2& m, int triangle = -1) {
    const int id = int(pos_.size());
    pos_.push_back(c);
    ms_.push_back(m);
    triangles_.push_back(triangle);
    links_.emplace_back();
    links_.back().fill(-1);
    grid_.insert(id, c);
    return id;
  }
  Vec2 latticeRowAt(int p) {
    const int t = triangles_[std::size_t(p)];
    if (t >= 0) rowHint_ = t;
    return metric_.latticeRow(pos_[std::size_t(p)], rowHint_);
  }
  void grow() {
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const int p = queue_[head];
      const Vec2 x = pos_[p];
      const Metric2 m = ms_[p];
      const MetricEigen e = m.eigen();
      const Eigen::Matrix2d s = latticeMap(e, o_.orientation, o_.alignRatio, rows_ ? latticeRowAt(p) : Vec2::Zero());
      for (const Vec2& d : dirs_) {
        const Vec2 c = x + s * d;
        if (acceptable(c, m, p)) {
          const Metric2 mc = metricAt(c);
          const int k = add(c, mc, hint_);
          queue_.push_back(k);
          link(p, k);
        } else if (blocker_ >= 0) {
          link(p, blocker_);
        }
      }
    }
  }

  const DomainGeometry& geo_;
  const MetricField& metric_;
  const InteriorPlacementOptions& o_;
  double y0_, y1_, margin_;
  bool constant_, rows_;
  Metric2 m0_;
  BucketGrid grid_;
  std::vector<Vec2> pos_, dirs_;
  std::vector<Metric2> ms_;
  /// Per node, up to kLinks lattice neighbours met so far (the nodes its candidates became or
  /// were blocked by, and back), −1 in the free slots.
  static constexpr int kLinks = 6;
  std::vector<std::array<int, kLinks>> links_;
  std::vector<int> queue_;
  /// Per node, the background triangle its metric was interpolated in (−1: context, warm seed,
  /// constant field): its lattice row is read there, where a walk from the previous node's
  /// triangle crossed hundreds of thin triangles of a layer (1.2·10⁴ instructions per row).
  std::vector<int> triangles_;
  int hint_ = -1, rowHint_ = -1, firstOwn_ = 0, blocker_ = -1;
  bool tooTall_ = false;
};

/// Probe points (lattice seeds for the parts the growth does not reach): a g × rows grid over
/// the box, nearest to the box centre first.
std::vector<Vec2> probePoints(const Vec2& lo, const Vec2& hi, int g, int rows) {
  std::vector<Vec2> probes;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < g; ++x)
      probes.push_back(lo + Vec2((x + 0.5) / g * (hi.x() - lo.x()), (y + 0.5) / rows * (hi.y() - lo.y())));
  const Vec2 mid = 0.5 * (lo + hi);
  std::stable_sort(probes.begin(), probes.end(),
                   [&](const Vec2& a, const Vec2& b) { return (a - mid).squaredNorm() < (b - mid).squaredNorm(); });
  return probes;
}

/// Bands of the banded growth: one per ~kBandNodes expected nodes, an even number from 4 to
/// kMaxBands; 0 below 4 bands' worth of nodes, for warm starts (seeds go first, in order) and
/// for fields that are not thread-safe (AnalyticMetricField): those grow in one piece.
constexpr double kBandNodes = 40000;
constexpr int kMaxBands = 32;
int latticeBands(const MetricField& metric, const Vec2& lo, const Vec2& hi, double spacing, bool warm) {
  const bool threadSafe = metric.isConstant() || metric.isThreadSafe();
  const double expected = (hi - lo).prod() / std::max(spacing * spacing, 1e-300);
  if (warm || !threadSafe || !(expected >= 4 * kBandNodes)) return 0;
  return 2 * std::clamp(int(expected / (2 * kBandNodes)), 2, kMaxBands / 2);
}

/// The banded growth: the even bands in parallel (each kept clear of the boundary nodes), then
/// the odd ones (each first grows from its two neighbours' nodes near it, so the lattice runs
/// on across the band's edges, then from its probes). A band's nodes depend on its own inputs
/// only: the same lattice for any thread count. Empty when some candidate's spacing box is
/// taller than the margin (a quarter band): the caller grows in one piece.
std::vector<LatticeGrower> growBands(const DomainGeometry& geo, const MetricField& metric, const NodeSet& nodes,
                                     const std::vector<Metric2>& ms, double spacing,
                                     const InteriorPlacementOptions& options, int bands) {
  const auto box = geo.boundingBox();          // named, not a structured binding: the lambdas
  const Vec2 lo = box.first, hi = box.second;  // below capture it (clang 14)
  const double height = (hi.y() - lo.y()) / bands, margin = 0.25 * height;
  const auto edge = [&](int b) { return b == bands ? std::numeric_limits<double>::infinity() : lo.y() + b * height; };
  const std::vector<Vec2> probes = probePoints(lo, hi, 48, 6 * bands);
  std::vector<LatticeGrower> g;
  g.reserve(std::size_t(bands));
  const double expected = (hi - lo).prod() / (spacing * spacing) / bands;
  for (int b = 0; b < bands; ++b) {
    const double y0 = b == 0 ? -std::numeric_limits<double>::infinity() : edge(b), y1 = edge(b + 1);
    g.emplace_back(geo, metric, options, Vec2(lo.x(), std::max(lo.y(), edge(b) - margin)),
                   Vec2(hi.x(), std::min(hi.y(), lo.y() + (b + 1) * height + margin)), spacing, y0, y1, margin,
                   std::size_t(2 * expected));
  }
  // The bands' seeds snapped to one lattice, the unit hexagonal one mapped by the box centre's
  // latticeMap: under a constant metric the fronts of two bands then meet on the same lattice,
  // without a seam (seams cost ~2 node rows each, which the population control then refills).
  const Vec2 mid = 0.5 * (lo + hi);
  const Eigen::Matrix2d map = latticeMap(metric.at(mid).eigen(), options.orientation, options.alignRatio);
  Eigen::Matrix2d inverse;
  inverse << map(1, 1), -map(0, 1), -map(1, 0), map(0, 0);
  inverse /= map(0, 0) * map(1, 1) - map(0, 1) * map(1, 0);
  const double rowHeight = std::sqrt(3.0) / 2;
  const auto snap = [&](const Vec2& p) {
    const Vec2 q = inverse * (p - mid);
    const double j = std::round(q.y() / rowHeight), i = std::round(q.x() - 0.5 * j);
    return Vec2(mid + map * Vec2(i + 0.5 * j, rowHeight * j));
  };
  const auto near = [&](int b, const Vec2& p) {
    return p.y() >= lo.y() + b * height - margin && p.y() < lo.y() + (b + 1) * height + margin;
  };
  ParallelFailure failure;
  for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int b = parity; b < bands; b += 2)
      failure.run(b, [&] {
        LatticeGrower& band = g[std::size_t(b)];
        for (int i = 0; i < nodes.size(); ++i)
          if (near(b, nodes.positions[i])) band.addContext(nodes.positions[i], ms[std::size_t(i)]);
        std::vector<int> from;
        for (const int nb : {b - 1, b + 1}) {
          if (parity == 0 || nb < 0 || nb >= bands) continue;
          const LatticeGrower& other = g[std::size_t(nb)];
          for (std::size_t i = std::size_t(other.firstOwn()); i < other.positions().size(); ++i)
            if (near(b, other.positions()[i]))
              from.push_back(band.addContext(other.positions()[i], other.metrics()[i]));
        }
        band.growFrom(std::move(from));
        for (const Vec2& probe : probes)
          if (probe.y() >= edge(b) && probe.y() < edge(b + 1)) band.seed(snap(probe));
      });
    failure.rethrow();
  }
  for (const auto& band : g)
    if (band.tooTall()) return {};
  return g;
}

}  // namespace

void placeInteriorNodes(const DomainGeometry& geo, const MetricField& metric, NodeSet& nodes, double spacingHint,
                        const InteriorPlacementOptions& options, std::span<const Vec2> seeds) {
  const auto [lo, hi] = geo.boundingBox();
  const bool constant = metric.isConstant();
  const Metric2 m0 = metric.at(0.5 * (lo + hi));
  std::vector<Metric2> ms(nodes.size());
  if (constant)
    std::fill(ms.begin(), ms.end(), m0);
  else
    metric.evaluate(nodes.positions, ms);
  auto append = [&](const LatticeGrower& band) {
    for (std::size_t i = std::size_t(band.firstOwn()); i < band.positions().size(); ++i) {
      nodes.positions.push_back(band.positions()[i]);
      nodes.kinds.push_back(NodeKind::Interior);
      nodes.loops.push_back(-1);
      nodes.arc.push_back(-1.0);
    }
  };
  const int bands = latticeBands(metric, lo, hi, spacingHint, !seeds.empty());
  if (bands > 0) {
    std::vector<LatticeGrower> g = growBands(geo, metric, nodes, ms, spacingHint, options, bands);
    std::size_t total = nodes.positions.size();
    for (const auto& band : g) total += band.positions().size() - std::size_t(band.firstOwn());
    nodes.positions.reserve(total);
    nodes.kinds.reserve(total);
    nodes.loops.reserve(total);
    nodes.arc.reserve(total);
    for (auto& band : g) {
      append(band);
      band.release();
    }

    if (!g.empty()) return;
  }
  const double inf = std::numeric_limits<double>::infinity();
  LatticeGrower one(geo, metric, options, lo, hi, spacingHint, -inf, inf, inf, nodes.size() * 4);
  for (int i = 0; i < nodes.size(); ++i) one.addContext(nodes.positions[i], ms[std::size_t(i)]);
  // Warm start: the seeds that fit (same spacing rules as lattice points), then lattice
  // growth from each of them into the gaps they leave.
  if (!seeds.empty()) {
    std::vector<Metric2> sm(seeds.size());
    if (constant)
      std::fill(sm.begin(), sm.end(), m0);
    else
      metric.evaluate(seeds, sm);
    std::vector<int> taken;
    for (std::size_t k = 0; k < seeds.size(); ++k)
      if (const int id = one.take(seeds[k], sm[k]); id >= 0) taken.push_back(id);
    one.growFrom(std::move(taken));
  }
  for (const Vec2& probe : probePoints(lo, hi, 48, 48)) one.seed(probe);
  append(one);
}

double metricArea(const Domain& domain, const DomainGeometry& geo, const MetricField& metric, int g) {
  const auto box = geo.boundingBox();          // named, not a structured binding: the lambda below
  const Vec2 lo = box.first, hi = box.second;  // captures it, which clang 14 rejects
  if (metric.isConstant()) return domain.area() * std::sqrt(metric.at(0.5 * (lo + hi)).det());
  const Vec2 d = (hi - lo) / g;
  const auto cellCentre = [&](int x, int y) { return Vec2(lo + Vec2((x + 0.5) * d.x(), (y + 0.5) * d.y())); };
  // Inside tests by rows in parallel (geo is read-only), then √det M at the inside centres
  // (MetricField::gridSqrtDeterminants: a background field rasterises its triangles, 6·10⁴
  // centres at g = 256 located one by one cost 10 % of a small slit remesh). The sum runs in
  // raster order.
  std::vector<char> in(std::size_t(g) * std::size_t(g));
#pragma omp parallel for schedule(static) if (g * g >= kMinParallelItems)
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x) in[std::size_t(y) * std::size_t(g) + std::size_t(x)] = geo.inside(cellCentre(x, y));
  std::vector<double> density(in.size(), 0.0);
  metric.gridSqrtDeterminants(lo, d, g, g, in, density);
  double sum = 0;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (in[i]) sum += density[i];
  return sum * d.x() * d.y();
}

long predictedNodeCount(double metricAreaValue, long boundaryNodes, int holes) {
  return std::lround(2.0 / std::sqrt(3.0) * metricAreaValue + 0.5 * double(boundaryNodes) + 1.0 - holes);
}

}  // namespace ablmg::mesher
