// meshDomainWithRegions (remesh.hpp): a domain with tagged polygonal regions, meshed as
// subdomains from a first triangulation of its loops and the regions' polygons.
#include "ablmg/adapt/boundary_mesh.hpp"
#include "ablmg/adapt/remesh.hpp"

#include "ablmg/core/error.hpp"

#include <cstdint>
#include <map>

namespace ablmg::adapt {
namespace {

std::uint64_t edgeKey(int a, int b) {
  return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
}

/// The domain's loops, then the regions', as a boundary-only mesh (vertices loop by loop, so
/// triangulateBoundary numbers the loops in this order: ref 1 + loop index).
Mesh2 loopsMesh(const Domain& domain, const std::vector<TaggedRegion>& regions) {
  Mesh2 m;
  const auto add = [&m](const std::vector<Vec2>& pts, const std::vector<int>& tags, int tag) {
    const int base = m.numVertices();
    const int n = int(pts.size());
    m.vertices.insert(m.vertices.end(), pts.begin(), pts.end());
    for (int k = 0; k < n; ++k)
      m.boundaryEdges.push_back({base + k, base + (k + 1) % n, tags.empty() ? tag : tags[std::size_t(k)]});
  };
  for (const auto& l : domain.loops()) add(l.points, l.tags, 1);
  for (const auto& r : regions) add(r.points, {}, r.tag);
  return m;
}

}  // namespace

mesher::MeshResult meshDomainWithRegions(const Domain& domain, const std::vector<TaggedRegion>& regions,
                                         const MetricField& field, const mesher::MeshOptions& options,
                                         const std::string& name) {
  ABLMG_REQUIRE(!domain.hasSlits(), name << ": regions in a domain with slits are not supported");
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const auto& r = regions[i];
    ABLMG_REQUIRE(r.tag >= 1,
                  name << ": regions[" << i << "]: tag must be >= 1 (0 is the rest of the domain), got " << r.tag);
    ABLMG_REQUIRE(r.points.size() >= 3, name << ": regions[" << i << "]: needs >= 3 points, got " << r.points.size());
    for (std::size_t k = 0; k < r.points.size(); ++k)
      ABLMG_REQUIRE(std::isfinite(r.points[k].x()) && std::isfinite(r.points[k].y()) && domain.contains(r.points[k]),
                    name << ": regions[" << i << "]: point " << k << " (" << r.points[k].x() << ", " << r.points[k].y()
                         << ") is not inside the domain");
  }
  const Mesh2 loops = loopsMesh(domain, regions);
  BoundaryTriangulation t;
  try {
    t = triangulateBoundary(loops, name, InteriorLoops::Subdomains);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (vertices numbered over the domain's loops, then the regions')");
  }
  // Refs: loop 0 (the outer loop) → 0, the holes' insides dropped, region k → its tag.
  const int holes = int(domain.loops().size()) - 1;
  std::map<std::uint64_t, int> edgeRef, count;
  for (const auto& e : loops.boundaryEdges) edgeRef[edgeKey(e.a, e.b)] = e.ref;  // no vertex dropped: same ids
  Mesh2 m;
  m.vertices = t.mesh.vertices;
  for (int k = 0; k < t.mesh.numTriangles(); ++k) {
    const int loop = t.mesh.triangleRefs[std::size_t(k)] - 1;
    if (loop >= 1 && loop <= holes) continue;
    m.triangles.push_back(t.mesh.triangles[std::size_t(k)]);
    m.triangleRefs.push_back(loop == 0 ? 0 : regions[std::size_t(loop - 1 - holes)].tag);
  }
  std::map<std::uint64_t, std::vector<std::pair<int, int>>> sides;  // edge → (triangle, local k)
  for (int k = 0; k < m.numTriangles(); ++k)
    for (int j = 0; j < 3; ++j) {
      const auto& tr = m.triangles[std::size_t(k)];
      sides[edgeKey(tr[std::size_t((j + 1) % 3)], tr[std::size_t((j + 2) % 3)])].emplace_back(k, j);
    }
  for (const auto& [key, s] : sides) {
    const auto& tr = m.triangles[std::size_t(s[0].first)];
    const int a = tr[std::size_t((s[0].second + 1) % 3)], b = tr[std::size_t((s[0].second + 2) % 3)];
    if (s.size() == 1)
      m.boundaryEdges.push_back({a, b, edgeRef.at(key)});
    else if (m.triangleRefs[std::size_t(s[0].first)] != m.triangleRefs[std::size_t(s[1].first)])
      m.interfaceEdges.push_back({std::min(a, b), std::max(a, b), edgeRef.at(key)});
  }
  m.requireValid(name + ": regions");
  RemeshResult r;
  remeshSubdomains(m, field, options, name, r);
  return {std::move(r.mesh), std::move(r.metric), r.stats};
}

}  // namespace ablmg::adapt
