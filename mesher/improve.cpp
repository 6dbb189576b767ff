#include "mesher/improve.hpp"

#include "core/error.hpp"
#include "core/predicates.hpp"
#include "mesher/quality.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace ablmg::mesher {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kMaxStar = 64;  ///< a longer star walk means a broken mesh: the vertex is not moved

int nextLocal(int k) { return k == 2 ? 0 : k + 1; }
int prevLocal(int k) { return k == 0 ? 2 : k - 1; }

/// The apex x of the triangle (a, b, x), counter-clockwise, that is equilateral in the
/// constant metric m: x = (a + b)/2 + (√3/2) J (b − a), with J the rotation by +90° in m,
/// J u = adj(m) R u / √det m (R: the Euclidean rotation by +90°).
Vec2 idealApex(const Vec2& a, const Vec2& b, const Metric2& m) {
  const Vec2 u = b - a;
  const Vec2 ru(-u.y(), u.x());
  const Vec2 ju(m.m22() * ru.x() - m.m12() * ru.y(), -m.m12() * ru.x() + m.m11() * ru.y());
  return 0.5 * (a + b) + (0.5 * std::sqrt(3.0) / std::sqrt(m.det())) * ju;
}

/// The mesh being improved, with what the edits need: triangle neighbours, one triangle per
/// vertex (to start star walks), boundary flags and every triangle's q, all kept up to date.
class Improver {
public:
  Improver(Mesh2& mesh, std::vector<Metric2>& metrics, const MetricField& field, const ImproveOptions& options,
           std::vector<double> quality)
      : mesh_(mesh), metrics_(metrics), field_(field), options_(options), quality_(std::move(quality)) {
    neighbours_ = mesh_.triangleNeighbours();
    triangleOfVertex_.assign(std::size_t(mesh_.numVertices()), -1);
    for (int t = 0; t < mesh_.numTriangles(); ++t)
      for (int v : mesh_.triangles[std::size_t(t)]) triangleOfVertex_[std::size_t(v)] = t;
    onBoundary_.assign(std::size_t(mesh_.numVertices()), 0);
    for (const auto& e : mesh_.boundaryEdges) onBoundary_[std::size_t(e.a)] = onBoundary_[std::size_t(e.b)] = 1;
    triangleMark_.assign(std::size_t(mesh_.numTriangles()), 0);
  }

  /// Runs the passes from the bad triangles `bad`; fills passes, swaps and moves.
  void run(std::vector<int> bad, ImproveStats& stats) {
    sortWorstFirst(bad);
    while (!bad.empty() && stats.passes < options_.maxPasses) {
      ++stats.passes;
      const long editsBefore = stats.swaps + stats.moves;
      for (int t : bad)
        if (isBad(t)) improveTriangle(t, stats);
      bad = stillBad(bad);
      if (stats.swaps + stats.moves == editsBefore) break;
    }
  }

  /// q of every triangle, bit-identical to elementQualities() of the current mesh.
  const std::vector<double>& qualities() const { return quality_; }

private:
  bool isBad(int t) const { return quality_[std::size_t(t)] < options_.qThreshold; }

  void sortWorstFirst(std::vector<int>& ts) const {
    std::sort(ts.begin(), ts.end(), [&](int s, int t) {
      const double qs = quality_[std::size_t(s)], qt = quality_[std::size_t(t)];
      return qs < qt || (qs == qt && s < t);
    });
  }

  /// Records that t changed in this pass (once).
  void touch(int t) {
    if (!triangleMark_[std::size_t(t)]) triangleMark_[std::size_t(t)] = 1, touched_.push_back(t);
  }

  /// The bad triangles among this pass's worklist and the triangles it changed, worst first.
  std::vector<int> stillBad(const std::vector<int>& worklist) {
    for (int t : worklist) touch(t);
    std::vector<int> bad;
    for (int t : touched_) {
      triangleMark_[std::size_t(t)] = 0;
      if (isBad(t)) bad.push_back(t);
    }
    touched_.clear();
    sortWorstFirst(bad);
    return bad;
  }

