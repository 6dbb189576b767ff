// ablmg.transfer: P1 fields from one mesh to another (adapt/transfer.hpp).
#include "ablmg/adapt/transfer.hpp"
#include "ablmg/core/error.hpp"
#include "module.hpp"

#include <pybind11/stl.h>

namespace ablmg::python {
namespace {

const char* kTransferDoc = R"(transfer(old_points, old_triangles, new_points, new_triangles, fields, *,
         method='projection', bound_preserving=False) -> array or list of arrays

P1 fields (one value per old vertex) carried to the new mesh of the same domain, as the
unsteady loop of `ablmg transient` does after each remesh (adapt/transfer.hpp):
  method 'projection'     conservative L2 projection on the supermesh of the two meshes:
                          the integral of each field is kept to round-off (polygonal
                          domains) and linear fields are reproduced;
         'interpolation'  the old field at each new vertex (exact for linear fields; new
                          vertices outside the old mesh take the closest old boundary value).
  bound_preserving        projection only: values clipped to the old field's [min, max], the
                          clipped mass given back where there is room.

  old_points, old_triangles, new_points, new_triangles  two valid meshes (arrays as for remesh)
  fields   one (n_old,) float64 array, or a list of them (transferred together)
Returns a (n_new,) array, or a list of them in the order given. Raises ValueError for an
invalid mesh, a field of the wrong size or with a NaN, an unknown method. The GIL is released
while computing.)";

}  // namespace

void bindTransfer(py::module_& m) {
  m.def(
      "transfer",
      [](py::handle oldPoints, py::handle oldTriangles, py::handle newPoints, py::handle newTriangles,
         py::handle fields, const std::string& method, bool boundPreserving) {
        const Mesh2 from = toMesh(oldPoints, oldTriangles, py::none(), py::none(), true, "transfer: old mesh");
        const Mesh2 to = toMesh(newPoints, newTriangles, py::none(), py::none(), true, "transfer: new mesh");
        const bool many = py::isinstance<py::list>(fields) || py::isinstance<py::tuple>(fields);
        std::vector<Eigen::VectorXd> in;
        const auto add = [&](py::handle f) {
          const std::vector<double> v = toValues(f, "fields", from.numVertices());
          in.emplace_back(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
        };
        if (many)
          for (py::handle f : fields) add(f);
        else
          add(fields);
        adapt::TransferOptions o;
        o.method = adapt::parseTransferMethod(method);
        o.boundPreserving = boundPreserving;
        std::vector<Eigen::VectorXd> out;
        {
          py::gil_scoped_release release;
          out = adapt::transferFields(from, to, in, o);
        }
        py::list result;
        for (const auto& v : out) result.append(py::array_t<double>(py::ssize_t(v.size()), v.data()));
        return many ? py::object(result) : py::object(result[0]);
      },
      kTransferDoc, py::arg("old_points"), py::arg("old_triangles"), py::arg("new_points"), py::arg("new_triangles"),
      py::arg("fields"), py::kw_only(), py::arg("method") = "projection", py::arg("bound_preserving") = false);
}

}  // namespace ablmg::python
