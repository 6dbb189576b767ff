#include "ablmg/adapt/boundary_mesh.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/mesher/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace ablmg::adapt {
namespace {

std::uint64_t undirectedKey(int a, int b) {
  return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
}

/// The loops of the edges, in compacted vertex ids: vertices, and per segment k (vertices k →
/// k + 1 mod n) the edge's ref.
struct Loops {
  std::vector<Vec2> points;                        ///< per compacted vertex
  std::vector<int> inputVertex;                    ///< per compacted vertex
  std::vector<std::vector<int>> vertices;          ///< per loop
  std::vector<std::vector<int>> refs;              ///< per loop, per segment
  std::unordered_map<std::uint64_t, int> edgeRef;  ///< undirected compacted edge → ref
};

/// 1. Every vertex on exactly two edges; the loops chained from their smallest vertex.
Loops chainLoops(const Mesh2& b, const std::string& name) {
  ABLMG_REQUIRE(!b.boundaryEdges.empty(), name << ": the mesh has neither triangles nor edges (nothing to mesh)");
  const std::size_t nv = b.vertices.size();
  std::vector<std::vector<std::pair<int, int>>> nbr(nv);  // (neighbour, ref)
  for (const auto& e : b.boundaryEdges) {
    ABLMG_REQUIRE(e.a != e.b, name << ": edge (" << e.a + 1 << ", " << e.b + 1 << ") joins a vertex to itself");
    nbr[std::size_t(e.a)].emplace_back(e.b, e.ref);
    nbr[std::size_t(e.b)].emplace_back(e.a, e.ref);
  }
  Loops L;
  std::vector<int> id(nv, -1);
  for (std::size_t v = 0; v < nv; ++v) {
    if (nbr[v].empty()) continue;
    const Vec2& p = b.vertices[v];
    ABLMG_REQUIRE(nbr[v].size() != 1, name << ": open chain of edges: vertex " << v + 1 << " (" << p.x() << ", "
                                           << p.y() << ") is on one edge (every boundary loop must be closed)");
    ABLMG_REQUIRE(nbr[v].size() == 2, name << ": vertex " << v + 1 << " (" << p.x() << ", " << p.y() << ") is on "
                                           << nbr[v].size()
                                           << " edges (boundary loops may not branch, touch or cross)");
    id[v] = int(L.points.size());
    L.points.push_back(p);
    L.inputVertex.push_back(int(v));
  }
  std::vector<char> visited(nv, 0);
  for (std::size_t s = 0; s < nv; ++s) {
    if (id[s] < 0 || visited[s]) continue;
    std::vector<int> loop, refs;
    int prev = -1, v = int(s);
    while (!visited[std::size_t(v)]) {
      visited[std::size_t(v)] = 1;
      loop.push_back(id[std::size_t(v)]);
      const auto& n = nbr[std::size_t(v)];
      // the first step takes the smaller neighbour; then the one we did not come from
      const int k = prev < 0 ? (n[0].first < n[1].first ? 0 : 1) : (n[0].first == prev ? 1 : 0);
      refs.push_back(n[std::size_t(k)].second);
      L.edgeRef[undirectedKey(id[std::size_t(v)], id[std::size_t(n[std::size_t(k)].first)])] = n[std::size_t(k)].second;
      prev = v;
      v = n[std::size_t(k)].first;
    }
    L.vertices.push_back(std::move(loop));
    L.refs.push_back(std::move(refs));
  }
  return L;
}

/// 2. No two edges cross or overlap (a sweep over x extents; exact predicates).
void requireNoCrossings(const Loops& L, const std::string& name) {
  struct Seg {
    int a, b;
    double x0, x1;
  };
  std::vector<Seg> segs;
  for (const auto& loop : L.vertices)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      segs.push_back({a, b, std::min(L.points[std::size_t(a)].x(), L.points[std::size_t(b)].x()),
                      std::max(L.points[std::size_t(a)].x(), L.points[std::size_t(b)].x())});
    }
  std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return s.x0 < t.x0; });
  for (std::size_t i = 0; i < segs.size(); ++i)
    for (std::size_t j = i + 1; j < segs.size() && segs[j].x0 <= segs[i].x1; ++j) {
      const Seg &s = segs[i], &t = segs[j];
      const auto P = [&](int v) { return L.points[std::size_t(v)]; };
      ABLMG_REQUIRE(!segmentsCross(P(s.a), P(s.b), P(t.a), P(t.b)),
                    name << ": edges (" << L.inputVertex[std::size_t(s.a)] + 1 << ", "
                         << L.inputVertex[std::size_t(s.b)] + 1 << ") and (" << L.inputVertex[std::size_t(t.a)] + 1
                         << ", " << L.inputVertex[std::size_t(t.b)] + 1 << ") cross (boundary loops may not cross)");
    }
}

double signedArea(const Loops& L, const std::vector<int>& loop) {
  if (loop.empty()) return 0;
  const Vec2 o = L.points[std::size_t(loop[0])];  // about a loop point: exact sign far from the origin
  double a = 0;
  for (std::size_t k = 0; k < loop.size(); ++k)
    a += cross(L.points[std::size_t(loop[k])] - o, L.points[std::size_t(loop[(k + 1) % loop.size()])] - o);
  return 0.5 * a;
}

/// Crossing-number test of p in loop l (p on no edge of it: loops do not touch).
bool insideLoop(const Loops& L, int l, const Vec2& p) {
  const auto& loop = L.vertices[std::size_t(l)];
  bool in = false;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec2 &a = L.points[std::size_t(loop[k])], &b = L.points[std::size_t(loop[(k + 1) % loop.size()])];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

/// The innermost loop containing p (−1: none) and how many loops contain p.
std::pair<int, int> innermostLoop(const Loops& L, const std::vector<double>& areas, const Vec2& p) {
  int best = -1, depth = 0;
  for (int l = 0; l < int(L.vertices.size()); ++l)
    if (insideLoop(L, l, p)) {
      ++depth;
      if (best < 0 || std::abs(areas[std::size_t(l)]) < std::abs(areas[std::size_t(best)])) best = l;
    }
  return {best, depth};
}

}  // namespace