  /// q of triangle t with its vertex at local index `local` placed at p with metric mp (the
  /// vertices in stored order, so that the value is bit-identical to elementQualities()).
  double qualityWith(int t, int local, const Vec2& p, const Metric2& mp) const {
    const auto& tr = mesh_.triangles[std::size_t(t)];
    std::array<Vec2, 3> x;
    std::array<Metric2, 3> m;
    for (int k = 0; k < 3; ++k) {
      x[std::size_t(k)] = k == local ? p : mesh_.vertices[std::size_t(tr[std::size_t(k)])];
      m[std::size_t(k)] = k == local ? mp : metrics_[std::size_t(tr[std::size_t(k)])];
    }
    return triangleQuality(x[0], x[1], x[2], (1.0 / 3.0) * (m[0] + m[1] + m[2]));
  }
  double qualityOfCorners(int a, int b, int c) const {
    const auto& x = mesh_.vertices;
    return triangleQuality(x[std::size_t(a)], x[std::size_t(b)], x[std::size_t(c)],
                           (1.0 / 3.0) * (metrics_[std::size_t(a)] + metrics_[std::size_t(b)] + metrics_[std::size_t(c)]));
  }

  static int localIndex(const std::array<int, 3>& tr, int v) { return tr[0] == v ? 0 : tr[1] == v ? 1 : 2; }

  // ---- (a) swaps ----

  struct Flip {
    int edge;     ///< local index (in t) of the vertex opposite the flipped edge
    double qMin;  ///< min q of the two new triangles
  };

  /// The flip of the edge of t opposite local vertex k, if allowed: t = (p, a, b), its
  /// neighbour u = (q, b, a); the new triangles (p, a, q), (q, b, p) must be strictly ccw.
  /// Returns the new min q, or −∞ when the flip is not allowed.
  double flipQuality(int t, int k) const {
    const int u = neighbours_[std::size_t(t)][std::size_t(k)];
    if (u < 0) return -std::numeric_limits<double>::infinity();  // boundary edge
    if (!mesh_.triangleRefs.empty() && mesh_.triangleRefs[std::size_t(t)] != mesh_.triangleRefs[std::size_t(u)])
      return -std::numeric_limits<double>::infinity();
    const auto& tt = mesh_.triangles[std::size_t(t)];
    const int p = tt[std::size_t(k)], a = tt[std::size_t(nextLocal(k))], b = tt[std::size_t(prevLocal(k))];
    const int q = oppositeVertex(u, a, b);
    const auto& x = mesh_.vertices;
    if (orient2d(x[std::size_t(p)], x[std::size_t(a)], x[std::size_t(q)]) <= 0 ||
        orient2d(x[std::size_t(q)], x[std::size_t(b)], x[std::size_t(p)]) <= 0)
      return -std::numeric_limits<double>::infinity();  // the quadrilateral p, a, q, b is not strictly convex
    return std::min(qualityOfCorners(p, a, q), qualityOfCorners(q, b, p));
  }

  int oppositeVertex(int u, int a, int b) const {
    for (int v : mesh_.triangles[std::size_t(u)])
      if (v != a && v != b) return v;
    return -1;
  }

  /// The flip of an edge of t that raises the min q of its two triangles most, if by more
  /// than swapMargin.
  std::optional<Flip> bestFlip(int t) const {
    std::optional<Flip> best;
    for (int k = 0; k < 3; ++k) {
      const int u = neighbours_[std::size_t(t)][std::size_t(k)];
      if (u < 0) continue;
      const double before = std::min(quality_[std::size_t(t)], quality_[std::size_t(u)]);
      const double after = flipQuality(t, k);
      if (after > before + options_.swapMargin && (!best || after > best->qMin)) best = Flip{k, after};
    }
    return best;
  }

