#include "ablmg/core/domain.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace ablmg {
namespace {

double loopSignedArea(const BoundaryLoop& loop) {
  // The shoelace sum about the origin cancels catastrophically far from it (a unit square at
  // x = 10⁹: products of 10¹⁸, area 0); the sum about the loop's first point does not. The
  // latter is taken only where the two differ beyond round-off, so that domains near the
  // origin keep their bits (and their meshes).
  double a = 0, b = 0;
  const std::size_t n = loop.points.size();
  if (n == 0) return 0;
  const Vec2 o = loop.points[0];
  for (std::size_t k = 0; k < n; ++k) {
    a += cross(loop.points[k], loop.points[(k + 1) % n]);
    b += cross(loop.points[k] - o, loop.points[(k + 1) % n] - o);
  }
  return 0.5 * (std::abs(a - b) > 1e-9 * std::abs(b) ? b : a);
}

void reverseLoop(BoundaryLoop& loop) {
  // segment k (p_k → p_{k+1}) becomes segment n−2−k of the reversed loop (p_{k+1} → p_k)
  const std::size_t n = loop.points.size();
  std::vector<Vec2> pts(n);
  std::vector<int> tags(n);
  for (std::size_t k = 0; k < n; ++k) {
    pts[k] = loop.points[(n - k) % n];         // p0, p_{n−1}, ..., p1
    tags[k] = loop.tags[(2 * n - k - 1) % n];  // segment (p_{n−k} → p_{n−k−1}) was tag[n−k−1]
  }
  loop.points = std::move(pts);
  loop.tags = std::move(tags);
  if (!loop.fixedPoints.empty()) {
    std::vector<char> f(n);
    for (std::size_t k = 0; k < n; ++k) f[k] = loop.fixedPoints[(n - k) % n];
    loop.fixedPoints = std::move(f);
  }
  if (!loop.keptSegments.empty()) {
    std::vector<char> f(n);
    for (std::size_t k = 0; k < n; ++k) f[k] = loop.keptSegments[(2 * n - k - 1) % n];
    loop.keptSegments = std::move(f);
  }
}

const char* loopName(std::size_t l) { return l == 0 ? "outer loop" : "hole"; }

/// The points that loop visits more than once (the ends and inner points of its slits), sorted.
std::vector<Vec2> repeatedPoints(const BoundaryLoop& loop) {
  std::vector<Vec2> pts = loop.points, out;
  const auto less = [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); };
  std::sort(pts.begin(), pts.end(), less);
  for (std::size_t k = 1; k < pts.size(); ++k)
    if (pts[k] == pts[k - 1] && (out.empty() || out.back() != pts[k])) out.push_back(pts[k]);
  return out;
}

bool isRepeated(const std::vector<Vec2>& repeated, const Vec2& p) {
  return std::binary_search(repeated.begin(), repeated.end(), p, [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
}

}  // namespace

Domain::Domain(BoundaryLoop outer, std::vector<BoundaryLoop> holes) {
  loops_.push_back(std::move(outer));
  for (auto& h : holes) loops_.push_back(std::move(h));
  for (std::size_t l = 0; l < loops_.size(); ++l) {
    auto& loop = loops_[l];
    ABLMG_REQUIRE(loop.points.size() >= 3, "domain: " << loopName(l) << " " << l << " has " << loop.points.size()
                                                      << " points (need at least 3)");
    if (loop.tags.empty()) loop.tags.assign(loop.points.size(), 1);
    ABLMG_REQUIRE(loop.tags.size() == loop.points.size(), "domain: loop " << l << " has " << loop.points.size()
                                                                          << " points but " << loop.tags.size()
                                                                          << " segment tags");
    ABLMG_REQUIRE(loop.fixedPoints.empty() || loop.fixedPoints.size() == loop.points.size(),
                  "domain: loop " << l << " has " << loop.points.size() << " points but " << loop.fixedPoints.size()
                                  << " fixedPoints flags");
    ABLMG_REQUIRE(loop.keptSegments.empty() || loop.keptSegments.size() == loop.points.size(),
                  "domain: loop " << l << " has " << loop.points.size() << " segments but " << loop.keptSegments.size()
                                  << " keptSegments flags");
    for (std::size_t k = 0; k < loop.points.size(); ++k)
      ABLMG_REQUIRE(std::isfinite(loop.points[k].x()) && std::isfinite(loop.points[k].y()),
                    "domain: loop " << l << " point " << k << " has a non-finite coordinate");
    const double a = loopSignedArea(loop);
    const bool wantCcw = (l == 0);
    if ((a > 0) != wantCcw && a != 0) reverseLoop(loop);
  }
  validate();
}

Domain Domain::rectangle(double x0, double y0, double x1, double y1) {
  ABLMG_REQUIRE(
      std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1) && x1 > x0 && y1 > y0,
      "domain: rectangle needs finite x0 < x1 and y0 < y1 (got " << x0 << "," << y0 << "," << x1 << "," << y1 << ")");
  BoundaryLoop loop;
  loop.points = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  loop.tags = {1, 2, 3, 4};
  return Domain(std::move(loop));
}

