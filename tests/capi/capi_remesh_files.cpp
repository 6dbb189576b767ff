// capi_remesh_files IN.mesh IN.sol OUT.mesh [-hgrad G]: a caller of the C interface reads a
// medit pair into arrays (io::readMesh, io::readSol), remeshes through ablmg.h only, and
// writes the result (+ OUT.sol) as `ablmg remesh` does (io::writeMeshAndSol). capi.cmake
// compares the files with the command's, byte for byte. Exit 1 with the message on failure.
#include "ablmg/capi/ablmg.h"
#include "ablmg/io/medit.hpp"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4 && !(argc == 6 && !std::strcmp(argv[4], "-hgrad"))) {
    std::cerr << "usage: capi_remesh_files IN.mesh IN.sol OUT.mesh [-hgrad G]\n";
    return 2;
  }
  try {
    const ablmg::Mesh2 mesh = ablmg::io::readMesh(argv[1]);
    const auto metric = ablmg::io::readSol(argv[2], mesh.numVertices());
    std::vector<double> xy, m;
    std::vector<int> vrefs, tri, trefs, edges, erefs;
    for (int i = 0; i < mesh.numVertices(); ++i) {
      xy.push_back(mesh.vertices[std::size_t(i)].x());
      xy.push_back(mesh.vertices[std::size_t(i)].y());
      vrefs.push_back(mesh.vertexRefs.empty() ? 0 : mesh.vertexRefs[std::size_t(i)]);
      m.insert(m.end(), {metric[std::size_t(i)].m11(), metric[std::size_t(i)].m12(), metric[std::size_t(i)].m22()});
    }
    for (int t = 0; t < mesh.numTriangles(); ++t) {
      for (int v : mesh.triangles[std::size_t(t)]) tri.push_back(v + 1);
      trefs.push_back(mesh.triangleRefs.empty() ? 0 : mesh.triangleRefs[std::size_t(t)]);
    }
    for (const auto& e : mesh.boundaryEdges) edges.insert(edges.end(), {e.a + 1, e.b + 1}), erefs.push_back(e.ref);
    ablmg_t* h = ablmg_create();
    int rc = ablmg_set_vertices(h, xy.data(), vrefs.data(), mesh.numVertices());
    if (!rc) rc = ablmg_set_triangles(h, tri.data(), trefs.data(), mesh.numTriangles(), 1);
    if (!rc) rc = ablmg_set_edges(h, edges.data(), erefs.data(), int(erefs.size()), 1);
    if (!rc) rc = ablmg_set_metric(h, m.data(), mesh.numVertices());
    if (!rc && argc == 6) rc = ablmg_set_double(h, ABLMG_HGRAD, std::atof(argv[5]));
    if (!rc) rc = ablmg_remesh(h);
    int nv = 0, nt = 0, ne = 0;
    if (!rc) rc = ablmg_get_sizes(h, &nv, &nt, &ne);
    std::vector<double> oxy(2 * std::size_t(nv)), om(3 * std::size_t(nv));
    std::vector<int> ovrefs(static_cast<std::size_t>(nv)), otri(3 * std::size_t(nt)),
        otrefs(static_cast<std::size_t>(nt)), oedges(2 * std::size_t(ne)), oerefs(static_cast<std::size_t>(ne));
    if (!rc) rc = ablmg_get_vertices(h, oxy.data(), ovrefs.data(), nv);
    if (!rc) rc = ablmg_get_triangles(h, otri.data(), otrefs.data(), nt, 0);
    if (!rc) rc = ablmg_get_edges(h, oedges.data(), oerefs.data(), ne, 0);
    if (!rc) rc = ablmg_get_metric(h, om.data(), nv);
    if (rc) {
      std::cerr << "capi_remesh_files: " << ablmg_last_error(h) << " (status " << rc << ")\n";
      ablmg_free(h);
      return 1;
    }
    ablmg_free(h);
    ablmg::Mesh2 out;
    std::vector<ablmg::Metric2> outMetric;
    for (int i = 0; i < nv; ++i) {
      out.vertices.emplace_back(oxy[2 * std::size_t(i)], oxy[2 * std::size_t(i) + 1]);
      out.vertexRefs.push_back(ovrefs[std::size_t(i)]);
      outMetric.push_back(
          ablmg::Metric2::raw(om[3 * std::size_t(i)], om[3 * std::size_t(i) + 1], om[3 * std::size_t(i) + 2]));
    }
    for (int t = 0; t < nt; ++t) {
      out.triangles.push_back({otri[3 * std::size_t(t)], otri[3 * std::size_t(t) + 1], otri[3 * std::size_t(t) + 2]});
      out.triangleRefs.push_back(otrefs[std::size_t(t)]);
    }
    for (int e = 0; e < ne; ++e)
      out.boundaryEdges.push_back({oedges[2 * std::size_t(e)], oedges[2 * std::size_t(e) + 1], oerefs[std::size_t(e)]});
    const std::string outSol = std::filesystem::path(argv[3]).replace_extension(".sol").string();
    ablmg::io::writeMeshAndSol(argv[3], out, outSol, outMetric);
  } catch (const std::exception& e) {
    std::cerr << "capi_remesh_files: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