  /// t = (p, a, b) and u = (q, b, a) become t = (p, a, q) and u = (q, b, p).
  void flip(int t, int k) {
    const int u = neighbours_[std::size_t(t)][std::size_t(k)];
    auto& tt = mesh_.triangles[std::size_t(t)];
    auto& tu = mesh_.triangles[std::size_t(u)];
    const int p = tt[std::size_t(k)], a = tt[std::size_t(nextLocal(k))], b = tt[std::size_t(prevLocal(k))];
    const int j = localIndex(tu, oppositeVertex(u, a, b));
    const int q = tu[std::size_t(j)];
    // Neighbours across the four outer sides, named by the side.
    const int nPA = neighbours_[std::size_t(t)][std::size_t(prevLocal(k))];
    const int nBP = neighbours_[std::size_t(t)][std::size_t(nextLocal(k))];
    const int nAQ = neighbours_[std::size_t(u)][std::size_t(nextLocal(j))];
    const int nQB = neighbours_[std::size_t(u)][std::size_t(prevLocal(j))];
    tt = {p, a, q};
    tu = {q, b, p};
    neighbours_[std::size_t(t)] = {nAQ, u, nPA};
    neighbours_[std::size_t(u)] = {nBP, t, nQB};
    replaceNeighbour(nAQ, u, t);
    replaceNeighbour(nBP, t, u);
    triangleOfVertex_[std::size_t(p)] = triangleOfVertex_[std::size_t(a)] = t;
    triangleOfVertex_[std::size_t(q)] = triangleOfVertex_[std::size_t(b)] = u;
    quality_[std::size_t(t)] = qualityOfCorners(p, a, q);
    quality_[std::size_t(u)] = qualityOfCorners(q, b, p);
    touch(t);
    touch(u);
  }

  /// In triangle t (if any), the neighbour `from` becomes `to`.
  void replaceNeighbour(int t, int from, int to) {
    if (t < 0) return;
    for (int& n : neighbours_[std::size_t(t)])
      if (n == from) n = to;
  }

  // ---- (b) relocation ----

  /// The triangles around interior vertex v, counter-clockwise; false when the walk meets
  /// the boundary or does not close within kMaxStar triangles.
  bool star(int v, std::vector<int>& out) const {
    out.clear();
    const int t0 = triangleOfVertex_[std::size_t(v)];
    int t = t0;
    do {
      if (int(out.size()) == kMaxStar) return false;
      out.push_back(t);
      t = neighbours_[std::size_t(t)][std::size_t(nextLocal(localIndex(mesh_.triangles[std::size_t(t)], v)))];
      if (t < 0) return false;
    } while (t != t0);
    return true;
  }

  /// The ring side (a, b) of star triangle t = (v, a, b).
  std::array<int, 2> ringSide(int t, int v) const {
    const auto& tr = mesh_.triangles[std::size_t(t)];
    const int i = localIndex(tr, v);
    return {tr[std::size_t(nextLocal(i))], tr[std::size_t(prevLocal(i))]};
  }

  /// The points tried for v: on the segments towards the mean ideal apex of the ring sides,
  /// towards the ring's centroid and towards the ideal apex of the worst star triangle's ring
  /// side, at full, half and quarter length.
  std::vector<Vec2> candidatePositions(int v, const std::vector<int>& starTriangles) const {
    const Vec2& x = mesh_.vertices[std::size_t(v)];
    Vec2 apexMean(0, 0), centroid(0, 0), worstApex = x;
    double worstQ = std::numeric_limits<double>::infinity();
    for (int t : starTriangles) {
      const auto [a, b] = ringSide(t, v);
      const Metric2 m = (1.0 / 3.0) * (metrics_[std::size_t(a)] + metrics_[std::size_t(b)] + metrics_[std::size_t(v)]);
      const Vec2 apex = idealApex(mesh_.vertices[std::size_t(a)], mesh_.vertices[std::size_t(b)], m);
      apexMean += apex;
      centroid += mesh_.vertices[std::size_t(a)];
      if (quality_[std::size_t(t)] < worstQ) worstQ = quality_[std::size_t(t)], worstApex = apex;
    }
    apexMean /= double(starTriangles.size());
    centroid /= double(starTriangles.size());
    std::vector<Vec2> out;
    for (const Vec2& target : {apexMean, centroid, worstApex})
      for (double s : {1.0, 0.5, 0.25}) out.push_back(x + s * (target - x));
    return out;
  }

  /// Min q of v's star with v at p (metric mp).
  double starQualityAt(int v, const std::vector<int>& starTriangles, const Vec2& p, const Metric2& mp) const {
    double qMin = std::numeric_limits<double>::infinity();
    for (int t : starTriangles) {
      const int i = localIndex(mesh_.triangles[std::size_t(t)], v);
      qMin = std::min(qMin, qualityWith(t, i, p, mp));
    }
    return qMin;
  }
  /// Every star triangle (v, a, b) stays strictly counter-clockwise with v at p (exact test):
  /// p lies in the kernel of the ring polygon, so the star still tiles it.
  bool keepsStarCcw(int v, const std::vector<int>& starTriangles, const Vec2& p) const {
    for (int t : starTriangles) {
      const auto [a, b] = ringSide(t, v);
      if (orient2d(mesh_.vertices[std::size_t(a)], mesh_.vertices[std::size_t(b)], p) <= 0) return false;
    }
    return true;
  }

