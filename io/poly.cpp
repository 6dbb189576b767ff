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
  if (p.empty()) return 0;
  double s = 0;  // about p[0]: exact sign far from the origin
  for (std::size_t i = 0; i < p.size(); ++i) s += cross(p[i] - p[0], p[(i + 1) % p.size()] - p[0]);
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

/// A .poly file's planar straight-line graph: vertices (0-based here; `base` is the file's first
/// vertex number), segments with the file line each was read on, and the hole points.
struct Pslg {
  std::vector<Vec2> pts;
  long base = 0;
  std::vector<Segment> segs;
  std::vector<std::vector<int>> incident;  ///< per vertex, the segments ending there
  std::vector<Vec2> holePts;
};

void readVertices(TextScanner& s, Pslg& g) {
  const long nv = s.nextInt("vertex count", 0, INT_MAX - 1);
  ABLMG_REQUIRE(nv > 0, s.where() << "0 vertices (vertices in a separate .node file are not supported)");
  s.nextInt("dimension", 2, 2);
  const long nattr = s.nextInt("number of vertex attributes", 0, 1000);
  const long nvmark = s.nextInt("number of vertex markers (0 or 1)", 0, 1);
  ABLMG_REQUIRE(nv <= long(s.size() / 6 + 1),
                s.where() << "vertex count " << nv << " is more than the file can hold (truncated?)");
  g.pts.reserve(std::size_t(nv));
  for (long i = 0; i < nv; ++i) {
    const long id = s.nextInt("vertex number", LONG_MIN, LONG_MAX);
    if (i == 0) {
      ABLMG_REQUIRE(id == 0 || id == 1, s.where() << "first vertex number is " << id << ", expected 0 or 1");
      g.base = id;
    }
    ABLMG_REQUIRE(id == g.base + i, s.where() << "vertex number " << id << ", expected " << g.base + i);
    const double x = s.nextDouble("vertex x coordinate"), y = s.nextDouble("vertex y coordinate");
    for (long k = 0; k < nattr; ++k) s.nextDouble("vertex attribute");
    if (nvmark) s.nextInt("vertex marker", INT_MIN, INT_MAX);
    g.pts.emplace_back(x, y);
  }
}

/// Segments (marker 0 or none reads as tag 1), then the optional hole section.
void readSegmentsAndHoles(TextScanner& s, Pslg& g) {
  const long nv = long(g.pts.size()), base = g.base;
  const long ns = s.nextInt("segment count", 0, INT_MAX - 1);
  ABLMG_REQUIRE(ns >= 3, s.where() << ns << " segments: a domain needs a closed loop of at least 3");
  ABLMG_REQUIRE(ns <= long(s.size() / 6 + 1),
                s.where() << "segment count " << ns << " is more than the file can hold (truncated?)");
  const long nsmark = s.nextInt("number of segment markers (0 or 1)", 0, 1);
  g.incident.assign(g.pts.size(), {});
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
    g.segs.push_back({ends[0], ends[1], tag, s.line()});
    g.incident[std::size_t(ends[0])].push_back(int(i));
    g.incident[std::size_t(ends[1])].push_back(int(i));
  }
  if (s.atEnd()) return;
  const long nh = s.nextInt("hole count", 0, INT_MAX - 1);
  ABLMG_REQUIRE(nh <= long(s.size() / 4 + 1),
                s.where() << "hole count " << nh << " is more than the file can hold (truncated?)");
  for (long i = 0; i < nh; ++i) {
    s.nextInt("hole number", LONG_MIN, LONG_MAX);
    const double x = s.nextDouble("hole x"), y = s.nextDouble("hole y");
    g.holePts.emplace_back(x, y);
  }
}

/// A chain of segments that ends at a vertex of no other segment (its tip).
struct Slit {
  std::vector<int> vertices;  ///< attachment (or free end) first, tip last
  int tag;
};

/// Peels the slits off the graph: their segments leave `g.incident` and are marked in `removed`.
std::vector<Slit> peelSlits(Pslg& g, std::vector<char>& removed, const std::string& name) {
  std::vector<Slit> slits;
  removed.assign(g.segs.size(), 0);
  const auto live = [&](int v) {
    int n = 0;
    for (int e : g.incident[std::size_t(v)]) n += !removed[std::size_t(e)];
    return n;
  };
  for (std::size_t v0 = 0; v0 < g.pts.size(); ++v0) {
    if (live(int(v0)) != 1) continue;
    Slit slit{{int(v0)}, 0};
    for (int v = int(v0);;) {
      int e = -1;
      for (int x : g.incident[std::size_t(v)])
        if (!removed[std::size_t(x)]) e = x;
      if (e < 0 || live(v) > 1) break;  // an attachment (3 or more) or the end of a free slit
      removed[std::size_t(e)] = 1;
      const Segment& seg = g.segs[std::size_t(e)];
      slit.tag = seg.tag;
      v = seg.a == v ? seg.b : seg.a;
      slit.vertices.push_back(v);
      if (live(v) != 1) break;
    }
    std::reverse(slit.vertices.begin(), slit.vertices.end());
    slits.push_back(std::move(slit));
  }
  if (!slits.empty() && std::all_of(removed.begin(), removed.end(), [](char r) { return r != 0; })) {
    const int tip = slits[0].vertices.back(), seg = g.incident[std::size_t(tip)][0];
    ABLMG_REQUIRE(false, name << ":" << g.segs[std::size_t(seg)].line << ": boundary is not closed at vertex "
                              << tip + g.base << " (only segment " << seg + g.base << " ends there)");
  }
  for (auto& inc : g.incident)
    inc.erase(std::remove_if(inc.begin(), inc.end(), [&](int e) { return removed[std::size_t(e)] != 0; }), inc.end());
  return slits;
}