Domain Domain::disk(Vec2 centre, double radius, int samples) {
  ABLMG_REQUIRE(std::isfinite(radius) && radius > 0, "domain: disk radius must be positive (got " << radius << ")");
  ABLMG_REQUIRE(samples >= 8 && samples <= 10000000,
                "domain: disk samples must be in [8, 1e7] (got " << samples << ")");
  BoundaryLoop loop;
  loop.smooth = true;
  for (int k = 0; k < samples; ++k) {
    const double t = 2 * std::numbers::pi * k / samples;
    loop.points.emplace_back(centre.x() + radius * std::cos(t), centre.y() + radius * std::sin(t));
  }
  loop.tags.assign(samples, 1);
  return Domain(std::move(loop));
}

double Domain::area() const {
  double a = 0;
  for (const auto& loop : loops_) a += loopSignedArea(loop);  // holes are clockwise: negative
  return a;
}

std::pair<Vec2, Vec2> Domain::boundingBox() const {
  Vec2 lo = outer().points[0], hi = lo;
  for (const auto& p : outer().points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

bool Domain::contains(const Vec2& p) const {
  // Winding number by upward/downward crossings of the ray from p towards +x; exact tests.
  int winding = 0;
  for (const auto& loop : loops_) {
    const std::size_t n = loop.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = loop.points[k];
      const Vec2& b = loop.points[(k + 1) % n];
      if (std::max(a.x(), b.x()) < p.x()) continue;
      const bool up = a.y() <= p.y() && p.y() < b.y();
      const bool down = b.y() <= p.y() && p.y() < a.y();
      if (!up && !down) {
        if (a.y() == p.y() && b.y() == p.y() && std::min(a.x(), b.x()) <= p.x())
          return true;  // on a horizontal segment
        continue;
      }
      const int o = orient2d(a, b, p);
      if (o == 0) return true;  // on the boundary
      if (up && o > 0) ++winding;
      if (down && o < 0) --winding;
    }
  }
  return winding != 0;
}

double Domain::distanceToBoundary(const Vec2& p) const {
  double best = INFINITY;
  for (const auto& loop : loops_) {
    const std::size_t n = loop.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = loop.points[k];
      const Vec2 ab = loop.points[(k + 1) % n] - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * ab - p).norm());
    }
  }
  return best;
}

std::vector<int> Domain::corners(int l) const {
  const BoundaryLoop& loop = loops_.at(l);
  const int n = static_cast<int>(loop.points.size());
  std::vector<int> out;
  for (int k = 0; k < n; ++k) {
    if (!loop.smooth) {
      out.push_back(k);
      continue;
    }
    const Vec2 din = loop.points[k] - loop.points[(k + n - 1) % n];
    const Vec2 dout = loop.points[(k + 1) % n] - loop.points[k];
    const double turn = std::atan2(std::abs(cross(din, dout)), din.dot(dout));
    const bool tagChange = loop.tags[k] != loop.tags[(k + n - 1) % n];
    const bool fixed = (!loop.fixedPoints.empty() && loop.fixedPoints[k]) ||
                       (!loop.keptSegments.empty() && (loop.keptSegments[k] || loop.keptSegments[(k + n - 1) % n]));
    if (tagChange || fixed || turn > std::numbers::pi / 6) out.push_back(k);
  }
  return out;
}