namespace {
/// 3–4. The constrained triangulation and the ref of each of its triangles (0: not kept).
std::vector<int> keptTriangles(const Loops& L, const mesher::Triangulation& tri, InteriorLoops mode) {
  std::vector<double> areas;
  for (const auto& loop : L.vertices) areas.push_back(signedArea(L, loop));
  const int n = tri.numPoints(), nt = tri.numTriangleSlots();
  std::vector<int> component(std::size_t(nt), -1), ref;
  for (int s = 0; s < nt; ++s) {
    if (component[std::size_t(s)] >= 0) continue;
    const int c = int(ref.size());
    std::vector<int> stack{s};
    component[std::size_t(s)] = c;
    bool artificial = false;
    while (!stack.empty()) {  // the triangles reached without crossing a loop edge
      const int t = stack.back();
      stack.pop_back();
      const auto& tv = tri.triangle(t);
      for (int k = 0; k < 3; ++k) {
        artificial = artificial || tv[std::size_t(k)] >= n;
        const int u = tri.neighbours(t)[std::size_t(k)];
        if (u < 0 || component[std::size_t(u)] >= 0) continue;
        if (L.edgeRef.count(undirectedKey(tv[std::size_t((k + 1) % 3)], tv[std::size_t((k + 2) % 3)]))) continue;
        component[std::size_t(u)] = c;
        stack.push_back(u);
      }
    }
    int r = 0;
    if (!artificial) {
      const auto& tv = tri.triangle(s);
      const Vec2 centre = (tri.point(tv[0]) + tri.point(tv[1]) + tri.point(tv[2])) / 3;
      const auto [loop, depth] = innermostLoop(L, areas, centre);
      if (loop >= 0 && (mode == InteriorLoops::Subdomains || depth % 2 == 1)) r = loop + 1;
    }
    ref.push_back(r);
  }
  std::vector<int> out(static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) out[std::size_t(t)] = ref[std::size_t(component[std::size_t(t)])];
  return out;
}
}  // namespace

BoundaryTriangulation triangulateBoundary(const Mesh2& boundary, const std::string& name, InteriorLoops mode) {
  const Loops L = chainLoops(boundary, name);
  requireNoCrossings(L, name);
  for (std::size_t l = 0; l < L.vertices.size(); ++l)
    ABLMG_REQUIRE(signedArea(L, L.vertices[l]) != 0, name << ": the loop through vertex "
                                                          << L.inputVertex[std::size_t(L.vertices[l][0])] + 1
                                                          << " has zero area");
  mesher::Triangulation tri = [&] {
    try {
      return mesher::Triangulation(L.points);
    } catch (const InputError& e) {  // coincident loop vertices
      throw InputError(name + ": " + e.what());
    }
  }();
  for (const auto& loop : L.vertices)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      ABLMG_REQUIRE(tri.recoverEdge(a, b), name << ": edge (" << L.inputVertex[std::size_t(a)] + 1 << ", "
                                                << L.inputVertex[std::size_t(b)] + 1
                                                << ") cannot be recovered (a vertex lies on it)");
    }
  const std::vector<int> keep = keptTriangles(L, tri, mode);
  BoundaryTriangulation out;
  Mesh2& m = out.mesh;
  m.vertices = L.points;
  out.inputVertex = L.inputVertex;
  std::unordered_map<std::uint64_t, int> side;  // undirected loop edge → the ref of one kept side
  for (int t = 0; t < tri.numTriangleSlots(); ++t) {
    if (keep[std::size_t(t)] == 0) continue;
    const auto& tv = tri.triangle(t);
    m.triangles.push_back(tv);
    m.triangleRefs.push_back(keep[std::size_t(t)]);
    for (int k = 0; k < 3; ++k) {
      const int a = tv[std::size_t((k + 1) % 3)], b = tv[std::size_t((k + 2) % 3)];
      const auto e = L.edgeRef.find(undirectedKey(a, b));
      if (e == L.edgeRef.end()) continue;
      const int u = tri.neighbours(t)[std::size_t(k)];
      if (u < 0 || keep[std::size_t(u)] == 0)
        m.boundaryEdges.push_back({a, b, e->second});  // tv is CCW: the triangle is left of a → b
      else if (a < b)
        m.interfaceEdges.push_back({a, b, e->second});
    }
  }
  // Features, renumbered: every one must be on an edge.
  std::vector<int> id(boundary.vertices.size(), -1);
  for (std::size_t v = 0; v < out.inputVertex.size(); ++v) id[std::size_t(out.inputVertex[v])] = int(v);
  const auto map = [&](int v, const char* what) {
    ABLMG_REQUIRE(id[std::size_t(v)] >= 0, name << ": " << what << " " << v + 1 << " is on no edge");
    return id[std::size_t(v)];
  };
  for (int v : boundary.corners) m.corners.push_back(map(v, "corner"));
  for (int v : boundary.requiredVertices) m.requiredVertices.push_back(map(v, "required vertex"));
  for (const auto& e : boundary.requiredEdges) m.requiredEdges.push_back({map(e[0], "vertex"), map(e[1], "vertex")});
  for (const auto& e : boundary.ridges) m.ridges.push_back({map(e[0], "vertex"), map(e[1], "vertex")});
  m.requireValid(name);
  return out;
}

}  // namespace ablmg::adapt
