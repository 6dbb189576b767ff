#include "ablmg/mesher/slit_domain.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>

#include <omp.h>

namespace ablmg::mesher {
namespace {

/// A loop point and the segment that leaves it.
struct Pt {
  Vec2 p;
  int tag = 1;
  char fixed = 0, kept = 0;
};
struct Loop {
  std::vector<Pt> pts;
  bool smooth = false;
};
using Piece = std::vector<Loop>;  ///< [0] the outer loop, then holes

Loop fromBoundaryLoop(const BoundaryLoop& b) {
  Loop l;
  l.smooth = b.smooth;
  for (std::size_t k = 0; k < b.points.size(); ++k)
    l.pts.push_back({b.points[k], b.tags[k], char(b.fixedPoints.empty() ? 0 : b.fixedPoints[k]),
                     char(b.keptSegments.empty() ? 0 : b.keptSegments[k])});
  return l;
}

BoundaryLoop toBoundaryLoop(const Loop& l) {
  BoundaryLoop b;
  b.smooth = l.smooth;
  for (const Pt& p : l.pts) {
    b.points.push_back(p.p);
    b.tags.push_back(p.tag);
    b.fixedPoints.push_back(p.fixed);
    b.keptSegments.push_back(p.kept);
  }
  return b;
}

double signedArea(const Loop& l) {
  if (l.pts.empty()) return 0;
  const Vec2 o = l.pts[0].p;  // about a loop point: exact sign far from the origin
  double a = 0;
  for (std::size_t k = 0; k < l.pts.size(); ++k) a += cross(l.pts[k].p - o, l.pts[(k + 1) % l.pts.size()].p - o);
  return 0.5 * a;
}

/// Winding number of `l` around q (q on no segment of l).
bool insideLoop(const Loop& l, const Vec2& q) {
  int w = 0;
  for (std::size_t k = 0; k < l.pts.size(); ++k) {
    const Vec2 &a = l.pts[k].p, &b = l.pts[(k + 1) % l.pts.size()].p;
    if (a.y() <= q.y() && q.y() < b.y() && orient2d(a, b, q) > 0) ++w;
    if (b.y() <= q.y() && q.y() < a.y() && orient2d(a, b, q) < 0) --w;
  }
  return w != 0;
}

/// A slit tip of the piece: a point whose two neighbours coincide. {-1, -1} if none.
std::pair<int, int> findTip(const Piece& piece) {
  for (std::size_t l = 0; l < piece.size(); ++l) {
    const auto& p = piece[l].pts;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n && n >= 3; ++i)
      if (p[(i + n - 1) % n].p == p[(i + 1) % n].p) return {int(l), int(i)};
  }
  return {-1, -1};
}

/// Where the ray from the tip (loop l, point i) straight ahead first meets a loop: {loop,
/// segment, point}. Throws InputError if it meets none.
struct Hit {
  int loop = -1, segment = -1;
  double u = 0;  ///< along the segment, snapped to 0 / 1 near its ends
  Vec2 at = Vec2::Zero();
};
Hit castRay(const Piece& piece, int l, int i) {
  const auto& lp = piece[std::size_t(l)].pts;
  const std::size_t n = lp.size();
  const Vec2 t = lp[std::size_t(i)].p, d = t - lp[(std::size_t(i) + 1) % n].p;
  Hit best;
  double bestS = INFINITY;
  for (std::size_t m = 0; m < piece.size(); ++m) {
    const auto& p = piece[m].pts;
    for (std::size_t j = 0; j < p.size(); ++j) {
      const Vec2 &a = p[j].p, &b = p[(j + 1) % p.size()].p;
      if (a == t || b == t) continue;  // the tip's own segments
      // Only a segment whose domain side (its left) faces the tip: of the two lips of another
      // slit, or the two visits of a point of it, the one the cut arrives at.
      if (orient2d(a, b, t) <= 0) continue;
      const double denom = cross(d, b - a);
      if (std::abs(denom) <= 1e-14 * d.norm() * (b - a).norm()) continue;  // parallel
      const double s = cross(a - t, b - a) / denom, u = cross(a - t, d) / denom;
      if (s <= 1e-12 || u < -1e-12 || u > 1 + 1e-12 || s >= bestS) continue;
      bestS = s;
      best = {int(m), int(j), u < 1e-9 ? 0.0 : u > 1 - 1e-9 ? 1.0 : u, Vec2::Zero()};
    }
  }
  ABLMG_REQUIRE(best.loop >= 0, "domain: the slit tip at ("
                                    << t.x() << ", " << t.y()
                                    << ") points out of the domain (its extension meets no loop)");
  const auto& p = piece[std::size_t(best.loop)].pts;
  const Vec2 &a = p[std::size_t(best.segment)].p, &b = p[(std::size_t(best.segment) + 1) % p.size()].p;
  best.at = best.u == 0 ? a : best.u == 1 ? b : Vec2(a + best.u * (b - a));
  return best;
}

/// Points along the straight cut a → b at equal metric arc length, round(metric length) ≥ 1
/// pieces, ends included (exactly a and b).
std::vector<Vec2> discretizeCut(const Vec2& a, const Vec2& b, const MetricField& metric) {
  Metric2 m[2];
  const Vec2 ab[2] = {a, b};
  metric.evaluate(ab, m);
  const int k = std::clamp(int(std::ceil(8 * edgeLength(a, m[0], b, m[1]))), 8, 1 << 16);
  std::vector<Vec2> sub;
  for (int j = 0; j <= k; ++j) sub.push_back(a + (double(j) / k) * (b - a));
  std::vector<Metric2> sm(sub.size());
  metric.evaluate(sub, sm);
  std::vector<double> s(sub.size(), 0.0);
  for (std::size_t j = 1; j < sub.size(); ++j) s[j] = s[j - 1] + edgeLength(sub[j - 1], sm[j - 1], sub[j], sm[j]);
  const int n = std::max(1, int(std::lround(s.back())));
  std::vector<Vec2> out{a};
  for (int i = 1; i < n; ++i) {
    const double target = s.back() * i / n;
    const std::size_t j = std::size_t(std::upper_bound(s.begin(), s.end(), target) - s.begin());
    const double f = (target - s[j - 1]) / std::max(s[j] - s[j - 1], 1e-300);
    out.push_back(sub[j - 1] + f * (sub[j] - sub[j - 1]));
  }
  out.push_back(b);
  return out;
}

/// The loop's points from index `from` on, cyclically, `count` of them.
void appendCyclic(std::vector<Pt>& out, const std::vector<Pt>& p, std::size_t from, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k) out.push_back(p[(from + k) % p.size()]);
}

