#include "ablmg/io/poly.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/text_scanner.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

namespace ablmg::io {
namespace {

struct Segment {
  int a, b, tag, line;
};

double signedArea(const std::vector<Vec2>& p) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) s += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * s;
}

/// Even-odd ray casting; hole points are meant to be well inside their hole.
bool insidePolygon(const std::vector<Vec2>& p, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y() > q.y()) != (p[j].y() > q.y())) {
      const double x = p[j].x() + (q.y() - p[j].y()) * (p[i].x() - p[j].x()) / (p[i].y() - p[j].y());
      if (q.x() < x) in = !in;
    }
  }
  return in;
}

}  // namespace

Domain parsePoly(const std::string& text, const std::string& name) {
  TextScanner s(text, name);
  ABLMG_REQUIRE(!s.atEnd(), name << ":1: empty file, expected the vertex count of a .poly");
  const long nv = s.nextInt("vertex count", 0, INT_MAX - 1);
  ABLMG_REQUIRE(nv > 0, s.where() << "0 vertices (vertices in a separate .node file are not supported)");
  s.nextInt("dimension", 2, 2);
  const long nattr = s.nextInt("number of vertex attributes", 0, 1000);
  const long nvmark = s.nextInt("number of vertex markers (0 or 1)", 0, 1);
  ABLMG_REQUIRE(nv <= long(s.size() / 6 + 1),
                s.where() << "vertex count " << nv << " is more than the file can hold (truncated?)");
  std::vector<Vec2> pts;
  pts.reserve(nv);
  long base = 0;
  for (long i = 0; i < nv; ++i) {
    const long id = s.nextInt("vertex number", LONG_MIN, LONG_MAX);
    if (i == 0) {
      ABLMG_REQUIRE(id == 0 || id == 1, s.where() << "first vertex number is " << id << ", expected 0 or 1");
      base = id;
    }
    ABLMG_REQUIRE(id == base + i, s.where() << "vertex number " << id << ", expected " << base + i);
    const double x = s.nextDouble("vertex x coordinate"), y = s.nextDouble("vertex y coordinate");
    for (long k = 0; k < nattr; ++k) s.nextDouble("vertex attribute");
    if (nvmark) s.nextInt("vertex marker", INT_MIN, INT_MAX);
    pts.emplace_back(x, y);
  }
  const long ns = s.nextInt("segment count", 0, INT_MAX - 1);
  ABLMG_REQUIRE(ns >= 3, s.where() << ns << " segments: a domain needs a closed loop of at least 3");
  ABLMG_REQUIRE(ns <= long(s.size() / 6 + 1),
                s.where() << "segment count " << ns << " is more than the file can hold (truncated?)");
  const long nsmark = s.nextInt("number of segment markers (0 or 1)", 0, 1);
  std::vector<Segment> segs;
  std::vector<std::vector<int>> incident(pts.size());
  for (long i = 0; i < ns; ++i) {
    s.nextInt("segment number", LONG_MIN, LONG_MAX);
    int ends[2];
    for (int k = 0; k < 2; ++k) {
      const long v = s.nextInt("segment endpoint", LONG_MIN, LONG_MAX);
      ABLMG_REQUIRE(v >= base && v < base + nv, s.where() << "segment " << i + base << ": endpoint " << v
                                                          << " out of range [" << base << ", " << base + nv - 1 << "]");
      ends[k] = int(v - base);
    }
    ABLMG_REQUIRE(ends[0] != ends[1],
                  s.where() << "segment " << i + base << " joins vertex " << ends[0] + base << " to itself");
    int tag = nsmark ? int(s.nextInt("segment marker", INT_MIN, INT_MAX)) : 1;
    if (tag == 0) tag = 1;
    segs.push_back({ends[0], ends[1], tag, s.line()});
    incident[ends[0]].push_back(int(i));
    incident[ends[1]].push_back(int(i));
  }
  std::vector<Vec2> holePts;
  if (!s.atEnd()) {
    const long nh = s.nextInt("hole count", 0, INT_MAX - 1);
    ABLMG_REQUIRE(nh <= long(s.size() / 4 + 1),
                  s.where() << "hole count " << nh << " is more than the file can hold (truncated?)");
    for (long i = 0; i < nh; ++i) {
      s.nextInt("hole number", LONG_MIN, LONG_MAX);
      const double x = s.nextDouble("hole x"), y = s.nextDouble("hole y");
      holePts.emplace_back(x, y);
    }
  }
  // Slits: chains of segments that end at a vertex of no other segment (a tip), peeled off the
  // loops and added after them (Domain::withSlit, attachment first; both lips get the marker).
  struct Slit {
    std::vector<int> vertices;
    int tag;
  };
  std::vector<Slit> slits;
  std::vector<char> removed(segs.size(), 0);
  const auto live = [&](int v) {
    int n = 0;
    for (int e : incident[std::size_t(v)]) n += !removed[std::size_t(e)];
    return n;
  };
  for (std::size_t v0 = 0; v0 < pts.size(); ++v0) {
    if (live(int(v0)) != 1) continue;
    Slit slit{{int(v0)}, 0};
    for (int v = int(v0);;) {
      int e = -1;
      for (int x : incident[std::size_t(v)])
        if (!removed[std::size_t(x)]) e = x;
      if (e < 0 || live(v) > 1) break;  // an attachment (3 or more) or the end of a free slit
      removed[std::size_t(e)] = 1;
      slit.tag = segs[std::size_t(e)].tag;
      v = segs[std::size_t(e)].a == v ? segs[std::size_t(e)].b : segs[std::size_t(e)].a;
      slit.vertices.push_back(v);
      if (live(v) != 1) break;
    }
    std::reverse(slit.vertices.begin(), slit.vertices.end());  // attachment (or free end) first
    slits.push_back(std::move(slit));
  }
  if (!slits.empty() && std::all_of(removed.begin(), removed.end(), [](char r) { return r != 0; })) {
    const int tip = slits[0].vertices.back(), seg = incident[std::size_t(tip)][0];
    ABLMG_REQUIRE(false, name << ":" << segs[std::size_t(seg)].line << ": boundary is not closed at vertex "
                              << tip + base << " (only segment " << seg + base << " ends there)");
  }
  for (std::size_t v = 0; v < pts.size(); ++v) {
    auto& inc = incident[v];
    inc.erase(std::remove_if(inc.begin(), inc.end(), [&](int e) { return removed[std::size_t(e)] != 0; }), inc.end());
  }
  // Degrees: every used vertex ends exactly two segments.
  for (std::size_t v = 0; v < pts.size(); ++v) {
    const auto& inc = incident[v];
    if (inc.empty()) continue;
    ABLMG_REQUIRE(inc.size() != 1, name << ":" << segs[inc[0]].line << ": boundary is not closed at vertex " << v + base
                                        << " (only segment " << inc[0] + base << " ends there)");
    ABLMG_REQUIRE(inc.size() == 2, name << ":" << segs[inc[0]].line << ": vertex " << v + base << " ends " << inc.size()
                                        << " segments; boundary loops must be simple");
  }
  // Walk loops in order of their first segment.
  std::vector<char> used(removed);
  std::vector<BoundaryLoop> loops;
  for (std::size_t first = 0; first < segs.size(); ++first) {
    if (used[first]) continue;
    BoundaryLoop loop;
    int seg = int(first), at = segs[first].a;
    while (!used[seg]) {
      used[seg] = 1;
      loop.points.push_back(pts[at]);
      loop.tags.push_back(segs[seg].tag);
      const int to = segs[seg].a == at ? segs[seg].b : segs[seg].a;
      const auto& inc = incident[to];
      seg = inc[0] == seg ? inc[1] : inc[0];
      at = to;
    }
    ABLMG_REQUIRE(loop.points.size() >= 3, name << ":" << segs[first].line << ": loop through segment " << first + base
                                                << " has only " << loop.points.size() << " segments");
    loops.push_back(std::move(loop));
  }
  std::size_t outer = 0;
  for (std::size_t l = 1; l < loops.size(); ++l)
    if (std::abs(signedArea(loops[l].points)) > std::abs(signedArea(loops[outer].points))) outer = l;
  std::vector<BoundaryLoop> holes;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (l == outer) continue;
    const bool hasHole =
        signedArea(loops[l].points) == 0 ||  // a zero-width loop: a free slit given as a gap
        std::any_of(holePts.begin(), holePts.end(), [&](const Vec2& h) { return insidePolygon(loops[l].points, h); });
    ABLMG_REQUIRE(hasHole, name << ": inner loop through (" << loops[l].points[0].x() << ", " << loops[l].points[0].y()
                                << ") contains no hole point (interior constraint loops are not supported)");
    holes.push_back(std::move(loops[l]));
  }
  try {
    Domain d(std::move(loops[outer]), std::move(holes));
    for (const Slit& slit : slits) {
      std::vector<Vec2> polyline;
      for (int v : slit.vertices) polyline.push_back(pts[std::size_t(v)]);
      try {
        d = d.withSlit(polyline, slit.tag, slit.tag);
      } catch (const InputError& e) {
        throw InputError("the open chain of segments from vertex " + std::to_string(slit.vertices.front() + base) +
                         " to vertex " + std::to_string(slit.vertices.back() + base) +
                         " is no closed loop and no slit inside the domain: " + e.what());
      }
    }
    return d;
  } catch (const InputError& e) { throw InputError(name + ": " + e.what()); }
}

Domain readPoly(const std::string& path) { return parsePoly(readTextFile(path), path); }

}  // namespace ablmg::io