/// The closed loops left after the slits, in order of their first segment; every used vertex
/// must end exactly two segments.
std::vector<BoundaryLoop> walkLoops(const Pslg& g, const std::vector<char>& removed, const std::string& name) {
  for (std::size_t v = 0; v < g.pts.size(); ++v) {
    const auto& inc = g.incident[v];
    if (inc.empty()) continue;
    ABLMG_REQUIRE(inc.size() != 1, name << ":" << g.segs[std::size_t(inc[0])].line
                                        << ": boundary is not closed at vertex " << v + g.base << " (only segment "
                                        << inc[0] + g.base << " ends there)");
    ABLMG_REQUIRE(inc.size() == 2, name << ":" << g.segs[std::size_t(inc[0])].line << ": vertex " << v + g.base
                                        << " ends " << inc.size() << " segments; boundary loops must be simple");
  }
  std::vector<char> used(removed);
  std::vector<BoundaryLoop> loops;
  for (std::size_t first = 0; first < g.segs.size(); ++first) {
    if (used[first]) continue;
    BoundaryLoop loop;
    int seg = int(first), at = g.segs[first].a;
    while (!used[std::size_t(seg)]) {
      used[std::size_t(seg)] = 1;
      loop.points.push_back(g.pts[std::size_t(at)]);
      loop.tags.push_back(g.segs[std::size_t(seg)].tag);
      const int to = g.segs[std::size_t(seg)].a == at ? g.segs[std::size_t(seg)].b : g.segs[std::size_t(seg)].a;
      const auto& inc = g.incident[std::size_t(to)];
      seg = inc[0] == seg ? inc[1] : inc[0];
      at = to;
    }
    ABLMG_REQUIRE(loop.points.size() >= 3, name << ":" << g.segs[first].line << ": loop through segment "
                                                << first + std::size_t(g.base) << " has only " << loop.points.size()
                                                << " segments");
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The loop of largest area is the outer boundary; every other loop must hold a hole point (or
/// have zero area: a free slit given as a gap). The slits are added last, attachment first.
Domain assembleDomain(std::vector<BoundaryLoop> loops, const std::vector<Slit>& slits, const Pslg& g) {
  std::size_t outer = 0;
  for (std::size_t l = 1; l < loops.size(); ++l)
    if (std::abs(signedArea(loops[l].points)) > std::abs(signedArea(loops[outer].points))) outer = l;
  std::vector<BoundaryLoop> holes;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (l == outer) continue;
    const bool hasHole = signedArea(loops[l].points) == 0 ||
                         std::any_of(g.holePts.begin(), g.holePts.end(),
                                     [&](const Vec2& h) { return insidePolygon(loops[l].points, h); });
    ABLMG_REQUIRE(hasHole, "inner loop through ("
                               << loops[l].points[0].x() << ", " << loops[l].points[0].y()
                               << ") contains no hole point (interior constraint loops are not supported)");
    holes.push_back(std::move(loops[l]));
  }
  Domain d(std::move(loops[outer]), std::move(holes));
  for (const Slit& slit : slits) {
    std::vector<Vec2> polyline;
    for (int v : slit.vertices) polyline.push_back(g.pts[std::size_t(v)]);
    try {
      d = d.withSlit(polyline, slit.tag, slit.tag);
    } catch (const InputError& e) {
      throw InputError("the open chain of segments from vertex " + std::to_string(slit.vertices.front() + g.base) +
                       " to vertex " + std::to_string(slit.vertices.back() + g.base) +
                       " is no closed loop and no slit inside the domain: " + e.what());
    }
  }
  return d;
}

}  // namespace

Domain parsePoly(const std::string& text, const std::string& name) {
  TextScanner s(text, name);
  ABLMG_REQUIRE(!s.atEnd(), name << ":1: empty file, expected the vertex count of a .poly");
  Pslg g;
  readVertices(s, g);
  readSegmentsAndHoles(s, g);
  std::vector<char> removed;
  const std::vector<Slit> slits = peelSlits(g, removed, name);
  std::vector<BoundaryLoop> loops = walkLoops(g, removed, name);
  try {
    return assembleDomain(std::move(loops), slits, g);
  } catch (const InputError& e) { throw InputError(name + ": " + e.what()); }
}

Domain readPoly(const std::string& path) { return parsePoly(readTextFile(path), path); }

}  // namespace ablmg::io
