// Fuzzes the medit .mesh reader (io/medit.hpp): parseMesh and parseSurfaceMesh on any bytes
// give an InputError or a mesh; a parsed mesh is then validated (validate() never throws), and a
// valid one goes on as `ablmg remesh` takes it: its boundary becomes a Domain (InputError or a
// domain of positive area) and points are located in it (a triangle of the mesh, barycentric
// weights summing to 1), and split into subdomains (InputError or at least one); a file of edges
// without triangles is triangulated inside its loops (boundary_mesh.hpp: InputError or a valid
// mesh, with holes or interfaces). Every InputError names the file ("fuzz:<line>: ...", the header's
// promise). Anything else (crash, sanitizer report, other exception) is a finding.
#include "ablmg/adapt/boundary_mesh.hpp"
#include "ablmg/core/domain_from_mesh.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/point_locator.hpp"
#include "ablmg/io/medit.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace {
/// The header's promise: every error is "<file>:<line>: <problem>" (or "<file>: <problem>").
void requireNamesFile(const ablmg::InputError& e) {
  if (std::string_view(e.what()).substr(0, 5) != "fuzz:") __builtin_trap();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const ablmg::io::SurfaceMeshFile f = ablmg::io::parseSurfaceMesh(text, "fuzz");
    for (const auto& t : f.triangles)
      for (int v : t)
        if (v < 0 || v >= int(f.vertices.size())) __builtin_trap();
  } catch (const ablmg::InputError& e) { requireNamesFile(e); }
  ablmg::Mesh2 mesh;
  try {
    mesh = ablmg::io::parseMesh(text, "fuzz");
  } catch (const ablmg::InputError& e) {
    requireNamesFile(e);
    return 0;
  }
  if (mesh.triangles.empty() && !mesh.boundaryEdges.empty() && mesh.boundaryEdges.size() <= 2000) {
    // a boundary discretization: its first mesh is valid, or an InputError naming the file
    for (auto mode : {ablmg::adapt::InteriorLoops::Holes, ablmg::adapt::InteriorLoops::Subdomains}) {
      try {
        const auto t = ablmg::adapt::triangulateBoundary(mesh, "fuzz", mode);
        if (!t.mesh.validate().ok || t.inputVertex.size() != t.mesh.vertices.size()) __builtin_trap();
      } catch (const ablmg::InputError& e) { requireNamesFile(e); }
    }
    return 0;
  }
  const ablmg::MeshValidation v = mesh.validate();
  if (!v.ok) return 0;
  try {
    const ablmg::Domain d = ablmg::domainFromMeshBoundary(mesh, "fuzz");
    if (!(d.area() > 0)) __builtin_trap();
  } catch (const ablmg::InputError& e) { requireNamesFile(e); }
  try {  // subdomains, interfaces and features (the sections remesh reads for them)
    const ablmg::MeshSubdomains sub = ablmg::subdomainsFromMesh(mesh, "fuzz");
    if (sub.regions.empty() || sub.junction.size() != mesh.vertices.size()) __builtin_trap();
  } catch (const ablmg::InputError& e) { requireNamesFile(e); }
  if (mesh.triangles.empty()) return 0;
  const ablmg::PointLocator locator(mesh);
  const ablmg::Vec2 probes[] = {
      mesh.vertices[0], (mesh.vertices[0] + mesh.vertices.back()) / 2, {0.5, 0.5}, {1e9, -1e9}};
  for (const auto& p : probes) {
    const auto loc = locator.locate(p);
    if (loc.triangle < 0 || loc.triangle >= mesh.numTriangles()) __builtin_trap();
    const double sum = loc.bary[0] + loc.bary[1] + loc.bary[2];
    if (!(std::abs(sum - 1) < 1e-6)) __builtin_trap();
  }
  return 0;
}
