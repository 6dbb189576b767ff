// Remeshing a mesh with subdomains and interfaces (adapt/remesh.hpp, remeshSubdomains): each
// subdomain is meshed on its own (the connection of paper §4 is per domain, so no link crosses an
// interface), from loops whose interface pieces are discretized once for both sides and fixed;
// the meshes are then glued at those shared points.
#include "ablmg/adapt/remesh.hpp"
#include "ablmg/core/bucket_grid.hpp"
#include "ablmg/core/domain_from_mesh.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <unordered_map>

namespace ablmg::adapt {
namespace {

std::uint64_t directed(int a, int b) { return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b); }
std::uint64_t undirected(int a, int b) { return directed(std::min(a, b), std::max(a, b)); }

/// Bits of a point, for gluing the subdomain meshes at their shared (bit-identical) points.
using PointKey = std::pair<std::uint64_t, std::uint64_t>;
PointKey keyOf(const Vec2& p) { return {std::bit_cast<std::uint64_t>(p.x()), std::bit_cast<std::uint64_t>(p.y())}; }

/// The ref of the cuts that split a slit's subdomain (never a file's ref: dropped after gluing).
constexpr int kCutRef = std::numeric_limits<int>::min() + 1;

/// Slits, given in a mesh as a zero-width gap: a boundary vertex at the same point as another
/// boundary vertex, or exactly on a boundary edge it is no end of, is a lip vertex (the two lips
/// of a slit need not share their points: a remesher may discretize each lip on its own). A
/// valid boundary touches itself nowhere else, so no other vertex is flagged. The edges are
/// bucketed (BucketGrid, about one cell per edge), each vertex tested against its cell's edges
/// with the exact orientation predicate. Returns the flags (per vertex) of the lip vertices.
std::vector<char> lipVertices(const Mesh2& mesh) {
  std::map<PointKey, int> seen;
  std::vector<char> lip(mesh.vertices.size(), 0);
  for (const auto& e : mesh.boundaryEdges)
    for (int v : {e.a, e.b}) {
      const auto [it, added] = seen.emplace(keyOf(mesh.vertices[std::size_t(v)]), v);
      if (!added && it->second != v) lip[std::size_t(v)] = lip[std::size_t(it->second)] = 1;
    }
  if (mesh.boundaryEdges.empty()) return lip;
  const auto at = [&](int v) { return mesh.vertices[std::size_t(v)]; };
  Vec2 lo = at(mesh.boundaryEdges[0].a), hi = lo;
  for (const auto& e : mesh.boundaryEdges)
    for (int v : {e.a, e.b}) lo = lo.cwiseMin(at(v)), hi = hi.cwiseMax(at(v));
  const double extent = (hi - lo).maxCoeff();
  if (!(extent > 0 && std::isfinite(extent))) return lip;  // one point, or coordinates no grid spans
  const double edges = double(mesh.boundaryEdges.size());
  BucketGrid grid(lo, hi, std::max(extent / std::sqrt(edges), std::numeric_limits<double>::min()),
                  long(4 * edges) + 16);
  std::vector<std::pair<int, int>> cellIds;  // (cell, edge) for every cell an edge's box covers
  for (std::size_t k = 0; k < mesh.boundaryEdges.size(); ++k) {
    const Vec2 a = at(mesh.boundaryEdges[k].a), b = at(mesh.boundaryEdges[k].b);
    const Vec2 l = a.cwiseMin(b), h = a.cwiseMax(b);
    for (int y = grid.cellY(l.y()); y <= grid.cellY(h.y()); ++y)
      for (int x = grid.cellX(l.x()); x <= grid.cellX(h.x()); ++x) cellIds.push_back({y * grid.nx() + x, int(k)});
  }
  grid.buildFromPairs(cellIds);
  for (const auto& [key, v] : seen) {
    const Vec2 p = at(v);
    for (const int k : grid.cell(grid.cellOf(p))) {
      const auto& e = mesh.boundaryEdges[std::size_t(k)];
      const Vec2 a = at(e.a), b = at(e.b);
      if (p == a || p == b || orient2d(a, b, p) != 0 || (p - a).dot(b - a) <= 0 || (p - b).dot(a - b) <= 0) continue;
      lip[std::size_t(v)] = 1;
      break;
    }
  }
  return lip;
}

/// A slit is made meshable by cutting its subdomain in two: from each tip (a boundary vertex
/// between two lip vertices, itself on no lip), the shortest path of mesh edges (Euclidean
/// length; ties to the smaller vertex) through vertices on no boundary, interface or earlier cut,
/// to a boundary or interface vertex on no lip. Its edges are added as interface edges of ref
/// kCutRef: the two lips then lie in two subdomains and keep distinct vertices. Returns the
/// number of tips; throws InputError if a tip has no path.
int cutSlits(Mesh2& mesh, const std::string& name) {
  const std::vector<char> lip = lipVertices(mesh);
  if (std::find(lip.begin(), lip.end(), 1) == lip.end()) return 0;
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::vector<int>> nbrs(nv);
  for (const auto& e : mesh.edges()) {
    nbrs[std::size_t(e[0])].push_back(e[1]);
    nbrs[std::size_t(e[1])].push_back(e[0]);
  }
  std::vector<char> blocked(nv, 0);  // on the boundary, an interface or a cut
  std::vector<std::array<int, 2>> bnbr(nv, {-1, -1});
  for (const auto& e : mesh.boundaryEdges) {
    blocked[std::size_t(e.a)] = blocked[std::size_t(e.b)] = 1;
    bnbr[std::size_t(e.a)][1] = e.b;
    bnbr[std::size_t(e.b)][0] = e.a;
  }
  for (const auto& e : mesh.interfaceEdges) blocked[std::size_t(e.a)] = blocked[std::size_t(e.b)] = 1;
  int tips = 0;
  for (std::size_t t = 0; t < nv; ++t) {
    if (lip[t] || bnbr[t][0] < 0 || !lip[std::size_t(bnbr[t][0])] || !lip[std::size_t(bnbr[t][1])]) continue;
    ++tips;
    std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
    std::vector<int> from(nv, -1);
    std::set<std::pair<double, int>> queue{{0.0, int(t)}};
    dist[t] = 0;
    int end = -1;
    while (!queue.empty() && end < 0) {
      const int v = queue.begin()->second;
      queue.erase(queue.begin());
      if (v != int(t) && blocked[std::size_t(v)]) {
        end = v;
        break;
      }
      for (int w : nbrs[std::size_t(v)]) {
        if (lip[std::size_t(w)] || std::size_t(w) == t) continue;
        const double d = dist[std::size_t(v)] + (mesh.vertices[std::size_t(w)] - mesh.vertices[std::size_t(v)]).norm();
        if (d < dist[std::size_t(w)]) {
          queue.erase({dist[std::size_t(w)], w});
          dist[std::size_t(w)] = d;
          from[std::size_t(w)] = v;
          queue.insert({d, w});
        }
      }
    }
    ABLMG_REQUIRE(end >= 0, name << ": the slit tip at vertex " << t + 1 << " cannot be joined to the boundary");
    for (int v = end; v != int(t); v = from[std::size_t(v)]) {
      mesh.interfaceEdges.push_back({from[std::size_t(v)], v, kCutRef});
      blocked[std::size_t(v)] = 1;
    }
    blocked[t] = 1;
  }
  return tips;
}

/// A chain of interface edges between two junctions (or a closed one), and its points after
/// discretization: on the input polyline, at equal metric arc length, ends included.
struct Curve {
  std::vector<int> vertices;  ///< input vertex ids, junction to junction
  int ref = 0;
  std::vector<Vec2> points;
};

/// The interface curves; `start` maps the directed first edge of each curve, both ways
/// (v0→v1: forward, vn→vn−1: backward), to (curve id, backward flag).
struct Curves {
  std::vector<Curve> list;
  std::unordered_map<std::uint64_t, std::pair<int, bool>> start;
};

Curves interfaceCurves(const Mesh2& mesh, std::vector<char>& junction) {
  std::unordered_map<int, std::vector<std::pair<int, int>>> adj;  // vertex -> (neighbour, ref)
  for (const auto& e : mesh.interfaceEdges) {
    adj[e.a].push_back({e.b, e.ref});
    adj[e.b].push_back({e.a, e.ref});
  }
  std::vector<int> order;
  for (const auto& [v, list] : adj) order.push_back(v);
  std::sort(order.begin(), order.end());
  Curves c;
  std::unordered_map<std::uint64_t, char> done;
  const auto walk = [&](int v0, int v1, int ref) {
    Curve curve{{v0, v1}, ref, {}};
    done[undirected(v0, v1)] = 1;
    while (!junction[std::size_t(curve.vertices.back())]) {
      const int v = curve.vertices.back(), prev = curve.vertices[curve.vertices.size() - 2];
      const auto& nbrs = adj[v];  // two, v is no junction
      const int w = nbrs[0].first == prev ? nbrs[1].first : nbrs[0].first;
      done[undirected(v, w)] = 1;
      curve.vertices.push_back(w);
    }
    const int id = int(c.list.size());
    c.start[directed(curve.vertices[0], curve.vertices[1])] = {id, false};
    const std::size_t n = curve.vertices.size();
    c.start[directed(curve.vertices[n - 1], curve.vertices[n - 2])] = {id, true};
    c.list.push_back(std::move(curve));
  };
  for (int pass = 0; pass < 2; ++pass)  // curves from junctions, then closed curves without one
    for (int v : order) {
      if (pass == 1 && !junction[std::size_t(v)]) {
        bool open = false;
        for (const auto& [w, ref] : adj[v]) open = open || !done.count(undirected(v, w));
        if (!open) continue;
        junction[std::size_t(v)] = 1;  // its smallest vertex
      }
      if (!junction[std::size_t(v)]) continue;
      for (const auto& [w, ref] : adj[v])
        if (!done.count(undirected(v, w))) walk(v, w, ref);
    }
  return c;
}

/// Points at equal metric arc length along the curve's polyline, n = round(metric length)
/// pieces (≥ 1; ≥ 3 when closed; 1 for a required edge), the ends included.
void discretize(Curve& curve, const Mesh2& mesh, const MetricField& field,
                const std::unordered_map<std::uint64_t, char>& required) {
  std::vector<Vec2> sub;
  for (std::size_t i = 0; i + 1 < curve.vertices.size(); ++i) {
    const Vec2 a = mesh.vertices[std::size_t(curve.vertices[i])], b = mesh.vertices[std::size_t(curve.vertices[i + 1])];
    Metric2 m[2];
    const Vec2 ab[2] = {a, b};
    field.evaluate(ab, m);
    const int k = std::clamp(int(std::ceil(4 * edgeLength(a, m[0], b, m[1]))), 1, 1 << 12);
    for (int j = 0; j < k; ++j) sub.push_back(a + (double(j) / k) * (b - a));
  }
  sub.push_back(mesh.vertices[std::size_t(curve.vertices.back())]);
  std::vector<Metric2> sm(sub.size());
  field.evaluate(sub, sm);
  std::vector<double> s(sub.size(), 0.0);
  for (std::size_t i = 1; i < sub.size(); ++i) s[i] = s[i - 1] + edgeLength(sub[i - 1], sm[i - 1], sub[i], sm[i]);
  const bool closed = curve.vertices.front() == curve.vertices.back();
  const bool requiredEdge =
      curve.vertices.size() == 2 && required.count(undirected(curve.vertices[0], curve.vertices[1]));
  const int n = requiredEdge ? 1 : std::max(closed ? 3 : 1, int(std::lround(s.back())));
  curve.points = {sub.front()};
  for (int i = 1; i < n; ++i) {
    const double t = s.back() * i / n;
    const std::size_t j = std::size_t(std::upper_bound(s.begin(), s.end(), t) - s.begin());
    const double f = (t - s[j - 1]) / std::max(s[j] - s[j - 1], 1e-300);
    curve.points.push_back(sub[j - 1] + f * (sub[j] - sub[j - 1]));
  }
  curve.points.push_back(sub.back());
}

/// One subdomain's Domain: boundary stretches as smooth polylines of the input vertices
/// (junctions fixed, required edges kept), interface stretches as their curves' points (all
/// fixed, every segment kept, so both sides get the same vertices and edges).
Domain regionDomain(const MeshSubdomain& r, const Mesh2& mesh, const std::vector<char>& junction, const Curves& curves,
                    const std::unordered_map<std::uint64_t, char>& required) {
  std::vector<BoundaryLoop> loops;
  for (std::size_t l = 0; l < r.loops.size(); ++l) {
    const auto& vs = r.loops[l];
    const std::size_t n = vs.size();
    std::size_t first = 0;  // start at a junction, so that no curve wraps around the start
    while (first < n && !junction[std::size_t(vs[first])]) ++first;
    if (first == n) first = 0;
    BoundaryLoop loop;
    loop.smooth = true;
    for (std::size_t i = 0; i < n;) {
      const std::size_t k = (first + i) % n;
      const int a = vs[k], b = vs[(k + 1) % n];
      if (!r.segmentInterface[l][k]) {
        loop.points.push_back(mesh.vertices[std::size_t(a)]);
        loop.tags.push_back(r.segmentRefs[l][k]);
        loop.fixedPoints.push_back(junction[std::size_t(a)]);
        loop.keptSegments.push_back(required.count(undirected(a, b)) ? 1 : 0);
        ++i;
        continue;
      }
      const auto it = curves.start.find(directed(a, b));
      ABLMG_REQUIRE(it != curves.start.end(),
                    "remesh: interface edge (" << a + 1 << ", " << b + 1 << ") starts no interface curve");
      const Curve& c = curves.list[std::size_t(it->second.first)];
      std::vector<Vec2> pts = c.points;
      if (it->second.second) std::reverse(pts.begin(), pts.end());
      for (std::size_t p = 0; p + 1 < pts.size(); ++p) {
        loop.points.push_back(pts[p]);
        loop.tags.push_back(c.ref);
        loop.fixedPoints.push_back(1);
        loop.keptSegments.push_back(1);
      }
      i += c.vertices.size() - 1;
    }
    loops.push_back(std::move(loop));
  }
  BoundaryLoop outer = std::move(loops.front());
  loops.erase(loops.begin());
  return Domain(std::move(outer), std::move(loops));
}

/// The subdomain meshes glued into one: boundary vertices at the same point merged, edges met
/// from both sides become interface edges, triangles take their subdomain's ref.
void glue(std::vector<mesher::MeshResult>& parts, const std::vector<int>& refs, const Curves& curves,
          RemeshResult& out) {
  Mesh2& m = out.mesh;
  std::map<PointKey, int> shared;  // the interface points (only they are shared: slit lips are not)
  for (const auto& c : curves.list)
    for (const Vec2& p : c.points) shared.emplace(keyOf(p), -1);
  std::map<std::uint64_t, std::size_t> edgeAt;  // undirected → index in m.boundaryEdges
  std::vector<char> isInterface;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const Mesh2& part = parts[p].mesh;
    std::vector<char> onBoundary(std::size_t(part.numVertices()), 0);
    for (const auto& e : part.boundaryEdges) onBoundary[std::size_t(e.a)] = onBoundary[std::size_t(e.b)] = 1;
    std::vector<int> id(std::size_t(part.numVertices()));
    for (int v = 0; v < part.numVertices(); ++v) {
      const std::size_t vs = std::size_t(v);
      const auto it = onBoundary[vs] ? shared.find(keyOf(part.vertices[vs])) : shared.end();
      if (it != shared.end()) {
        if (it->second >= 0) {
          id[vs] = it->second;
          continue;
        }
        id[vs] = it->second = m.numVertices();
      } else {
        id[vs] = m.numVertices();
      }
      m.vertices.push_back(part.vertices[vs]);
      out.metric.push_back(parts[p].metric[vs]);
    }
    for (const auto& t : part.triangles) {
      m.triangles.push_back({id[std::size_t(t[0])], id[std::size_t(t[1])], id[std::size_t(t[2])]});
      m.triangleRefs.push_back(refs[p]);
    }
    for (const auto& e : part.boundaryEdges) {
      const BoundaryEdge g{id[std::size_t(e.a)], id[std::size_t(e.b)], e.ref};
      const auto [it, added] = edgeAt.emplace(undirected(g.a, g.b), m.boundaryEdges.size());
      if (added) {
        m.boundaryEdges.push_back(g);
        isInterface.push_back(0);
      } else {
        isInterface[it->second] = 1;
      }
    }
  }
  std::vector<BoundaryEdge> boundary;
  for (std::size_t e = 0; e < m.boundaryEdges.size(); ++e) {
    if (isInterface[e] && m.boundaryEdges[e].ref == kCutRef) continue;  // a slit's cut: not an interface
    (isInterface[e] ? m.interfaceEdges : boundary).push_back(m.boundaryEdges[e]);
  }
  m.boundaryEdges = std::move(boundary);
}

