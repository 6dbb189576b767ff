#include "ablmg/mesher/improve.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace ablmg::mesher {
namespace {

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

/// One triangle of a vertex's star as it is, or as an edit would make it: the three corners
/// in stored order, corner `local` being the vertex that is placed (its id in `corners` is
/// irrelevant); `t` the triangle's id, or −1 if the edit creates it.
struct StarSlot {
  int t;
  std::array<int, 3> corners;
  int local;
};

/// The mesh being improved, with what the edits need: triangle neighbours, one triangle per
/// vertex (to start star walks), boundary flags and every triangle's q, all kept up to date.
/// Collapses leave dead vertices and triangles behind; compact() removes them at the end.
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
    deadVertex_.assign(std::size_t(mesh_.numVertices()), 0);
    triangleMark_.assign(std::size_t(mesh_.numTriangles()), 0);
    deadTriangle_.assign(std::size_t(mesh_.numTriangles()), 0);
    changedAt_.assign(std::size_t(mesh_.numTriangles()), 0);
    collapseFailedAt_.assign(std::size_t(mesh_.numTriangles()), -1);
    moveFailedAt_.assign(std::size_t(mesh_.numVertices()), -1);
  }

  /// Runs the passes from the bad triangles `bad`; fills passes and the edit counts.
  void run(std::vector<int> bad, ImproveStats& stats) {
    sortWorstFirst(bad);
    while (!bad.empty() && stats.passes < options_.maxPasses) {
      ++stats.passes;
      const long editsBefore = edits(stats);
      for (int t : bad)
        if (isBad(t)) improveTriangle(t, stats);
      bad = stillBad(bad);
      if (edits(stats) == editsBefore) break;
    }
  }

  /// Removes dead triangles and vertices, keeping the survivors' order (ids shift down; the
  /// boundary edges are renumbered). Returns q of every triangle of the compacted mesh,
  /// bit-identical to elementQualities() of it.
  std::vector<double> compact() {
    std::vector<int> newId(mesh_.vertices.size(), -1);
    int nv = 0;
    for (std::size_t v = 0; v < mesh_.vertices.size(); ++v) {
      if (deadVertex_[v]) continue;
      newId[v] = nv;
      mesh_.vertices[std::size_t(nv)] = mesh_.vertices[v];
      metrics_[std::size_t(nv)] = metrics_[v];
      if (!mesh_.vertexRefs.empty()) mesh_.vertexRefs[std::size_t(nv)] = mesh_.vertexRefs[v];
      ++nv;
    }
    mesh_.vertices.resize(std::size_t(nv));
    metrics_.resize(std::size_t(nv));
    if (!mesh_.vertexRefs.empty()) mesh_.vertexRefs.resize(std::size_t(nv));
    std::size_t nt = 0;
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      if (deadTriangle_[t]) continue;
      for (int& v : mesh_.triangles[t]) v = newId[std::size_t(v)];
      mesh_.triangles[nt] = mesh_.triangles[t];
      quality_[nt] = quality_[t];
      if (!mesh_.triangleRefs.empty()) mesh_.triangleRefs[nt] = mesh_.triangleRefs[t];
      ++nt;
    }
    mesh_.triangles.resize(nt);
    quality_.resize(nt);
    if (!mesh_.triangleRefs.empty()) mesh_.triangleRefs.resize(nt);
    for (auto& e : mesh_.boundaryEdges) e.a = newId[std::size_t(e.a)], e.b = newId[std::size_t(e.b)];
    return std::move(quality_);
  }

 private:
  static long edits(const ImproveStats& s) { return s.swaps + s.moves + s.collapses; }
  bool isBad(int t) const { return !deadTriangle_[std::size_t(t)] && quality_[std::size_t(t)] < options_.qThreshold; }

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

  /// q of the star slot s with its placed corner at p (metric mp), the corners in stored
  /// order, so that the value is bit-identical to elementQualities() once the edit is made.
  double slotQuality(const StarSlot& s, const Vec2& p, const Metric2& mp) const {
    std::array<Vec2, 3> x;
    std::array<Metric2, 3> m;
    for (int k = 0; k < 3; ++k) {
      x[std::size_t(k)] = k == s.local ? p : mesh_.vertices[std::size_t(s.corners[std::size_t(k)])];
      m[std::size_t(k)] = k == s.local ? mp : metrics_[std::size_t(s.corners[std::size_t(k)])];
    }
    return triangleQuality(x[0], x[1], x[2], (1.0 / 3.0) * (m[0] + m[1] + m[2]));
  }
  double qualityOfCorners(int a, int b, int c) const {
    const auto& x = mesh_.vertices;
    return triangleQuality(
        x[std::size_t(a)], x[std::size_t(b)], x[std::size_t(c)],
        (1.0 / 3.0) * (metrics_[std::size_t(a)] + metrics_[std::size_t(b)] + metrics_[std::size_t(c)]));
  }
  void updateQuality(int t) {
    const auto& tr = mesh_.triangles[std::size_t(t)];
    quality_[std::size_t(t)] = qualityOfCorners(tr[0], tr[1], tr[2]);
    changedAt_[std::size_t(t)] = edits_;
    touch(t);
  }
  /// No triangle of `slots` changed since edit number `stamp` (a search that failed then
  /// would fail again: its result depends only on these triangles' vertices and metrics).
  bool unchangedSince(const std::vector<StarSlot>& slots, long stamp) const {
    if (stamp < 0) return false;
    for (const StarSlot& s : slots)
      if (changedAt_[std::size_t(s.t)] > stamp) return false;
    return true;
  }
  /// Metric length of the edge a–b (eq. 3 with the mean of the end metrics, as `ablmg stats`).
  double edgeLength(int a, int b) const {
    return average(metrics_[std::size_t(a)], metrics_[std::size_t(b)])
        .length(mesh_.vertices[std::size_t(b)] - mesh_.vertices[std::size_t(a)]);
  }

  static int localIndex(const std::array<int, 3>& tr, int v) { return tr[0] == v ? 0 : tr[1] == v ? 1 : 2; }
  int oppositeVertex(int u, int a, int b) const {
    for (int v : mesh_.triangles[std::size_t(u)])
      if (v != a && v != b) return v;
    return -1;
  }
  bool sameRef(int t, int u) const {
    return mesh_.triangleRefs.empty() || mesh_.triangleRefs[std::size_t(t)] == mesh_.triangleRefs[std::size_t(u)];
  }
  /// In triangle t (if any), the neighbour `from` becomes `to`.
  void replaceNeighbour(int t, int from, int to) {
    if (t < 0) return;
    for (int& n : neighbours_[std::size_t(t)])
      if (n == from) n = to;
  }

  // ---- (a) swaps ----

  /// The flip of the edge of t opposite local vertex k, if allowed: t = (p, a, b), its
  /// neighbour u = (q, b, a); the new triangles (p, a, q), (q, b, p) must be strictly ccw.
  /// Returns the new min q, or −∞ when the flip is not allowed.
  double flipQuality(int t, int k) const {
    const int u = neighbours_[std::size_t(t)][std::size_t(k)];
    if (u < 0 || !sameRef(t, u)) return -std::numeric_limits<double>::infinity();  // boundary edge or region border
    const auto& tt = mesh_.triangles[std::size_t(t)];
    const int p = tt[std::size_t(k)], a = tt[std::size_t(nextLocal(k))], b = tt[std::size_t(prevLocal(k))];
    const int q = oppositeVertex(u, a, b);
    const auto& x = mesh_.vertices;
    if (orient2d(x[std::size_t(p)], x[std::size_t(a)], x[std::size_t(q)]) <= 0 ||
        orient2d(x[std::size_t(q)], x[std::size_t(b)], x[std::size_t(p)]) <= 0)
      return -std::numeric_limits<double>::infinity();  // the quadrilateral p, a, q, b is not strictly convex
    return std::min(qualityOfCorners(p, a, q), qualityOfCorners(q, b, p));
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
    updateQuality(t);
    updateQuality(u);
  }

  // ---- placing one vertex in a star (moves, and the vertex a collapse leaves) ----

  /// The triangles around interior vertex v as star slots; false when the walk meets the
  /// boundary or does not close within kMaxStar triangles.
  bool star(int v, std::vector<StarSlot>& out) const {
    out.clear();
    const int t0 = triangleOfVertex_[std::size_t(v)];
    int t = t0;
    do {
      if (int(out.size()) == kMaxStar) return false;
      const auto& tr = mesh_.triangles[std::size_t(t)];
      const int i = localIndex(tr, v);
      out.push_back({t, tr, i});
      t = neighbours_[std::size_t(t)][std::size_t(nextLocal(i))];
      if (t < 0) return false;
    } while (t != t0);
    return true;
  }

  /// The ring side (a, b) of slot s = (v, a, b).
  static std::array<int, 2> ringSide(const StarSlot& s) {
    return {s.corners[std::size_t(nextLocal(s.local))], s.corners[std::size_t(prevLocal(s.local))]};
  }

  /// The points tried from x (metric mx) in the star `slots`: on the segments towards the mean
  /// ideal apex of the ring sides, towards the ring's centroid and towards the ideal apex of
  /// the worst slot's ring side (its q with the vertex at x), at full, half and quarter length.
  std::vector<Vec2> candidatePositions(const Vec2& x, const Metric2& mx, const std::vector<StarSlot>& slots) const {
    Vec2 apexMean(0, 0), centroid(0, 0), worstApex = x;
    double worstQ = std::numeric_limits<double>::infinity();
    for (const StarSlot& s : slots) {
      const auto side = ringSide(s);
      const Metric2 m = (1.0 / 3.0) * (metrics_[std::size_t(side[0])] + metrics_[std::size_t(side[1])] + mx);
      const Vec2 apex = idealApex(mesh_.vertices[std::size_t(side[0])], mesh_.vertices[std::size_t(side[1])], m);
      apexMean += apex;
      centroid += mesh_.vertices[std::size_t(side[0])];
      if (const double q = slotQuality(s, x, mx); q < worstQ) worstQ = q, worstApex = apex;
    }
    apexMean /= double(slots.size());
    centroid /= double(slots.size());
    std::vector<Vec2> out;
    for (const Vec2& target : {apexMean, centroid, worstApex})
      for (double s : {1.0, 0.5, 0.25}) out.push_back(x + s * (target - x));
    return out;
  }

  struct Candidate {
    Vec2 x;         ///< position of the placed vertex
    Metric2 m;      ///< the field's metric there
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

  /// The candidate with the vertex of slots_ at p, or nothing if a slot would not be strictly
  /// ccw (exact orient2d: p must lie in the kernel of the ring polygon, so the star tiles it)
  /// or the field has no SPD metric at p.
  std::optional<Candidate> evaluate(const Vec2& p) const {
    if (!p.allFinite()) return std::nullopt;
    for (const StarSlot& s : slots_) {
      const auto side = ringSide(s);
      if (orient2d(mesh_.vertices[std::size_t(side[0])], mesh_.vertices[std::size_t(side[1])], p) <= 0)
        return std::nullopt;
    }
    Metric2 mp;
    try {
      // Located from the previous probe's triangle (the probes of a star are close;
      // MetricField::evaluate falls back on its own start when that one is far).
      field_.evaluate(std::span<const Vec2>(&p, 1), std::span<Metric2>(&mp, 1), std::span<int>(&fieldHint_, 1));
    } catch (const InputError&) {
      return std::nullopt;  // not a place to move to
    }
    return at(p, mp);
  }
  /// The candidate with the vertex of slots_ at p with metric mp (no admissibility test).
  Candidate at(const Vec2& p, const Metric2& mp) const {
    Candidate c{p, mp, std::numeric_limits<double>::infinity(), 0};
    for (const StarSlot& s : slots_) {
      c.q = std::min(c.q, slotQuality(s, p, mp));
      const int a = ringSide(s)[0];  // every ring vertex starts one ring side
      c.unitEdges +=
          std::abs(average(mp, metrics_[std::size_t(a)]).length(mesh_.vertices[std::size_t(a)] - p) - 1) <= 0.1;
    }
    return c;
  }

  /// Refines `best` by compass search in the metric of its start: 8 directions at 45° in
  /// metric space, steps of 0.2, 0.1, 0.05, 0.025 metric units, up to 4 moves per step length;
  /// a probe is taken when it is admissible and ranks better(). At most 128 field evaluations.
  void compassSearch(Candidate& best) const {
    const MetricEigen e = best.m.eigen();
    const Vec2 axis1 = e.h1 * Vec2(std::cos(e.theta), std::sin(e.theta)),
               axis2 = e.h2 * Vec2(-std::sin(e.theta), std::cos(e.theta));
    for (double step = 0.2; step > 0.02; step *= 0.5) {
      bool moved = true;
      for (int round = 0; round < 4 && moved; ++round) {
        moved = false;
        for (int k = 0; k < 8; ++k) {
          const double angle = k * std::numbers::pi / 4;
          const Vec2 p = best.x + step * (std::cos(angle) * axis1 + std::sin(angle) * axis2);
          if (const auto c = evaluate(p); c && better(*c, best)) best = *c, moved = true;
        }
      }
    }
  }

  /// The best place for the vertex of the star slots_ (ranked by better()): `start` (if
  /// given, admissible), the candidatePositions() from `base` (metric mBase) and `extra`
  /// points, refined by compassSearch(); nothing if no point is admissible.
  std::optional<Candidate> place(std::optional<Candidate> start, const Vec2& base, const Metric2& mBase,
                                 std::initializer_list<Vec2> extra = {}) const {
    std::optional<Candidate> best = start;
    auto consider = [&](const Vec2& p) {
      if (const auto c = evaluate(p); c && (!best || better(*c, *best))) best = c;
    };
    for (const Vec2& p : extra) consider(p);
    for (const Vec2& p : candidatePositions(base, mBase, slots_)) consider(p);
    if (best) compassSearch(*best);
    return best;
  }

  // ---- (b) moves ----

  /// The best position for vertex v; nothing if v is on the boundary or the best position
  /// does not raise the min q of its star by more than moveMargin.
  std::optional<Candidate> bestMove(int v) {
    if (onBoundary_[std::size_t(v)] || !star(v, slots_)) return std::nullopt;
    if (unchangedSince(slots_, moveFailedAt_[std::size_t(v)])) return std::nullopt;
    double before = std::numeric_limits<double>::infinity();
    for (const StarSlot& s : slots_) before = std::min(before, quality_[std::size_t(s.t)]);
    const Vec2 x = mesh_.vertices[std::size_t(v)];
    Candidate stay = at(x, metrics_[std::size_t(v)]);
    stay.q = before;
    const auto best = place(stay, x, metrics_[std::size_t(v)]);
    if (!(best->q > before + options_.moveMargin)) {
      moveFailedAt_[std::size_t(v)] = edits_;
      return std::nullopt;
    }
    return best;
  }

  /// Puts v at `to` (position and metric) and updates its star's q.
  void moveVertex(int v, const Candidate& to) {
    star(v, slots_);  // closed: bestMove(v) walked it
    mesh_.vertices[std::size_t(v)] = to.x;
    metrics_[std::size_t(v)] = to.m;
    for (const StarSlot& s : slots_) updateQuality(s.t);
  }

  // ---- (c) collapses of a short interior edge ----

  /// The edge a–b of t opposite local k, t = (p, a, b), and its neighbour u = (q, b, a).
  struct EdgeQuad {
    int t, u, p, a, b, q;
  };
  std::optional<EdgeQuad> edgeQuad(int t, int k) const {
    const int u = neighbours_[std::size_t(t)][std::size_t(k)];
    if (u < 0 || !sameRef(t, u)) return std::nullopt;  // boundary edge or region border
    const auto& tt = mesh_.triangles[std::size_t(t)];
    const int a = tt[std::size_t(nextLocal(k))], b = tt[std::size_t(prevLocal(k))];
    return EdgeQuad{t, u, tt[std::size_t(k)], a, b, oppositeVertex(u, a, b)};
  }
  /// The point of a–b where the lengths from a in a's metric and to b in b's metric agree.
  Vec2 metricMidpoint(int a, int b) const {
    const Vec2 &xa = mesh_.vertices[std::size_t(a)], &xb = mesh_.vertices[std::size_t(b)];
    const double la = metrics_[std::size_t(a)].length(xb - xa), lb = metrics_[std::size_t(b)].length(xb - xa);
    return xa + (lb / (la + lb)) * (xb - xa);
  }

  /// Fills slots_ with the star of a after b is merged into it (the edge e collapsed): the
  /// triangles around a and b but t and u, b replaced by a. False when a or b is on the
  /// boundary, a star is open or too long, the triangles do not share one ref, or the rings of
  /// a and b share a vertex other than p and q (the collapse would fold the mesh: link condition).
  /// `before`: the min q of the triangles the collapse changes or removes.
  bool collapseStar(const EdgeQuad& e, double& before) {
    if (onBoundary_[std::size_t(e.a)] || onBoundary_[std::size_t(e.b)]) return false;
    if (!star(e.a, starA_) || !star(e.b, slots_)) return false;
    if (starA_.size() + slots_.size() - 2 > std::size_t(kMaxStar)) return false;
    ringA_.clear();
    for (const StarSlot& s : starA_) ringA_.push_back(ringSide(s)[0]);
    std::sort(ringA_.begin(), ringA_.end());
    int shared = 0;
    for (const StarSlot& s : slots_) shared += std::binary_search(ringA_.begin(), ringA_.end(), ringSide(s)[0]);
    if (shared != 2) return false;
    std::erase_if(slots_, [&](const StarSlot& s) { return s.t == e.t || s.t == e.u; });
    for (StarSlot& s : slots_) s.corners[std::size_t(s.local)] = e.a;
    before = std::numeric_limits<double>::infinity();
    for (const StarSlot& s : starA_) {
      before = std::min(before, quality_[std::size_t(s.t)]);
      if (s.t != e.t && s.t != e.u) slots_.push_back(s);
    }
    for (const StarSlot& s : slots_)
      if (!sameRef(s.t, e.t)) return false;
    for (const StarSlot& s : slots_) before = std::min(before, quality_[std::size_t(s.t)]);
    return true;
  }
  /// The best place for the vertex left by collapsing e (tried: a, b, their metric midpoint
  /// and the candidates around it), if it raises the min q of the changed triangles by more
  /// than collapseMargin.
  std::optional<Candidate> bestCollapse(const EdgeQuad& e) {
    double before;
    if (!collapseStar(e, before)) return std::nullopt;
    const long failedAt = collapseFailedAt_[std::size_t(e.t)];
    if (unchangedSince(starA_, failedAt) && unchangedSince(slots_, failedAt)) return std::nullopt;  // t, u ∈ starA_
    const Vec2 mid = metricMidpoint(e.a, e.b);
    const auto best = place(std::nullopt, mid, average(metrics_[std::size_t(e.a)], metrics_[std::size_t(e.b)]),
                            {mesh_.vertices[std::size_t(e.a)], mesh_.vertices[std::size_t(e.b)], mid});
    if (!best || !(best->q > before + options_.collapseMargin)) {
      collapseFailedAt_[std::size_t(e.t)] = edits_;
      return std::nullopt;
    }
    return best;
  }
  /// Merges b into a (at `to`): t and u and vertex b die; their outer neighbours are stitched.
  void collapse(const EdgeQuad& e, const Candidate& to) {
    double before;
    collapseStar(e, before);  // true: bestCollapse(e) checked it
    const int nBP = neighbours_[std::size_t(e.t)][std::size_t(localIndex(mesh_.triangles[std::size_t(e.t)], e.a))];
    const int nPA = neighbours_[std::size_t(e.t)][std::size_t(localIndex(mesh_.triangles[std::size_t(e.t)], e.b))];
    const int nAQ = neighbours_[std::size_t(e.u)][std::size_t(localIndex(mesh_.triangles[std::size_t(e.u)], e.b))];
    const int nQB = neighbours_[std::size_t(e.u)][std::size_t(localIndex(mesh_.triangles[std::size_t(e.u)], e.a))];
    replaceNeighbour(nBP, e.t, nPA), replaceNeighbour(nPA, e.t, nBP);  // b–p and p–a become one edge a–p
    replaceNeighbour(nAQ, e.u, nQB), replaceNeighbour(nQB, e.u, nAQ);  // a–q and q–b become one edge a–q
    deadTriangle_[std::size_t(e.t)] = deadTriangle_[std::size_t(e.u)] = 1;
    deadVertex_[std::size_t(e.b)] = 1;
    mesh_.vertices[std::size_t(e.a)] = to.x;
    metrics_[std::size_t(e.a)] = to.m;
    triangleOfVertex_[std::size_t(e.a)] = slots_[0].t;
    triangleOfVertex_[std::size_t(e.p)] = nPA;
    triangleOfVertex_[std::size_t(e.q)] = nAQ;
    for (const StarSlot& s : slots_) {
      mesh_.triangles[std::size_t(s.t)] = s.corners;
      updateQuality(s.t);
    }
  }

  // ---- the choice ----

  /// Bad triangle t gets the best of: its best flip, the best move of one of its vertices and
  /// the collapse of its shortest edge (metric length), judged by the min q of the triangles
  /// each changes (a tie goes to the earlier kind).
  void improveTriangle(int t, ImproveStats& stats) {
    enum class Kind { None, Flip, Move, Collapse } kind = Kind::None;
    double bestQ = -std::numeric_limits<double>::infinity();
    int flipEdge = -1, mover = -1;
    Candidate chosen{};
    for (int k = 0; k < 3; ++k) {
      const int u = neighbours_[std::size_t(t)][std::size_t(k)];
      if (u < 0) continue;
      const double before = std::min(quality_[std::size_t(t)], quality_[std::size_t(u)]);
      const double after = flipQuality(t, k);
      if (after > before + options_.swapMargin && after > bestQ) kind = Kind::Flip, flipEdge = k, bestQ = after;
    }
    for (int v : std::array<int, 3>(mesh_.triangles[std::size_t(t)]))
      if (const auto c = bestMove(v); c && c->q > bestQ) kind = Kind::Move, mover = v, chosen = *c, bestQ = c->q;
    int shortest = 0;
    double shortestLength = std::numeric_limits<double>::infinity();
    const auto& tr = mesh_.triangles[std::size_t(t)];
    for (int k = 0; k < 3; ++k)
      if (const double l = edgeLength(tr[std::size_t(nextLocal(k))], tr[std::size_t(prevLocal(k))]); l < shortestLength)
        shortest = k, shortestLength = l;
    std::optional<EdgeQuad> collapsed;
    if (options_.collapseEdges)
      if (const auto e = edgeQuad(t, shortest))
        if (const auto c = bestCollapse(*e); c && c->q > bestQ)
          kind = Kind::Collapse, collapsed = e, chosen = *c, bestQ = c->q;
    if (kind != Kind::None) ++edits_;
    switch (kind) {
      case Kind::None:
        break;
      case Kind::Flip:
        flip(t, flipEdge), ++stats.swaps;
        break;
      case Kind::Move:
        moveVertex(mover, chosen), ++stats.moves;
        break;
      case Kind::Collapse:
        collapse(*collapsed, chosen), ++stats.collapses;
        break;
    }
  }

  Mesh2& mesh_;
  std::vector<Metric2>& metrics_;
  const MetricField& field_;
  mutable int fieldHint_ = -1;  ///< the last probe's location in field_ (where its walk starts)
  ImproveOptions options_;
  std::vector<double> quality_;                  ///< q of every triangle, current (dead ones: stale)
  std::vector<std::array<int, 3>> neighbours_;   ///< across the side opposite local vertex k; −1: boundary
  std::vector<int> triangleOfVertex_;            ///< one live triangle holding each live vertex
  std::vector<char> onBoundary_;                 ///< vertex lies on a boundary edge
  std::vector<char> deadVertex_, deadTriangle_;  ///< removed by a collapse (until compact())
  std::vector<char> triangleMark_;               ///< triangle is in touched_
  std::vector<int> touched_;                     ///< triangles changed in this pass (marked)
  long edits_ = 0;                               ///< edits made so far
  std::vector<long> changedAt_;                  ///< per triangle: edits_ when it last changed
  std::vector<long> moveFailedAt_;               ///< per vertex: edits_ when bestMove last failed (−1: never)
  std::vector<long> collapseFailedAt_;           ///< per triangle: edits_ when collapsing its shortest edge last failed
  std::vector<StarSlot> slots_, starA_;          ///< the star being placed in; scratch
  std::vector<int> ringA_;                       ///< scratch
};

