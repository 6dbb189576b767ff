// ablmg.read_mesh, ablmg.write_mesh, ablmg.write_vtu, ablmg.loglog_plot.
#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "module.hpp"

#include <pybind11/stl.h>

#include <filesystem>
#include <optional>

namespace ablmg::python {
namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// {name: (entities,) or (entities, k) array} → VTK fields.
std::vector<io::Field> toFields(const py::object& data, long entities, const char* what) {
  std::vector<io::Field> out;
  if (data.is_none()) return out;
  for (const auto& [k, v] : py::dict(data)) {
    const std::string name = py::str(k);
    const std::string where = std::string(what) + "['" + name + "']";
    const py::array a = py::module_::import("numpy").attr("asarray")(v);
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
      throw py::type_error(where + ": expected a real array, got dtype " + std::string(py::str(a.dtype())));
    ABLMG_REQUIRE((a.ndim() == 1 || a.ndim() == 2) && a.shape(0) == entities,
                  where << ": expected " << entities << " rows, got an array of shape ndim " << a.ndim() << ", "
                        << (a.ndim() ? a.shape(0) : 0) << " rows");
    const int comps = a.ndim() == 1 ? 1 : int(a.shape(1));
    const auto flat = toValues(py::module_::import("numpy").attr("ravel")(a), where.c_str(), entities * comps);
    out.push_back({name, comps, flat});
  }
  return out;
}

}  // namespace

void bindIo(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::string& path, std::optional<std::string> sol) {
        PyMesh r;
        {
          py::gil_scoped_release release;
          r.mesh = io::readMesh(path);
          r.mesh.requireValid(path, std::nullopt, 1e-9, 1);  // the file's own (1-based) ids in errors
          if (sol) r.metric = io::readSol(*sol, r.mesh.numVertices());
        }
        return r;
      },
      R"(read_mesh(path, sol=None) -> Mesh

Reads a 2D medit .mesh (io/medit.hpp: MMG, FreeFem++, Gmsh and meshio write it) and, if `sol`
names one, its per-vertex metric (.sol: type 1 sizes or type 3 tensors m11 m12 m22). The mesh
must be valid (Mesh2::validate; boundary edges from its Edges section, with refs). Raises
ValueError "<file>:<line>: ..." for a malformed file, "<file>: invalid mesh: ..." otherwise.)",
      py::arg("path"), py::arg("sol") = py::none());

  m.def(
      "write_mesh",
      [](const std::string& path, const PyMesh& mesh, py::object sol) {
        ABLMG_REQUIRE(endsWith(path, ".mesh"), "write_mesh: '" << path << "' must end in .mesh");
        std::optional<std::string> solPath;
        if (py::isinstance<py::str>(sol))
          solPath = sol.cast<std::string>();
        else if (sol.is_none() && !mesh.metric.empty())
          solPath = std::filesystem::path(path).replace_extension(".sol").string();
        else
          ABLMG_REQUIRE(sol.is_none() || (py::isinstance<py::bool_>(sol) && !sol.cast<bool>()),
                        "write_mesh: sol must be a path, None or False");
        ABLMG_REQUIRE(!solPath || !mesh.metric.empty(), "write_mesh: sol given but the mesh has no metric");
        py::gil_scoped_release release;
        if (solPath)
          io::writeMeshAndSol(path, mesh.mesh, *solPath, mesh.metric);
        else
          io::writeMesh(path, mesh.mesh);
      },
      R"(write_mesh(path, mesh, sol=None)

Writes a Mesh as medit .mesh (Vertices, Edges with refs, Triangles; shortest round-trip
doubles; atomic: a temporary file renamed), and its metric as a tensor .sol: to `sol` if it is
a path, beside the mesh (same name, .sol) if sol is None and the mesh has a metric, not at all
if sol is False. The bytes are those `ablmg remesh` / `ablmg mesh` write.)",
      py::arg("path"), py::arg("mesh"), py::arg("sol") = py::none());

  m.def(
      "write_vtu",
      [](const std::string& path, const PyMesh& mesh, py::object pointData, py::object cellData) {
        ABLMG_REQUIRE(endsWith(path, ".vtu"), "write_vtu: '" << path << "' must end in .vtu");
        std::vector<io::Field> points = toFields(pointData, mesh.mesh.numVertices(), "point_data");
        const std::vector<io::Field> cells = toFields(cellData, mesh.mesh.numTriangles(), "cell_data");
        if (!mesh.metric.empty())
          for (auto& f : io::metricFields(mesh.metric)) points.push_back(std::move(f));
        py::gil_scoped_release release;
        io::writeVtu(path, mesh.mesh, points, cells);
      },
      R"(write_vtu(path, mesh, point_data=None, cell_data=None)

Writes a Mesh as a VTK XML unstructured grid (.vtu, through VTK's writer; ParaView, meshio):
triangles, the cell field "ref" when the mesh has triangle refs, the point fields of the
metric ("metric" m11 m12 m22, "h1", "h2", "angle") when it has one, and the given fields:
dicts {name: (n,) or (n, k) array} per vertex (point_data) or per triangle (cell_data).)",
      py::arg("path"), py::arg("mesh"), py::arg("point_data") = py::none(), py::arg("cell_data") = py::none());

  m.def(
      "loglog_plot",
      [](const std::string& path, py::dict curves, std::vector<double> slopes, const std::string& xlabel,
         const std::string& ylabel, const std::string& title) {
        ABLMG_REQUIRE(endsWith(path, ".png"), "loglog_plot: '" << path << "' must end in .png");
        std::vector<io::Curve> cs;
        for (const auto& [k, v] : curves) {
          const std::string name = py::str(k);
          const py::sequence xy = py::reinterpret_borrow<py::sequence>(v);
          ABLMG_REQUIRE(xy.size() == 2, "loglog_plot: curve '" << name << "' must be (x, y)");
          const py::array x = py::module_::import("numpy").attr("asarray")(xy[0]);
          const long n = long(x.size());
          io::Curve c{name, toValues(x, ("curve '" + name + "' x").c_str(), n),
                      toValues(xy[1], ("curve '" + name + "' y").c_str(), n)};
          for (long i = 0; i < n; ++i)
            ABLMG_REQUIRE(c.x[std::size_t(i)] > 0 && c.y[std::size_t(i)] > 0,
                          "loglog_plot: curve '" << name << "' has a value <= 0 at " << i);
          cs.push_back(std::move(c));
        }
        ABLMG_REQUIRE(!cs.empty(), "loglog_plot: no curves");
        py::gil_scoped_release release;
        io::drawLogLogPlot(path, cs, slopes, xlabel, ylabel, title);
      },
      R"(loglog_plot(path, curves, slopes=(), xlabel='N', ylabel='error', title='')

A log-log PNG (cairo, io/picture.hpp; the plots of `ablmg adapt`): curves = {name: (x, y)}
with positive values, markers and a legend, and a dashed reference line per slope.)",
      py::arg("path"), py::arg("curves"), py::arg("slopes") = std::vector<double>{}, py::arg("xlabel") = "N",
      py::arg("ylabel") = "error", py::arg("title") = "");
}

}  // namespace ablmg::python
