#pragma once
/// The output files of `ablmg mesh` (-o and the config's "outputs"): medit, VTK or a picture,
/// chosen by the extension. Kept apart from cli/config.hpp because it is the one part of the
/// mesh command that needs VTK and cairo: the light `ablmg` front end (cli/CMakeLists.txt)
/// links config.cpp but not this file.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include "ablmg/io/vtu.hpp"

#include <span>
#include <string>
#include <vector>

namespace ablmg::cli {

/// Writes one output of a meshing run, the format chosen by the extension of `path`:
///  .mesh → medit mesh, plus the metric as a tensor .sol beside it (same name, .sol);
///  .vtu  → VTK with point fields metric (m11 m12 m22), h1, h2, angle and the qualityFields;
///  .png  → bubbles (paper §3: the unit-metric ellipse of each vertex scaled by 1/2) over the
///          mesh edges and the domain boundary.
/// A mesh without triangles (bubbles only) is written as points. Atomic; throws InputError for
/// an unknown extension (before anything is written if called through checkOutputPath first).
void writeMeshOutput(const std::string& path, const Domain& domain, const Mesh2& mesh,
                     const std::vector<Metric2>& metric);
/// The fields that colour a mesh by how well it follows its metric (for ParaView): cell
/// "quality" (q of mesher/quality.hpp, 1 = unit equilateral) and point "edge_length_min" /
/// "edge_length_max" (the shortest and longest metric length, eq. (3), of the edges at the
/// vertex; the target is 1, [1/√2, √2] the usual band). metric.size() == numVertices().
struct QualityFields {
  std::vector<io::Field> point, cell;
};
QualityFields qualityFields(const Mesh2& mesh, std::span<const Metric2> metric);

/// Throws InputError unless `path` ends in .mesh, .vtu or .png (`what` names the flag or key).
void checkOutputPath(const std::string& path, const std::string& what);

}  // namespace ablmg::cli
