#pragma once
/// Shared by the files of the Python module: the Mesh result type and the binders.
#include "convert.hpp"

#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <vector>

namespace ablmg::python {

/// What ablmg.Mesh holds: a valid Mesh2, optionally one metric per vertex, and statistics.
/// Its arrays are read-only views into these vectors.
struct PyMesh {
  Mesh2 mesh;
  std::vector<Metric2> metric;  ///< empty: no metric
  py::dict stats;
};

void bindMesh(py::module_& m);      ///< Mesh, Domain, MeshOptions, mesh, uniform_mesh, remesh
void bindAdapt(py::module_& m);     ///< hessian_metric, quality
void bindIo(py::module_& m);        ///< read_mesh, write_mesh, write_vtu, loglog_plot
void bindTransfer(py::module_& m);  ///< transfer

}  // namespace ablmg::python