/// The cut's points strictly between its ends, as fixed points starting kept cut segments.
void appendCut(std::vector<Pt>& out, const std::vector<Vec2>& cut, bool reversed) {
  for (std::size_t k = 1; k + 1 < cut.size(); ++k)
    out.push_back({cut[reversed ? cut.size() - 1 - k : k], kSlitCutTag, 1, 1});
}

/// One cut: from the tip (loop l, point i) to the hit; the piece is split (same loop) or its two
/// loops joined. New pieces are appended to `pieces`.
void cutOnce(std::vector<Piece>& pieces, std::size_t pi, int l, int i, const MetricField& metric,
             std::vector<std::vector<Vec2>>& cuts) {
  Hit hit = castRay(pieces[pi], l, i);
  Piece& piece = pieces[pi];
  auto& hl = piece[std::size_t(hit.loop)].pts;
  std::size_t h = std::size_t(hit.segment);
  if (hit.u == 1) h = (h + 1) % hl.size();
  if (hit.u > 0 && hit.u < 1) {  // a new point inside the segment
    hl[h].kept = 0;
    hl.insert(hl.begin() + std::ptrdiff_t(h) + 1, Pt{hit.at, hl[h].tag, 1, 0});
    if (hit.loop == l && std::size_t(i) > h) ++i;
    ++h;
  }
  hl[h].fixed = 1;
  auto& tl = piece[std::size_t(l)].pts;
  tl[std::size_t(i)].fixed = 1;
  const std::vector<Vec2> cut = discretizeCut(tl[std::size_t(i)].p, hl[h].p, metric);
  cuts.push_back(cut);
  const std::size_t ti = std::size_t(i), n = tl.size();
  if (hit.loop == l) {  // split: tip → ... → hit → cut back, and hit → ... → tip → cut
    Loop a{{}, piece[std::size_t(l)].smooth}, b{{}, a.smooth};
    appendCyclic(a.pts, tl, ti, (h + n - ti) % n + 1);
    a.pts.back().tag = kSlitCutTag;
    a.pts.back().kept = 1;
    appendCut(a.pts, cut, true);
    appendCyclic(b.pts, tl, h, (ti + n - h) % n + 1);
    b.pts.back().tag = kSlitCutTag;
    b.pts.back().kept = 1;
    appendCut(b.pts, cut, false);
    Piece rest;  // the holes other than loop l
    for (std::size_t k = 1; k < piece.size(); ++k)
      if (k != std::size_t(l)) rest.push_back(std::move(piece[k]));
    std::vector<Loop> outers, holes;
    for (Loop* x : {&a, &b}) (signedArea(*x) > 0 ? outers : holes).push_back(std::move(*x));
    if (l != 0) holes.insert(holes.begin(), std::move(piece[0]));  // a hole was split: the outer stays
    std::vector<Piece> made;
    if (l != 0) made.push_back({std::move(holes[0])});
    for (auto& o : outers) made.push_back({std::move(o)});
    for (std::size_t k = 1; k < holes.size(); ++k) made.front().push_back(std::move(holes[k]));
    for (auto& hole : rest) {  // to the innermost new outer that contains it
      std::size_t to = 0;
      for (std::size_t k = made.size(); k-- > 0;)
        if (insideLoop(made[k][0], hole.pts[0].p)) {
          to = k;
          break;
        }
      made[to].push_back(std::move(hole));
    }
    pieces[pi] = std::move(made[0]);
    for (std::size_t k = 1; k < made.size(); ++k) pieces.push_back(std::move(made[k]));
    return;
  }
  // join: all of loop l from the tip, the cut, all of the hit loop from the hit, the cut back
  Loop& other = piece[std::size_t(hit.loop)];
  Loop& own = piece[std::size_t(l)];
  for (Loop* x : {&own, &other})
    if (!x->smooth && (own.smooth || other.smooth))
      for (Pt& p : x->pts) p.fixed = 1;
  Loop joined{{}, own.smooth || other.smooth};
  appendCyclic(joined.pts, tl, ti, n);
  joined.pts.push_back({tl[ti].p, kSlitCutTag, 1, 1});
  appendCut(joined.pts, cut, false);
  appendCyclic(joined.pts, hl, h, hl.size());
  joined.pts.push_back({hl[h].p, kSlitCutTag, 1, 1});
  appendCut(joined.pts, cut, true);
  const std::size_t keep = std::min(std::size_t(l), std::size_t(hit.loop)),
                    drop = std::max(std::size_t(l), std::size_t(hit.loop));
  piece[keep] = std::move(joined);
  piece.erase(piece.begin() + std::ptrdiff_t(drop));
}

}  // namespace