bool Domain::hasSlits() const {
  return std::any_of(loops_.begin(), loops_.end(), [](const BoundaryLoop& l) { return !repeatedPoints(l).empty(); });
}

Domain Domain::withSlit(const std::vector<Vec2>& pts, int tagLeft, int tagRight) const {
  ABLMG_REQUIRE(pts.size() >= 2, "domain: a slit needs at least 2 points (got " << pts.size() << ")");
  for (std::size_t k = 0; k < pts.size(); ++k) {
    ABLMG_REQUIRE(std::isfinite(pts[k].x()) && std::isfinite(pts[k].y()),
                  "domain: slit point " << k << " has a non-finite coordinate");
    ABLMG_REQUIRE(k == 0 || pts[k] != pts[k - 1], "domain: slit point " << k << " repeats point " << k - 1);
  }
  const auto where = [&](std::size_t k) {
    std::ostringstream os;
    os << "domain: slit point " << k << " (" << pts[k].x() << ", " << pts[k].y() << ")";
    return os.str();
  };
  for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    ABLMG_REQUIRE(contains(0.5 * (pts[k] + pts[k + 1])), where(k) << ": the slit leaves the domain after this point");
  // Where points[0] lies on a loop: a point of it, or inside one of its segments.
  int al = -1, ak = -1;
  bool onPoint = false;
  for (std::size_t l = 0; l < loops_.size() && al < 0; ++l) {
    const auto& p = loops_[l].points;
    for (std::size_t k = 0; k < p.size() && al < 0; ++k) {
      const Vec2 &a = p[k], &b = p[(k + 1) % p.size()];
      onPoint = a == pts[0];
      if (onPoint || (orient2d(a, b, pts[0]) == 0 && (pts[0] - a).dot(b - a) > 0 && (pts[0] - b).dot(a - b) > 0)) {
        al = int(l);
        ak = int(k);
      }
    }
  }
  std::vector<BoundaryLoop> loops = loops_;
  const std::size_t n = pts.size();
  if (al < 0) {  // free: a hole along the slit and back (a midpoint if it has one segment)
    std::vector<Vec2> q = pts;
    if (n == 2) q.insert(q.begin() + 1, 0.5 * (pts[0] + pts[1]));
    BoundaryLoop hole;
    hole.points = q;
    hole.tags.assign(q.size() - 1, tagLeft);
    hole.tags.push_back(tagRight);  // from the end back
    for (std::size_t k = q.size() - 2; k >= 1; --k) {
      hole.points.push_back(q[k]);
      hole.tags.push_back(tagRight);
    }
    loops.push_back(std::move(hole));
  } else {
    BoundaryLoop& loop = loops[std::size_t(al)];
    const std::size_t m = loop.points.size(), k = std::size_t(ak);
    if (loop.fixedPoints.empty()) loop.fixedPoints.assign(m, 0);
    if (loop.keptSegments.empty()) loop.keptSegments.assign(m, 0);
    BoundaryLoop out;
    out.smooth = loop.smooth;
    const auto add = [&](const Vec2& p, int tag, char fixed, char kept) {
      out.points.push_back(p);
      out.tags.push_back(tag);
      out.fixedPoints.push_back(fixed);
      out.keptSegments.push_back(kept);
    };
    for (std::size_t i = 0; i <= k; ++i)
      add(loop.points[i], i == k && onPoint ? tagLeft : loop.tags[i], loop.fixedPoints[i],
          i == k ? 0 : loop.keptSegments[i]);
    if (!onPoint) add(pts[0], tagLeft, 1, 0);
    for (std::size_t i = 1; i < n; ++i) add(pts[i], i + 1 < n ? tagLeft : tagRight, 0, 0);
    for (std::size_t i = n - 2; i >= 1; --i) add(pts[i], tagRight, 0, 0);
    add(pts[0], loop.tags[k], 1, 0);
    for (std::size_t i = k + 1; i < m; ++i)
      add(loop.points[i], loop.tags[i], loop.fixedPoints[i], loop.keptSegments[i]);
    if (onPoint) out.fixedPoints[k] = 1;
    loop = std::move(out);
  }
  BoundaryLoop outer = std::move(loops.front());
  loops.erase(loops.begin());
  try {
    return Domain(std::move(outer), std::move(loops));
  } catch (const InputError& e) { throw InputError(where(n - 1) + " (the tip): " + e.what()); }
}