double minOf(const std::vector<double>& x) { return x.empty() ? 0.0 : *std::min_element(x.begin(), x.end()); }

}  // namespace

void requireValid(const ImproveOptions& o) {
  ABLMG_REQUIRE(o.qThreshold > 0 && o.qThreshold <= 1,
                "improve options: qThreshold must be in (0, 1], got " << o.qThreshold);
  ABLMG_REQUIRE(o.maxPasses >= 0, "improve options: maxPasses must be >= 0, got " << o.maxPasses);
  ABLMG_REQUIRE(o.swapMargin >= 0 && std::isfinite(o.swapMargin),
                "improve options: swapMargin must be >= 0, got " << o.swapMargin);
  ABLMG_REQUIRE(o.collapseMargin >= 0 && std::isfinite(o.collapseMargin),
                "improve options: collapseMargin must be >= 0, got " << o.collapseMargin);
  ABLMG_REQUIRE(o.moveMargin >= 0 && std::isfinite(o.moveMargin),
                "improve options: moveMargin must be >= 0, got " << o.moveMargin);
}

ImproveStats improveQuality(Mesh2& mesh, std::vector<Metric2>& metrics, const MetricField& field,
                            const ImproveOptions& options) {
  const Stopwatch watch;
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
    const std::vector<double> q = improver.compact();
    stats.badAfter = long(std::count_if(q.begin(), q.end(), [&](double x) { return x < options.qThreshold; }));
    stats.qMinAfter = minOf(q);
  }
  stats.seconds = watch.seconds();
  return stats;
}

}  // namespace ablmg::mesher