SlitPieces cutAtSlits(const Domain& domain, const MetricField& metric) {
  std::vector<Piece> pieces(1);
  for (const auto& b : domain.loops()) pieces[0].push_back(fromBoundaryLoop(b));
  SlitPieces out;
  for (std::size_t pi = 0; pi < pieces.size(); ++pi)
    for (int guard = 0;; ++guard) {
      const auto [l, i] = findTip(pieces[pi]);
      if (l < 0) break;
      ABLMG_REQUIRE(guard < 100000, "domain: too many slit tips");
      cutOnce(pieces, pi, l, i, metric, out.cuts);
    }
  for (const Piece& piece : pieces) {
    BoundaryLoop outer = toBoundaryLoop(piece[0]);
    std::vector<BoundaryLoop> holes;
    for (std::size_t k = 1; k < piece.size(); ++k) holes.push_back(toBoundaryLoop(piece[k]));
    Domain d;
    try {
      d = Domain(std::move(outer), std::move(holes));
    } catch (const InputError& e) {
      throw InputError(std::string("domain: cutting at the slits left an invalid piece: ") + e.what());
    }
    ABLMG_REQUIRE(!d.hasSlits(),
                  "domain: a slit cannot be cut into simple pieces (a slit attached to a hole whose "
                  "extension meets another loop is not supported)");
    out.pieces.push_back(std::move(d));
  }
  return out;
}