namespace {

/// A boundary segment a → b, segment `index` of loop `loop`, with its bounding box.
struct Segment {
  Vec2 a, b, lo, hi;
  int loop, index;
};

/// The pairs of segments whose bounding boxes overlap (closed boxes: touching counts), each once,
/// as (i, j) with i < j, through a uniform grid of about one cell per segment over the segments'
/// bounding box: the pair is visited in the lowest cell both boxes cover. Expected O(n) for a
/// boundary whose segments are short against the domain; a sweep in one coordinate is O(n²)
/// on a boundary with many segments on one vertical side.
template <class Visit>
void forOverlappingPairs(const std::vector<Segment>& segs, Visit visit) {
  const std::size_t n = segs.size();
  if (n < 2) return;
  Vec2 lo = segs[0].lo, hi = segs[0].hi;
  for (const Segment& s : segs) {
    lo = lo.cwiseMin(s.lo);
    hi = hi.cwiseMax(s.hi);
  }
  // Fewer cells when long segments would cover too many of them (memory stays O(n)).
  for (int g = std::clamp(int(std::ceil(std::sqrt(double(n)))), 1, 2048);; g = std::max(1, g / 2)) {
    // A cell size that underflows (a subnormal extent) or overflows gives one column or row; the
    // cell index is clamped as a double, so no NaN or out-of-range value is converted to int.
    const auto cellSize = [&](double extent) {
      const double size = extent / g;
      return size > 0 && std::isfinite(size) ? size : std::numeric_limits<double>::infinity();
    };
    const double w = cellSize(hi.x() - lo.x()), h = cellSize(hi.y() - lo.y());
    const auto cell = [&](double v, double origin, double size) {
      const double t = std::floor((v - origin) / size);
      return t >= 1 ? int(std::min(t, double(g - 1))) : 0;  // NaN (an overflowed v − origin over an infinite size) → 0
    };
    std::vector<std::array<int, 4>> range(n);  // cx0, cy0, cx1, cy1
    std::size_t entries = 0;
    for (std::size_t i = 0; i < n; ++i) {
      range[i] = {cell(segs[i].lo.x(), lo.x(), w), cell(segs[i].lo.y(), lo.y(), h), cell(segs[i].hi.x(), lo.x(), w),
                  cell(segs[i].hi.y(), lo.y(), h)};
      entries += std::size_t(range[i][2] - range[i][0] + 1) * std::size_t(range[i][3] - range[i][1] + 1);
    }
    if (entries > 64 * n && g > 1) continue;
    std::vector<std::size_t> start(std::size_t(g) * std::size_t(g) + 1, 0);
    for (const auto& r : range)
      for (int cy = r[1]; cy <= r[3]; ++cy)
        for (int cx = r[0]; cx <= r[2]; ++cx) ++start[std::size_t(cy) * g + cx + 1];
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<int> members(entries);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)  // in index order, so each cell's list is sorted
      for (int cy = range[i][1]; cy <= range[i][3]; ++cy)
        for (int cx = range[i][0]; cx <= range[i][2]; ++cx) members[fill[std::size_t(cy) * g + cx]++] = int(i);
    for (int cy = 0; cy < g; ++cy)
      for (int cx = 0; cx < g; ++cx) {
        const std::size_t c = std::size_t(cy) * g + cx;
        for (std::size_t p = start[c]; p < start[c + 1]; ++p)
          for (std::size_t q = p + 1; q < start[c + 1]; ++q) {
            const int i = members[p], j = members[q];
            const auto &ri = range[std::size_t(i)], &rj = range[std::size_t(j)];
            if (segs[std::size_t(i)].hi.x() < segs[std::size_t(j)].lo.x() ||
                segs[std::size_t(j)].hi.x() < segs[std::size_t(i)].lo.x() ||
                segs[std::size_t(i)].hi.y() < segs[std::size_t(j)].lo.y() ||
                segs[std::size_t(j)].hi.y() < segs[std::size_t(i)].lo.y())
              continue;
            if (std::max(ri[0], rj[0]) != cx || std::max(ri[1], rj[1]) != cy) continue;  // seen in another cell
            visit(i, j);
          }
      }
    return;
  }
}

}  // namespace