/// Input features (corners, required vertices and edges) → the output's vertex ids. Every one
/// is a fixed point of some loop, so it is found at its exact coordinates.
void mapFeatures(const Mesh2& in, Mesh2& out, const std::string& name) {
  std::map<PointKey, int> at;
  for (const auto& e : out.boundaryEdges) at[keyOf(out.vertices[std::size_t(e.a)])] = e.a;
  for (const auto& e : out.interfaceEdges) {
    at[keyOf(out.vertices[std::size_t(e.a)])] = e.a;
    at[keyOf(out.vertices[std::size_t(e.b)])] = e.b;
  }
  for (const auto& e : out.boundaryEdges) at[keyOf(out.vertices[std::size_t(e.b)])] = e.b;
  const auto find = [&](int v, const char* what) {
    const auto it = at.find(keyOf(in.vertices[std::size_t(v)]));
    ABLMG_REQUIRE(it != at.end(), name << ": " << what << " " << v + 1 << " lies inside a subdomain (only " << what
                                       << "s on the boundary or on interfaces are kept)");
    return it->second;
  };
  for (int v : in.corners) out.corners.push_back(find(v, "corner"));
  for (int v : in.requiredVertices) out.requiredVertices.push_back(find(v, "required vertex"));
  for (const auto& e : in.requiredEdges)
    out.requiredEdges.push_back({find(e[0], "required edge end"), find(e[1], "required edge end")});
}

}  // namespace