namespace {
using PointKey = std::pair<std::uint64_t, std::uint64_t>;
PointKey keyOf(const Vec2& p) { return {std::bit_cast<std::uint64_t>(p.x()), std::bit_cast<std::uint64_t>(p.y())}; }

/// A piece's share of the meshing work: ∫ √det M over it (its node count, up to a constant),
/// sampled at the centres of a kSamples² grid on its bounding box. Coarse, but it only decides
/// how the pieces are scheduled, never what they become.
double pieceWeight(const Domain& piece, const MetricField& metric) {
  constexpr int kSamples = 32;
  const auto [lo, hi] = piece.boundingBox();
  const Vec2 d = (hi - lo) / kSamples;
  std::vector<Vec2> pts;
  for (int j = 0; j < kSamples; ++j)
    for (int i = 0; i < kSamples; ++i) {
      const Vec2 p = lo + Vec2((i + 0.5) * d.x(), (j + 0.5) * d.y());
      if (piece.contains(p)) pts.push_back(p);
    }
  std::vector<double> density(pts.size());
  metric.sqrtDeterminants(pts, density);
  double w = 0;
  for (const double x : density) w += x;
  return w * d.x() * d.y();
}

/// The pieces meshed with `options`, in order. With two threads or more (options' or OpenMP's), a thread-safe metric
/// and no piece holding more than kMaxShare of the work, the pieces are meshed concurrently, one
/// thread each (the mesher's own parallel regions then run on one thread: its output does not
/// depend on the thread count, so the meshes are the same bits as one after the other); most
/// of a piece's meshing runs on one thread anyway (the lattice below the banded growth's size,
/// the post-pass, the validation), so two pieces side by side take about half the wall time.
/// Progress is reported by the calling thread's pieces only. The first piece's error (in piece
/// order) is thrown, as the sequential loop would.
std::vector<MeshResult> meshPieces(const std::vector<Domain>& pieces, const MetricField& metric,
                                   const MeshOptions& options) {
  constexpr double kMaxShare = 0.65;  // beyond it one piece on one thread outlasts both on two
  const int n = int(pieces.size());
  std::vector<MeshResult> parts(pieces.size());
  const int asked = std::max(options.placement.threads, options.connect.threads);  // 0: OpenMP's default
  const int threads = std::min(n, asked > 0 ? asked : omp_get_max_threads());
  bool concurrent = threads >= 2 && !omp_in_parallel() && metric.isThreadSafe();
  if (concurrent) {
    std::vector<double> w(pieces.size());
    for (int k = 0; k < n; ++k) w[std::size_t(k)] = pieceWeight(pieces[std::size_t(k)], metric);
    double total = 0;
    for (const double x : w) total += x;
    concurrent = total > 0 && std::isfinite(total) && *std::max_element(w.begin(), w.end()) <= kMaxShare * total;
  }
  if (!concurrent) {
    for (int k = 0; k < n; ++k) parts[std::size_t(k)] = meshDomain(pieces[std::size_t(k)], metric, options);
    return parts;
  }
  MeshOptions quiet = options;
  quiet.progress = {};
  ParallelFailure failure;
  const int saved = omp_get_max_active_levels();
  omp_set_max_active_levels(1);  // the pieces' team active, the mesher's regions inside it not
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int k = 0; k < n; ++k)
    failure.run(k, [&] {
      parts[std::size_t(k)] = meshDomain(pieces[std::size_t(k)], metric, omp_get_thread_num() == 0 ? options : quiet);
    });
  omp_set_max_active_levels(saved);
  failure.rethrow();
  return parts;
}
}  // namespace

