#pragma once
/// NumPy ↔ ablmg for the Python module: every array argument goes through one of these, which
/// check dtype (TypeError) and shape, range and finiteness (ValueError, naming the argument
/// and the offending entry), and every array result is a read-only view into the C++ object
/// that owns it (no copy).
///
/// Input arrays are read in place when they already have the dtype (float64 for coordinates
/// and metrics, any integer type for indices); other real dtypes are converted once. The one
/// copy made is into the C++ containers the library takes (Mesh2, std::vector<Metric2>).
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <vector>

namespace ablmg::python {

namespace py = pybind11;

/// (n, 2) real array → points (n ≥ 1; finite).
std::vector<Vec2> toPoints(py::handle obj, const char* name);
/// (m, 3) integer array → triangles with ids in [0, numVertices) (m ≥ 1).
std::vector<std::array<int, 3>> toTriangles(py::handle obj, const char* name, long numVertices);
/// (n,) real array of length `expected` (finite).
std::vector<double> toValues(py::handle obj, const char* name, long expected);
/// (n,) integer array of length `expected`.
std::vector<int> toInts(py::handle obj, const char* name, long expected);
/// (n, 3) [m11, m12, m22] tensors or (n,) sizes h (M = I/h²), n = `expected`; each SPD.
std::vector<Metric2> toMetrics(py::handle obj, const char* name, long expected);

/// A Mesh2 from arrays. Clockwise triangles are turned counter-clockwise (exact orientation
/// test). boundary_edges (k, 2) + boundary_refs (k,) (default: all 1) are oriented with the
/// mesh on their left; without them the boundary edges are the edges of one triangle, ref 1.
/// With `validate`, throws InputError "<what>: invalid mesh: ..." unless Mesh2::validate passes.
Mesh2 toMesh(py::handle points, py::handle triangles, py::handle boundaryEdges, py::handle boundaryRefs, bool validate,
             const char* what);

/// Read-only views sharing memory with `owner` (kept alive by the array).
py::array pointsView(const std::vector<Vec2>& points, py::handle owner);
py::array trianglesView(const std::vector<std::array<int, 3>>& triangles, py::handle owner);
py::array boundaryEdgesView(const std::vector<BoundaryEdge>& edges, py::handle owner);  ///< (k, 2)
py::array boundaryRefsView(const std::vector<BoundaryEdge>& edges, py::handle owner);   ///< (k,)
py::array metricsView(const std::vector<Metric2>& metrics, py::handle owner);           ///< (n, 3)
/// A NumPy array that owns `values` (moved into a capsule, no copy).
py::array ownedArray(std::vector<Metric2> metrics);

/// JSON → Python dict/list/float/... (the statistics have the keys of the CLI's JSON reports).
py::object toPython(const nlohmann::json& j);

}  // namespace ablmg::python
