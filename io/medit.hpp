#pragma once
/// medit ASCII .mesh / .sol files (the format of MMG, FreeFem++, Gmsh "medit" export).
///
/// Reading (`.mesh`): `MeshVersionFormatted` 0, 1 or 2, `Dimension` 2 (or 3 when every z is 0),
/// `Vertices` (x y [z] ref), `Edges` (a b ref), `Triangles` (a b c ref), `Corners` and
/// `RequiredVertices` (vertex indices), `RequiredEdges` and `Ridges` (indices into Edges),
/// `End`. Keywords are case-insensitive, `#` starts a comment, and other sections (Normals,
/// Tangents, Quadrilaterals, FreeFem's Identifier, ...) are skipped. Indices in files are
/// 1-based; Mesh2 is 0-based. Clockwise triangles are reoriented counter-clockwise.
/// Edges are read as MMG reads them: the list may be partial or absent.
///  - an edge in one triangle → Mesh2::boundaryEdges, oriented with the domain on its left;
///    boundary edges the file does not list are added with ref 0;
///  - an edge in two triangles → Mesh2::interfaceEdges (a marked interior line); edges between
///    triangles of different refs (subdomains) that the file does not list are added, ref 0;
///  - repeated edges (either direction) and repeated triangles (any vertex order) are merged,
///    the first kept; an edge in no triangle is an error.
/// A file without triangles (a boundary discretization, to be meshed) keeps its Edges as given
/// (repeats merged). Each repair is reported in MeshFile::warnings (the library prints
/// nothing). The result is not validated (call Mesh2::validate / requireValid if needed).
///
/// Reading (`.sol`): `SolAtVertices`, N, then "nsol type..." and per vertex the nsol fields'
/// values; type 1 = scalar size h → Metric2::isotropic(h), type 2 = vector (skipped), type 3 =
/// symmetric tensor m11 m12 m22 (MMG order; in Dimension 3 m11 m12 m13 m22 m23 m33 with
/// m13 = m23 = 0). The field read: `field` (1-based) if given, else the one tensor field if
/// there is exactly one, else the first field. An optional `Dimension` line (FreeFem writes
/// one) defaults to 2.
///
/// Every error is an ablmg::InputError "<file>:<line>: <problem>" (truncated file, non-finite
/// number, index out of range, non-positive size, non-SPD tensor, count mismatch). Garbage
/// input throws, never crashes.
///
/// Writing: `MeshVersionFormatted 2`, `Dimension 2` (or 3 for surfaces), each double in the
/// shortest form that reads back to the same bits (std::to_chars: 0.1, 1e-300, 0.3333333333333333),
/// atomically (temporary file + rename), readable by MMG, FreeFem++ and Gmsh.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace ablmg::io {

/// A mesh as read, and what the reader repaired on the way ("<file>: 3 repeated edges merged").
struct MeshFile {
  Mesh2 mesh;
  std::vector<std::string> warnings;
};
/// Reads a 2D medit mesh. Throws InputError naming file:line.
MeshFile readMeshFile(const std::string& path);
/// Same, from text in memory; `name` is used in messages (for tests and fuzzing).
MeshFile parseMeshFile(const std::string& text, const std::string& name);
/// readMeshFile(path).mesh (the warnings dropped).
Mesh2 readMesh(const std::string& path);
Mesh2 parseMesh(const std::string& text, const std::string& name);

/// A .mesh file's vertices in 3D (z = 0 in Dimension 2) and its triangles, in the file's
/// orientation (not reoriented, not validated); other sections are read and dropped.
struct SurfaceMeshFile {
  int dimension = 2;  ///< the file's Dimension
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangleRefs;
};
/// Reads a medit mesh of Dimension 2 or 3 (any z), e.g. a surface written by writeSurfaceMesh.
/// Same errors as readMesh.
SurfaceMeshFile readSurfaceMesh(const std::string& path);
SurfaceMeshFile parseSurfaceMesh(const std::string& text, const std::string& name);

/// Reads per-vertex metrics. If expectedVertices ≥ 0 the count must match (error names both).
/// `field` ≥ 1 picks that field of a multi-field file (it must be of type 1 or 3); 0 = default
/// (see above).
std::vector<Metric2> readSol(const std::string& path, int expectedVertices = -1, int field = 0);
std::vector<Metric2> parseSol(const std::string& text, const std::string& name, int expectedVertices = -1,
                              int field = 0);

/// Writes Vertices (with vertexRefs or 0), Edges (boundaryEdges, then interfaceEdges, with
/// refs), Triangles (refs or 0), and Corners, RequiredVertices, RequiredEdges, Ridges when
/// the mesh has any (RequiredEdges and Ridges that are not among the written edges are added
/// to Edges, with ref 0).
void writeMesh(const std::string& path, const Mesh2& mesh);
/// Surface mesh: Dimension 3, Vertices (x y z 0), Triangles (refs or 0).
void writeSurfaceMesh(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& triangleRefs = {});
/// Tensor .sol (type 3, m11 m12 m22), one per vertex.
void writeSol(const std::string& path, std::span<const Metric2> metrics);
/// writeMesh then writeSol (same files), the two formatted and streamed in parallel (two
/// threads; the text goes out in blocks, never held whole). The .sol is renamed into place
/// only after the .mesh: if the .mesh fails the old .sol is untouched; if the .sol cannot be
/// written the new .mesh is removed again.
void writeMeshAndSol(const std::string& meshPath, const Mesh2& mesh, const std::string& solPath,
                     std::span<const Metric2> metrics);
/// Scalar .sol (type 1), one value per vertex (e.g. sizes h, or a P1 solution).
void writeScalarSol(const std::string& path, std::span<const double> values);

}  // namespace ablmg::io