bool needsSubdomains(const Mesh2& mesh) {
  const std::vector<char> lip = lipVertices(mesh);
  if (std::find(lip.begin(), lip.end(), 1) != lip.end()) return true;
  if (!mesh.interfaceEdges.empty() || !mesh.corners.empty() || !mesh.requiredVertices.empty() ||
      !mesh.requiredEdges.empty() || !mesh.ridges.empty())
    return true;
  return std::adjacent_find(mesh.triangleRefs.begin(), mesh.triangleRefs.end(), std::not_equal_to<>()) !=
         mesh.triangleRefs.end();
}

void remeshSubdomains(const Mesh2& input, const MetricField& field, const mesher::MeshOptions& options,
                      const std::string& name, RemeshResult& out) {
  for (const auto* edges : {&input.boundaryEdges, &input.interfaceEdges})
    for (const auto& e : *edges)
      ABLMG_REQUIRE(e.ref != kCutRef, name << ": edge (" << e.a + 1 << ", " << e.b + 1 << ") has ref " << e.ref
                                           << ", which is reserved (the remesher's cuts at slit tips)");
  Mesh2 cutMesh;
  const std::vector<char> lip = lipVertices(input);
  const bool slits = std::find(lip.begin(), lip.end(), 1) != lip.end();
  if (slits) {
    cutMesh = input;
    cutSlits(cutMesh, name);
  }
  const Mesh2& mesh = slits ? cutMesh : input;
  MeshSubdomains sub = subdomainsFromMesh(mesh, name);
  std::unordered_map<std::uint64_t, char> required;
  for (const auto& e : mesh.requiredEdges) required[undirected(e[0], e[1])] = 1;
  Curves curves = interfaceCurves(mesh, sub.junction);
  for (auto& c : curves.list) discretize(c, mesh, field, required);
  std::vector<mesher::MeshResult> parts;
  std::vector<int> refs;
  for (const auto& r : sub.regions) {
    Domain d;
    try {
      d = regionDomain(r, mesh, sub.junction, curves, required);
    } catch (const InputError& e) { throw InputError(name + ": subdomain " + std::to_string(r.ref) + ": " + e.what()); }
    parts.push_back(mesher::meshDomain(d, field, options));
    refs.push_back(r.ref);
    if (parts.size() == 1)
      out.stats = parts.back().stats;
    else
      mesher::addPartStats(out.stats, parts.back().stats);
  }
  glue(parts, refs, curves, out);
  mapFeatures(mesh, out.mesh, name);
  out.mesh.requireValid(name + ": glued subdomains");
}

}  // namespace ablmg::adapt
