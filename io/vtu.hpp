#pragma once
/// VTK XML unstructured grid (.vtu) output through vtkXMLUnstructuredGridWriter (binary,
/// appended, zlib-compressed), written atomically (temporary file + rename). Open in ParaView.
///
/// Fields: `values` is point- or cell-major: values[i * components + c] for entity i.
/// Point fields need values.size() == numVertices × components; cell fields numTriangles ×
/// components (checked: ablmg::InputError naming the field). Typical fields:
///   metricTensorField(...)  "metric" with 3 components m11 m12 m22, plus "h1", "h2", "angle";
///   a P1 solution "u" (1 component); per-triangle "quality" or "error".
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace ablmg::io {

struct Field {
  std::string name;
  int components = 1;          ///< 1 = scalar; 3 for (m11, m12, m22), etc.
  std::vector<double> values;  ///< entity-major, size = entities × components
};

/// 2D mesh (z = 0) with point and cell fields. Vertex and triangle refs are added as the cell
/// field "ref" and point field "vertexRef" when present.
void writeVtu(const std::string& path, const Mesh2& mesh, const std::vector<Field>& pointData = {},
              const std::vector<Field>& cellData = {});

/// 3D triangles (surfaces) with point and cell fields.
void writeVtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<int, 3>>& triangles, const std::vector<Field>& pointData = {},
              const std::vector<Field>& cellData = {});

/// Point fields describing per-vertex metrics: "metric" (m11, m12, m22), "h1", "h2" (sizes,
/// h1 ≥ h2) and "angle" (θ of the h1 direction, radians in [0, π)).
std::vector<Field> metricFields(std::span<const Metric2> metrics);

}  // namespace ablmg::io