MeshResult meshSlitDomain(const Domain& domain, const MetricField& metric, const MeshOptions& options) {
  for (std::size_t l = 0; l < domain.loops().size(); ++l)
    for (int tag : domain.loops()[l].tags)
      ABLMG_REQUIRE(tag != kSlitCutTag, "domain: loop " << l << " has tag " << tag
                                                        << ", which is reserved (the cuts of a domain with slits)");
  const SlitPieces cut = cutAtSlits(domain, metric);
  std::map<PointKey, int> shared;  // cut points → output vertex (-1 until met)
  for (const auto& c : cut.cuts)
    for (const Vec2& p : c) shared.emplace(keyOf(p), -1);
  MeshResult out;
  Mesh2& m = out.mesh;
  std::map<std::pair<int, int>, int> cutEdges;  // undirected cut edge → times met
  std::vector<MeshResult> parts = meshPieces(cut.pieces, metric, options);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    MeshResult& part = parts[k];
    std::vector<char> onBoundary(std::size_t(part.mesh.numVertices()), 0);
    for (const auto& e : part.mesh.boundaryEdges) onBoundary[std::size_t(e.a)] = onBoundary[std::size_t(e.b)] = 1;
    std::vector<int> id(std::size_t(part.mesh.numVertices()));
    for (std::size_t v = 0; v < id.size(); ++v) {
      const auto it = onBoundary[v] ? shared.find(keyOf(part.mesh.vertices[v])) : shared.end();
      if (it != shared.end() && it->second >= 0) {
        id[v] = it->second;
        continue;
      }
      id[v] = m.numVertices();
      if (it != shared.end()) it->second = id[v];
      m.vertices.push_back(part.mesh.vertices[v]);
      out.metric.push_back(part.metric[v]);
    }
    for (std::size_t t = 0; t < part.mesh.triangles.size(); ++t) {
      const auto& tri = part.mesh.triangles[t];
      m.triangles.push_back({id[std::size_t(tri[0])], id[std::size_t(tri[1])], id[std::size_t(tri[2])]});
      if (!part.mesh.triangleRefs.empty()) m.triangleRefs.push_back(part.mesh.triangleRefs[t]);
    }
    for (const auto& e : part.mesh.boundaryEdges) {
      const BoundaryEdge g{id[std::size_t(e.a)], id[std::size_t(e.b)], e.ref};
      if (g.ref == kSlitCutTag)
        ++cutEdges[{std::min(g.a, g.b), std::max(g.a, g.b)}];
      else
        m.boundaryEdges.push_back(g);
    }
    if (k == 0)
      out.stats = part.stats;
    else
      addPartStats(out.stats, part.stats);
  }
  for (const auto& [e, times] : cutEdges)
    ABLMG_REQUIRE(times == 2, "meshDomain: a slit cut edge was meshed on " << times << " side(s), not 2");
  if (m.triangleRefs.size() != m.triangles.size()) m.triangleRefs.clear();
  bool anySmooth = false;
  for (const auto& loop : domain.loops()) anySmooth = anySmooth || loop.smooth;
  double area = domain.area();
  if (anySmooth) {
    area = 0;
    const Vec2 o = m.boundaryEdges.empty() ? Vec2(0, 0) : m.vertices[std::size_t(m.boundaryEdges[0].a)];
    for (const auto& e : m.boundaryEdges)
      area += 0.5 * cross(m.vertices[std::size_t(e.a)] - o, m.vertices[std::size_t(e.b)] - o);
  }
  m.requireValid("meshDomain (slits glued)", area, 1e-9);
  return out;
}

}  // namespace ablmg::mesher