  struct Candidate {
    Vec2 x;       ///< position of the vertex
    Metric2 m;    ///< the field's metric there
    double q;       ///< min q of the star with the vertex there
    int unitEdges;  ///< star edges with metric length within ±10 % of 1 with the vertex there
  };

  /// Candidates rank by min(q, qThreshold), then by unitEdges, then by q: below the threshold
  /// the star's q decides; once it is reached, the position that keeps more unit-length edges
  /// wins (a bare max-min of q would trade edge lengths for shape where the metric varies fast).
  bool better(const Candidate& c, const Candidate& than) const {
    const double capped = std::min(c.q, options_.qThreshold), cappedThan = std::min(than.q, options_.qThreshold);
    if (capped != cappedThan) return capped > cappedThan;
    if (c.unitEdges != than.unitEdges) return c.unitEdges > than.unitEdges;
    return c.q > than.q;
  }

  /// Refines `best` by compass search in the metric of its start: 8 directions at 45° in
  /// metric space, steps of 0.2, 0.1, 0.05, 0.025 metric units, up to 4 moves per step length;
  /// a probe is taken when it keeps the star strictly ccw and ranks better(). At most 128
  /// field evaluations.
  void compassSearch(int v, Candidate& best) const {
    const MetricEigen e = best.m.eigen();
    const Vec2 axis1 = e.h1 * Vec2(std::cos(e.theta), std::sin(e.theta)), axis2 = e.h2 * Vec2(-std::sin(e.theta), std::cos(e.theta));
    for (double step = 0.2; step > 0.02; step *= 0.5) {
      bool moved = true;
      for (int round = 0; round < 4 && moved; ++round) {
        moved = false;
        for (int k = 0; k < 8; ++k) {
          const double angle = k * std::numbers::pi / 4;
          const Vec2 p = best.x + step * (std::cos(angle) * axis1 + std::sin(angle) * axis2);
          if (const auto c = evaluate(v, p); c && better(*c, best)) best = *c, moved = true;
        }
      }
    }
  }

  /// The candidate with v at p, or nothing if a star triangle would not be strictly ccw
  /// (or the field has no SPD metric at p).
  std::optional<Candidate> evaluate(int v, const Vec2& p) const {
    if (!p.allFinite() || !keepsStarCcw(v, starTriangles_, p)) return std::nullopt;
    Metric2 mp;
    try {
      mp = field_.at(p);
    } catch (const InputError&) {
      return std::nullopt;  // not a place to move to
    }
    return Candidate{p, mp, starQualityAt(v, starTriangles_, p, mp), unitEdges(v, p, mp)};
  }

  /// How many of v's edges have metric length within ±10 % of 1 (eq. 3, as `ablmg stats`)
  /// with v at p (metric mp).
  int unitEdges(int v, const Vec2& p, const Metric2& mp) const {
    int n = 0;
    for (int t : starTriangles_) {
      const int a = ringSide(t, v)[0];
      const double l = average(mp, metrics_[std::size_t(a)]).length(mesh_.vertices[std::size_t(a)] - p);
      n += std::abs(l - 1) <= 0.1;
    }
    return n;
  }

  /// The best position for vertex v (ranked by better()): the best of candidatePositions()
  /// refined by compassSearch(); nothing if v is on the boundary or the best position does not
  /// raise the min q of its star by more than moveMargin.
  std::optional<Candidate> bestMove(int v) {
    if (onBoundary_[std::size_t(v)] || !star(v, starTriangles_)) return std::nullopt;
    double before = std::numeric_limits<double>::infinity();
    for (int t : starTriangles_) before = std::min(before, quality_[std::size_t(t)]);
    const Vec2 x = mesh_.vertices[std::size_t(v)];
    Candidate best{x, metrics_[std::size_t(v)], before, unitEdges(v, x, metrics_[std::size_t(v)])};
    for (const Vec2& p : candidatePositions(v, starTriangles_))
      if (const auto c = evaluate(v, p); c && better(*c, best)) best = *c;
    compassSearch(v, best);
    if (!(best.q > before + options_.moveMargin)) return std::nullopt;
    return best;
  }

