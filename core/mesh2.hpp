#pragma once
/// Mesh2: a 2D triangle mesh — vertices, counter-clockwise triangles, tagged boundary edges.
///
/// Invariants of a mesh that passed validate() (every mesh the library returns has):
///  - every triangle is counter-clockwise with positive area (exact orientation test);
///  - every interior edge lies in exactly two triangles, with opposite orientations;
///  - the edges lying in one triangle are exactly `boundaryEdges` (each once), so the
///    boundary is closed and the mesh covers its domain once: no gaps, no overlaps;
///  - every vertex is used by a triangle; coordinates are finite;
///  - `interfaceEdges` are interior edges (each in two triangles, listed once, none a boundary
///    edge), and every edge between two triangles of different `triangleRefs` is one of them:
///    the internal boundaries between subdomains (material interfaces) and interior edges a
///    file marked (a medit `Edges` entry inside the domain);
///  - `corners`, `requiredVertices`, `requiredEdges`, `ridges` name existing vertices / edges.
/// Subdomain k is the set of triangles with triangleRefs == k (0 for all if empty).
/// Ids are 0-based int; files (medit) are 1-based and io/ converts.
#include "ablmg/core/vec2.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace ablmg {

struct BoundaryEdge {
  int a, b;     ///< vertex ids; for a validated mesh, a→b runs with the domain on its left
  int ref = 1;  ///< reference tag of the domain segment it lies on
};

struct MeshValidation {
  bool ok = true;
  std::string firstProblem;  ///< empty when ok; else names the triangle/edge/vertex and why
  long invertedTriangles = 0, nonManifoldEdges = 0, openEdges = 0, unusedVertices = 0;
  double area = 0;  ///< sum of triangle areas
};

class Mesh2 {
 public:
  std::vector<Vec2> vertices;
  std::vector<int> vertexRefs;                ///< optional, one per vertex (0 if empty)
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise
  std::vector<int> triangleRefs;              ///< optional, one per triangle (0 if empty)
  std::vector<BoundaryEdge> boundaryEdges;
  /// Interior edges (in two triangles) that carry a ref: subdomain interfaces, marked lines.
  /// a→b in either direction.
  std::vector<BoundaryEdge> interfaceEdges;
  /// Features a remesh keeps (medit Corners, RequiredVertices, RequiredEdges, Ridges): vertex
  /// ids, and edges as vertex pairs (either order). Corners and required vertices stay mesh
  /// vertices at the same coordinates; a required edge stays an edge (no vertex inserted);
  /// a ridge's end vertices are kept as corners (the feature line is not cut by a chord).
  std::vector<int> corners, requiredVertices;
  std::vector<std::array<int, 2>> requiredEdges, ridges;

  int numVertices() const { return int(vertices.size()); }
  int numTriangles() const { return int(triangles.size()); }
  /// Sum of (signed) triangle areas.
  double area() const;
  double triangleArea(int t) const;

  /// Checks the invariants above. If `expectedArea` is given, the area must also match it to
  /// relative `areaTolerance`. Never throws; see requireValid() for the throwing form. The ids
  /// in firstProblem are printed plus `idBase` (1 for a mesh read from a 1-based medit file, so
  /// that the message names the file's own vertex and triangle numbers).
  MeshValidation validate(std::optional<double> expectedArea = std::nullopt, double areaTolerance = 1e-9,
                          int idBase = 0) const;
  /// validate() and throw ablmg::Error("<what>: invalid mesh: <firstProblem>") when it fails
  /// (with idBase 1: "invalid mesh (ids from 1, as in the file)").
  void requireValid(const std::string& what, std::optional<double> expectedArea = std::nullopt,
                    double areaTolerance = 1e-9, int idBase = 0) const;

  /// Unique undirected edges (a < b), sorted.
  std::vector<std::array<int, 2>> edges() const;
  /// For each triangle t and local edge k (opposite vertex k), the neighbour triangle or −1.
  std::vector<std::array<int, 3>> triangleNeighbours() const;
  /// Vertex → incident triangles, CSR: triangles of v are ids[offsets[v] .. offsets[v+1]).
  struct VertexTriangles {
    std::vector<int> offsets, ids;
  };
  VertexTriangles vertexTriangles() const;
};

}  // namespace ablmg
