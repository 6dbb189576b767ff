// ablmg.hessian_metric and ablmg.quality.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/mesher/quality.hpp"
#include "module.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>

namespace ablmg::python {
namespace {

const char* kHessianDoc = R"(hessian_metric(points, triangles, u, target_vertices, *, norm='l2', p=None,
               shape_blend=None, hmin=0.0, hmax=inf, max_anisotropy=1e4, hgrad=<loop's>,
               method='lsq') -> (n, 3) float64 [m11, m12, m22]

The metric for the next mesh from a P1 field u (one value per vertex), as the adaptive loop of
`ablmg adapt` computes it (adapt/adaptive_loop.hpp adaptMetric): recovered Hessians
(adapt/hessian_recovery.hpp), then the metric optimal for the interpolation error at the
complexity of `target_vertices` vertices (adapt/metric_from_hessian.hpp), then, if hgrad > 1,
size gradation (adapt/gradation.hpp) and a rescale back to that complexity.

  points, triangles  a valid mesh (arrays as for remesh; any vertex order, e.g. a solver's)
  u                  (n,) float64 nodal values, finite
  target_vertices    N: the complexity aimed at is (sqrt(3)/2) N (about N vertices), >= 10
  norm               'l2': optimal for the Lp norm of the error (M_p, Loseille-Alauzet);
                     'h1': for the W^{1,p} seminorm
  p                  the norm's exponent, >= 1 or inf; None: the loop's (inf with norm 'l2', 2 with
                     'h1': W^{1,inf} would crowd the vertices into a corner singularity)
  (every default is AdaptOptions' in adapt/adaptive_loop.hpp, i.e. `ablmg adapt`'s: the call
  with no options gives the metric of its loop; ablmg.ADAPT_DEFAULTS lists them)
  shape_blend        w in [0, 1]: the shape (|H|/sqrt(det|H|))^(1+w); None: the loop's (0.05, for
                     either norm); 0: the Lp shape; 1: the H1 shape
  hmin, hmax         size bounds; hmax = inf means a quarter of the bounding-box diagonal
  max_anisotropy     largest h1/h2 (>= 1)
  hgrad              <= 0: no gradation; > 1: gradation factor
  method             'lsq' (quadratic least-squares fit) or 'double' (recovered gradient,
                     recovered again)
Returns one metric per vertex of the given mesh, in its vertex order: pass it with the same
points/triangles to remesh. One default differs from the loop's: no saddle shape (`ablmg adapt
--saddle-shape 0`), which pays only with the per-vertex lattice rows the loop hands to its
mesher and remesh does not take. Raises ValueError for an invalid mesh, a NaN in u, a bad option.
The GIL is released while computing.)";

const char* kQualityDoc = R"(quality(points, triangles, metric=None, *, e=0.05) -> dict

The statistics of `ablmg stats MESH --sol METRIC --json` ("quality" there; mesher/quality.hpp):
edge metric lengths l (eq. 3 with the averaged tensor; min, mean, max, share in [1/sqrt2,
sqrt2] and within 10 %, the deviation histogram |l - 1| in bins of width e, paper Table 1),
element quality q = 4 sqrt(3) A_M / sum l^2 (1 = unit equilateral), Lee's alpha (eqs. 19-20),
and validity (Mesh2::validate: valid, first_problem).

  points, triangles  arrays as for remesh (the mesh need not be valid: the report says so)
  metric             (n, 3) tensors, (n,) sizes, or None for the identity (Euclidean lengths)
  e                  histogram bin width (> 0))";

}  // namespace

void bindAdapt(py::module_& m) {
  const adapt::AdaptOptions defaults;
  py::dict d;
  d["norm"] = adapt::toString(defaults.metric.norm);
  d["p"] = defaults.metric.p;
  d["hmin"] = defaults.metric.hmin;
  d["hmax"] = defaults.metric.hmax;
  d["max_anisotropy"] = defaults.metric.maxAnisotropy;
  if (defaults.metric.shapeBlend) d["shape_blend"] = *defaults.metric.shapeBlend;
  d["hgrad"] = defaults.hgrad;
  d["method"] = adapt::toString(defaults.hessian);
  m.attr("ADAPT_DEFAULTS") = d;
  m.def(
      "hessian_metric",
      [](py::handle points, py::handle triangles, py::handle u, double targetVertices, const std::string& norm,
         std::optional<double> p, std::optional<double> shapeBlend, double hmin, double hmax, double maxAnisotropy,
         double hgrad, const std::string& method) {
        const Mesh2 mesh = toMesh(points, triangles, py::none(), py::none(), true, "hessian_metric");
        const std::vector<double> values = toValues(u, "u", mesh.numVertices());
        adapt::AdaptOptions o;
        o.targetVertices = {targetVertices};
        o.hessian = adapt::parseHessianMethod(method);
        o.metric.norm = adapt::parseErrorNorm(norm);
        // None: the loop's (p = inf for the L2 norm; 2 for H1, the seminorm itself)
        if (p)
          o.metric.p = *p;
        else if (o.metric.norm == adapt::ErrorNorm::H1)
          o.metric.p = 2;
        // None: the loop's (AdaptOptions: its blend, for either norm, as `ablmg adapt`)
        if (shapeBlend) o.metric.shapeBlend = shapeBlend;
        o.metric.hmin = hmin;
        o.metric.hmax = hmax;
        o.metric.maxAnisotropy = maxAnisotropy;
        o.hgrad = hgrad;
        o.metric.saddleShape = 0;  // needs the per-vertex lattice rows, which remesh does not take
        adapt::validate(o);
        std::vector<Metric2> metric;
        {
          py::gil_scoped_release release;
          metric = adapt::adaptMetric(mesh, values, targetVertices, o).metric;
        }
        return ownedArray(std::move(metric));
      },
      kHessianDoc, py::arg("points"), py::arg("triangles"), py::arg("u"), py::arg("target_vertices"), py::kw_only(),
      py::arg("norm") = adapt::toString(defaults.metric.norm), py::arg("p") = py::none(),
      py::arg("shape_blend") = py::none(), py::arg("hmin") = defaults.metric.hmin,
      py::arg("hmax") = defaults.metric.hmax, py::arg("max_anisotropy") = defaults.metric.maxAnisotropy,
      py::arg("hgrad") = defaults.hgrad, py::arg("method") = adapt::toString(defaults.hessian));

  m.def(
      "quality",
      [](py::handle points, py::handle triangles, py::handle metric, double e) {
        const Mesh2 mesh = toMesh(points, triangles, py::none(), py::none(), false, "quality");
        const std::vector<Metric2> metrics = metric.is_none() ? std::vector<Metric2>(mesh.vertices.size())
                                                              : toMetrics(metric, "metric", mesh.numVertices());
        ABLMG_REQUIRE(std::isfinite(e) && e > 0, "quality: e must be positive, got " << e);
        mesher::MeshQuality q;
        {
          py::gil_scoped_release release;
          q = mesher::meshQuality(mesh, metrics, e);
        }
        return toPython(cli::qualityJson(q));
      },
      kQualityDoc, py::arg("points"), py::arg("triangles"), py::arg("metric") = py::none(), py::kw_only(),
      py::arg("e") = 0.05);
}

}  // namespace ablmg::python