void Domain::validate() const {
  std::vector<Segment> segs;
  for (std::size_t l = 0; l < loops_.size(); ++l) {
    const auto& pts = loops_[l].points;
    const std::size_t n = pts.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = pts[k];
      const Vec2& b = pts[(k + 1) % n];
      ABLMG_REQUIRE(a != b, "domain: " << loopName(l) << " " << l << " segment " << k << " has zero length (point ("
                                       << a.x() << ", " << a.y() << ") repeated)");
      segs.push_back({a, b, a.cwiseMin(b), a.cwiseMax(b), int(l), int(k)});
    }
  }
  std::vector<std::vector<Vec2>> repeated(loops_.size());
  for (std::size_t l = 0; l < loops_.size(); ++l) repeated[l] = repeatedPoints(loops_[l]);
  // Segments are numbered loop by loop, so the first bad pair in (i, j) order is the same whatever
  // order the pairs are visited in: it is the one reported.
  std::pair<int, int> firstBad{-1, -1};
  forOverlappingPairs(segs, [&](int i, int j) {
    if (firstBad.first >= 0 && std::pair(i, j) >= firstBad) return;
    const Segment &s = segs[std::size_t(i)], &t = segs[std::size_t(j)];
    const int n = int(loops_[std::size_t(s.loop)].points.size());
    const bool neighbours = s.loop == t.loop && ((s.index + 1) % n == t.index || (t.index + 1) % n == s.index);
    const auto& rep = repeated[std::size_t(s.loop)];
    const bool gapPair = s.loop == t.loop && s.a == t.b && s.b == t.a;  // the two lips of a slit
    const bool meetAtRepeated =
        s.loop == t.loop && !rep.empty() &&
        ((isRepeated(rep, s.a) && (s.a == t.a || s.a == t.b)) || (isRepeated(rep, s.b) && (s.b == t.a || s.b == t.b)));
    bool bad;
    if (gapPair) {
      bad = false;
    } else if (neighbours || meetAtRepeated) {
      // consecutive segments share one point; they must not fold back onto each other
      bad = segmentsCross(s.a, s.b, t.a, t.b);
    } else {
      bad = segmentsIntersect(s.a, s.b, t.a, t.b);
    }
    if (bad) firstBad = {i, j};
  });
  if (firstBad.first >= 0) {
    const Segment &s = segs[std::size_t(firstBad.first)], &t = segs[std::size_t(firstBad.second)];
    ABLMG_REQUIRE(false, "domain: " << loopName(std::size_t(s.loop)) << " " << s.loop << " segment " << s.index
                                    << " intersects " << loopName(std::size_t(t.loop)) << " " << t.loop << " segment "
                                    << t.index << " (self-intersecting or touching boundary)");
  }
  // Holes must lie inside the outer loop (no crossings, so testing one point suffices).
  const Domain outerOnly = [&] {
    Domain d;
    d.loops_ = {loops_[0]};
    return d;
  }();
  for (std::size_t l = 1; l < loops_.size(); ++l)
    ABLMG_REQUIRE(outerOnly.contains(loops_[l].points[0]), "domain: hole " << l << " lies outside the outer loop");
  ABLMG_REQUIRE(area() > 0, "domain: enclosed area is not positive (" << area() << ")");
}

}  // namespace ablmg