  /// Puts v at `to` (position and metric) and updates its star's q.
  void moveVertex(int v, const Candidate& to) {
    star(v, starTriangles_);  // closed: bestMove(v) walked it
    mesh_.vertices[std::size_t(v)] = to.x;
    metrics_[std::size_t(v)] = to.m;
    for (int t : starTriangles_) {
      const auto& tr = mesh_.triangles[std::size_t(t)];
      quality_[std::size_t(t)] = qualityOfCorners(tr[0], tr[1], tr[2]);
      touch(t);
    }
  }

  // ---- the choice ----

  /// Bad triangle t gets the better of its best flip and the best move of one of its
  /// vertices, judged by the min q of the triangles each changes (a tie goes to the flip).
  void improveTriangle(int t, ImproveStats& stats) {
    const std::optional<Flip> flipped = bestFlip(t);
    int mover = -1;
    Candidate move{};
    for (int v : std::array<int, 3>(mesh_.triangles[std::size_t(t)]))
      if (const auto c = bestMove(v); c && (mover < 0 || c->q > move.q)) mover = v, move = *c;
    if (mover >= 0 && (!flipped || move.q > flipped->qMin)) {
      moveVertex(mover, move);
      ++stats.moves;
    } else if (flipped) {
      flip(t, flipped->edge);
      ++stats.swaps;
    }
  }

  Mesh2& mesh_;
  std::vector<Metric2>& metrics_;
  const MetricField& field_;
  ImproveOptions options_;
  std::vector<double> quality_;                  ///< q of every triangle, current
  std::vector<std::array<int, 3>> neighbours_;   ///< across the side opposite local vertex k; −1: boundary
  std::vector<int> triangleOfVertex_;            ///< one triangle holding each vertex
  std::vector<char> onBoundary_;                 ///< vertex lies on a boundary edge
  std::vector<char> triangleMark_;               ///< triangle is in touched_
  std::vector<int> touched_;                     ///< triangles changed in this pass (marked)
  std::vector<int> starTriangles_;               ///< scratch
};

double minOf(const std::vector<double>& x) { return x.empty() ? 0.0 : *std::min_element(x.begin(), x.end()); }

} // namespace

void requireValid(const ImproveOptions& o) {
  ABLMG_REQUIRE(o.qThreshold > 0 && o.qThreshold <= 1, "improve options: qThreshold must be in (0, 1], got " << o.qThreshold);
  ABLMG_REQUIRE(o.maxPasses >= 0, "improve options: maxPasses must be >= 0, got " << o.maxPasses);
  ABLMG_REQUIRE(o.swapMargin >= 0 && std::isfinite(o.swapMargin), "improve options: swapMargin must be >= 0, got " << o.swapMargin);
  ABLMG_REQUIRE(o.moveMargin >= 0 && std::isfinite(o.moveMargin), "improve options: moveMargin must be >= 0, got " << o.moveMargin);
}


ImproveStats improveQuality(Mesh2& mesh, std::vector<Metric2>& metrics, const MetricField& field, const ImproveOptions& options) {
  const auto t0 = Clock::now();
  requireValid(options);
  std::vector<double> quality = elementQualities(mesh, metrics);  // checks metrics.size()
  ImproveStats stats;
  std::vector<int> bad;
  for (int t = 0; t < mesh.numTriangles(); ++t)
    if (quality[std::size_t(t)] < options.qThreshold) bad.push_back(t);
  stats.badBefore = stats.badAfter = long(bad.size());
  stats.qMinBefore = stats.qMinAfter = minOf(quality);
  if (!bad.empty() && options.maxPasses > 0) {
    Improver improver(mesh, metrics, field, options, std::move(quality));
    improver.run(std::move(bad), stats);
    const std::vector<double>& q = improver.qualities();
    stats.badAfter = long(std::count_if(q.begin(), q.end(), [&](double x) { return x < options.qThreshold; }));
    stats.qMinAfter = minOf(q);
  }
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return stats;
}

} // namespace ablmg::mesher
