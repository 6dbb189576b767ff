// The Python module `ablmg`: the mesher, the remesher of a solver's loop, the Hessian metric
// and the quality statistics on NumPy arrays (docs/python.md).
#include "module.hpp"

#include "ablmg/core/error.hpp"

PYBIND11_MODULE(ablmg, m) {
  namespace py = pybind11;
  py::options options;
  options.disable_function_signatures();  // each docstring starts with its own signature line
  m.doc() = R"(ablmg: anisotropic bubble-type mesh generation, and remeshing inside a solver's loop.

Arrays are NumPy: points (n, 2) float64, triangles (m, 3) integer (0-based, either
orientation on input; counter-clockwise on output), boundary edges (k, 2) integer with refs
(k,), metrics (n, 3) [m11, m12, m22] (SPD, edges of unit length have |e|_M = 1) or (n,) sizes
h (M = I/h^2). Results are read-only views into the C++ mesh (copy them to modify).

Functions: mesh (domain + metric field), uniform_mesh, remesh (mesh + per-vertex metric),
hessian_metric (P1 field -> metric of a target vertex count), transfer (P1 fields to a new
mesh: conservative projection or interpolation), quality (the statistics of
`ablmg stats`), read_mesh / write_mesh (medit .mesh/.sol), write_vtu, loglog_plot.
Classes: Mesh, Domain, MeshOptions.

Errors: ValueError for bad input (shape, NaN, non-SPD metric, invalid mesh, bad option),
naming the argument and the entry; TypeError for a wrong dtype; ablmg.Error (a ValueError)
when the mesher itself fails. The GIL is released while the C++ code runs, so other Python
threads keep running; a Python metric callable is called with the GIL, one call at a time.)";
  static py::exception<ablmg::Error> error(m, "Error", PyExc_ValueError);
  error.doc() = "The mesher failed on valid input (a subclass of ValueError).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ablmg::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const ablmg::Error& e) { PyErr_SetString(error.ptr(), e.what()); }
  });
  ablmg::python::bindMesh(m);
  ablmg::python::bindAdapt(m);
  ablmg::python::bindIo(m);
  ablmg::python::bindTransfer(m);
  m.attr("__version__") = ABLMG_VERSION;
}
