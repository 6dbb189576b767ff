// ablmg.Mesh, ablmg.Domain, ablmg.MeshOptions; ablmg.mesh, ablmg.uniform_mesh, ablmg.remesh.
#include "ablmg/adapt/adaptive_loop.hpp"
#include "ablmg/adapt/remesh.hpp"
#include "ablmg/adapt/metric_snap.hpp"
#include "ablmg/cli/stats_json.hpp"
#include "ablmg/core/domain.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/fem/test_problems.hpp"
#include "ablmg/mesher/mesher.hpp"
#include "module.hpp"

#include <omp.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <exception>
#include <mutex>
#include <optional>

namespace ablmg::python {
namespace {

/// A metric given as a Python callable f(x, y) of two (n,) float64 arrays, returning (n, 3)
/// tensors [m11, m12, m22], (n,) sizes, a tuple (m11, m12, m22) of arrays or scalars, or one
/// scalar size. The mesher evaluates it in batches (every bubble at once). Each call takes a
/// mutex, then the GIL: Python is never entered by two threads at once, whichever thread of
/// the mesher calls. A Python exception propagates out of meshDomain as itself; if it ever
/// arose inside an OpenMP region (where C++ exceptions must not escape), it is kept, the
/// identity returned, and rethrown by rethrowIfFailed() once meshing is over.
class PythonMetricField final : public MetricField {
 public:
  /// Made and destroyed with the GIL held.
  explicit PythonMetricField(py::object f) : f_(std::move(f)) {}
  Metric2 at(const Vec2& p) const override {
    Metric2 m;
    evaluate(std::span<const Vec2>(&p, 1), std::span<Metric2>(&m, 1));
    return m;
  }
  void evaluate(std::span<const Vec2> points, std::span<Metric2> out) const override {
    std::lock_guard lock(mutex_);
    if (failure_) {
      std::fill(out.begin(), out.end(), Metric2());
      return;
    }
    try {
      py::gil_scoped_acquire gil;
      call(points, out);
    } catch (...) {
      if (!omp_in_parallel()) throw;
      failure_ = std::current_exception();
      std::fill(out.begin(), out.end(), Metric2());
    }
  }
  void rethrowIfFailed() const {
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  void call(std::span<const Vec2> points, std::span<Metric2> out) const {
    const py::ssize_t n = py::ssize_t(points.size());
    py::array_t<double> x(n), y(n);
    auto xs = x.mutable_unchecked<1>();
    auto ys = y.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) xs(i) = points[std::size_t(i)].x(), ys(i) = points[std::size_t(i)].y();
    const py::object result = f_(x, y);
    const auto where = [&](py::ssize_t i) {
      std::ostringstream os;
      os << "metric(x, y) at (" << points[std::size_t(i)].x() << ", " << points[std::size_t(i)].y() << ")";
      return os.str();
    };
    const py::module_ np = py::module_::import("numpy");
    if (py::isinstance<py::tuple>(result) || py::isinstance<py::list>(result)) {
      const py::sequence s = result;
      ABLMG_REQUIRE(s.size() == 3,
                    "metric(x, y): a tuple result must be (m11, m12, m22), got " << s.size() << " entries");
      py::array_t<double> c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = py::array_t<double, py::array::forcecast>::ensure(
            np.attr("broadcast_to")(np.attr("asarray")(s[std::size_t(k)], "float64"), py::make_tuple(n)));
      ABLMG_REQUIRE(c[0] && c[1] && c[2], "metric(x, y): tuple entries must broadcast to shape (" << n << ",)");
      for (py::ssize_t i = 0; i < n; ++i)
        out[std::size_t(i)] = Metric2::fromTensor(c[0].at(i), c[1].at(i), c[2].at(i), where(i));
      return;
    }
    const py::array a = np.attr("asarray")(result);
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
      throw py::type_error("metric(x, y): expected a real array, got dtype " + std::string(py::str(a.dtype())));
    const auto d = py::array_t<double, py::array::forcecast>::ensure(a);
    if (d.ndim() == 2 && d.shape(0) == n && d.shape(1) == 3) {
      const auto r = d.unchecked<2>();
      for (py::ssize_t i = 0; i < n; ++i)
        out[std::size_t(i)] = Metric2::fromTensor(r(i, 0), r(i, 1), r(i, 2), where(i));
      return;
    }
    ABLMG_REQUIRE(d.ndim() == 0 || (d.ndim() == 1 && d.shape(0) == n),
                  "metric(x, y): expected shape (" << n << ", 3), (" << n << ",) or a scalar, got ndim " << d.ndim());
    for (py::ssize_t i = 0; i < n; ++i) {
      const double h = d.ndim() == 0 ? *d.data() : d.at(i);
      ABLMG_REQUIRE(std::isfinite(h) && h > 0, where(i) << ": size " << h << " must be positive and finite");
      out[std::size_t(i)] = Metric2::fromSizes(h, h, 0.0, where(i));
    }
  }

  py::object f_;
  mutable std::mutex mutex_;
  mutable std::exception_ptr failure_;
};

/// A constant metric: a size h (float) or a tensor (m11, m12, m22).
std::optional<Metric2> constantMetric(const py::handle& metric) {
  if (py::isinstance<py::float_>(metric) || py::isinstance<py::int_>(metric)) {
    const double h = metric.cast<double>();
    ABLMG_REQUIRE(std::isfinite(h) && h > 0, "metric: size " << h << " must be positive and finite");
    return Metric2::isotropic(h);
  }
  if (PyCallable_Check(metric.ptr())) return std::nullopt;
  const auto v = toValues(metric, "metric", 3);
  return Metric2::fromTensor(v[0], v[1], v[2], "metric");
}

mesher::MeshOptions preset(const std::string& name) {
  ABLMG_REQUIRE(name == "mesh" || name == "remesh" || name == "adapt",
                "MeshOptions: preset must be 'mesh', 'remesh' or 'adapt', got '" << name << "'");
  return mesher::meshPreset(mesher::parseMeshPreset(name));
}

/// options (a MeshOptions or None → the preset), then the seed and lattice shortcuts.
mesher::MeshOptions resolveOptions(const std::optional<mesher::MeshOptions>& options, const char* presetName,
                                   std::optional<long long> seed, const std::optional<std::string>& lattice) {
  mesher::MeshOptions o = options ? *options : preset(presetName);
  if (seed) {
    ABLMG_REQUIRE(*seed >= 0, "seed must be >= 0, got " << *seed);
    o.placement.seed = std::uint64_t(*seed);
  }
  if (lattice) o.placement.lattice.orientation = mesher::parseLatticeOrientation(*lattice);
  return o;
}

py::object wrap(Mesh2 mesh, std::vector<Metric2> metric, nlohmann::json stats) {
  stats["vertices"] = mesh.numVertices();
  stats["triangles"] = mesh.numTriangles();
  PyMesh r{std::move(mesh), std::move(metric), py::dict(toPython(stats))};
  return py::cast(std::move(r));
}

BoundaryLoop toLoop(py::handle points, py::handle tags, bool smooth, const char* name) {
  BoundaryLoop loop;
  loop.points = toPoints(points, name);
  if (!tags.is_none()) loop.tags = toInts(tags, (std::string(name) + " tags").c_str(), long(loop.points.size()));
  loop.smooth = smooth;
  return loop;
}

py::array loopPoints(const BoundaryLoop& l) {
  py::array_t<double> a({py::ssize_t(l.points.size()), py::ssize_t(2)});
  auto r = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    r(i, 0) = l.points[std::size_t(i)].x(), r(i, 1) = l.points[std::size_t(i)].y();
  return a;
}

const char* kRemeshDoc = R"(remesh(points, triangles, metric, boundary_edges=None, boundary_refs=None, *,
       hmin=None, hmax=None, hgrad=None, seed=None, lattice=None, options=None, domain=None,
       metric_quantum=None) -> Mesh
remesh(mesh, metric=None, **same keywords) -> Mesh

Remeshes the domain covered by a triangle mesh so that edges have unit length in a
per-vertex metric: the call a solver makes between two solves (adapt/remesh.hpp; what
`ablmg remesh` runs between reading and writing files, with the same result bytes).

  points          (n, 2) float64 vertex coordinates
  triangles       (m, 3) integer vertex ids (0-based; clockwise ones are turned)
  metric          (n, 3) [m11, m12, m22] SPD tensors, or (n,) sizes h (M = I/h^2), per
                  vertex; interpolated log-Euclidean between vertices
  boundary_edges  (k, 2) integer: the boundary edges (each in one triangle), with
  boundary_refs   (k,) integer refs (default 1), kept on the new boundary. Without them the
                  boundary is the edges of one triangle, ref 1.
  hmin, hmax      clamp the sizes of the metric to [hmin, hmax] (defaults 0, inf)
  hgrad           size gradation beta > 1 on the input mesh after the clamp (default 1.3,
                  MMG's); <= 0 (e.g. -1): none
  seed            placement seed (default 0: no jitter; s > 0: another mesh of the same
                  statistics, the same for the same s); lattice: 'auto' (default), 'axes', 'short', 'long'
  options         a MeshOptions (default MeshOptions('remesh'))
  domain          a Domain the mesh covers (e.g. the exact polygon of the problem): meshed
                  instead of the domain rebuilt from the mesh's boundary loops; the metric is
                  then used as given (hmin, hmax, hgrad must stay None), as the adaptive loop
                  of `ablmg adapt` does.
  metric_quantum  > 0: the metric is first snapped to a grid of this step (log2 of its
                  eigenvalues, its angle; adapt/metric_snap.hpp), so that metrics differing
                  by round-off (e.g. the solutions of 1 and 2 MPI ranks) give the same mesh;
                  2**-8 changes the sizes by < 0.07 %. Default None: used as given.

The second form takes an ablmg.Mesh (e.g. from read_mesh) with everything it carries besides
the arrays (corners, required vertices and edges, ridges, interface edges of a medit file) and
its own metric unless one is given: what `ablmg remesh -in FILE` remeshes.

The domain is the mesh's boundary loops (one outer loop, holes) with their refs; corners (ref
changes, turns > 30 deg) are kept, other boundary nodes are placed anew. Returns a valid Mesh
whose metric is the (clamped, graded) metric interpolated at the new vertices and whose stats
are those of `ablmg remesh --report`. Same input and seed: the same mesh, bit for bit.
Raises ValueError for a bad shape, NaN, a non-SPD metric, an invalid mesh, an option out of
range; TypeError for a non-numeric dtype. The GIL is released while meshing.)";

const char* kMeshDoc =
    R"(mesh(domain, metric, *, seed=None, lattice=None, options=None, background_vertices=None) -> Mesh

Meshes a Domain so that edges have unit length in a metric field (mesher/mesher.hpp: bubble
placement, paper section 3; ABLMG connection, section 4; quality post-pass).

  domain   an ablmg.Domain (polygons: outer loop + holes, a ref per segment)
  metric   a size h (float: M = I/h^2), a tensor (m11, m12, m22), or a callable
           f(x, y) taking two (n,) float64 arrays and returning (n, 3) [m11, m12, m22], (n,)
           sizes, a tuple (m11, m12, m22) of arrays or scalars, or a scalar size. It is called
           on batches of points (vectorize it), with the GIL, never by two threads at once;
           an exception it raises propagates. Non-SPD or NaN values raise ValueError naming
           the point.
  seed, lattice, options   as for remesh (default MeshOptions('mesh'), `ablmg mesh`'s)
  background_vertices      with a callable: None calls it during meshing (exact values; the
           bubble dynamics evaluates whole batches, but the lattice growth and the quality
           post-pass ask for single points, one Python call each, which dominates when the
           post-pass has much to do). A number N instead samples it once, in one call, on
           the vertices of a uniform mesh of about N vertices, and meshes with that
           background (log-Euclidean interpolation, no Python during meshing): choose N so
           the background resolves the metric.

Returns a valid Mesh (boundary refs = the domain's segment tags, metric at the vertices,
stats as `ablmg mesh --report`). The GIL is released while meshing (retaken for callbacks).)";

}  // namespace

void bindMesh(py::module_& m) {
  py::class_<PyMesh>(m, "Mesh", R"(A valid triangle mesh (Mesh2): vertices, counter-clockwise triangles, boundary
edges with refs, optionally a metric per vertex, and the statistics of the run that made it.

Mesh(points, triangles, boundary_edges=None, boundary_refs=None, metric=None) builds one from
arrays (validated: ValueError names the first problem). The array attributes are read-only
views into the C++ mesh; np.array(mesh.points) copies.)")
      .def(py::init([](py::handle points, py::handle triangles, py::handle edges, py::handle refs, py::handle metric) {
             PyMesh r{toMesh(points, triangles, edges, refs, true, "Mesh"), {}, py::dict()};
             if (!metric.is_none()) r.metric = toMetrics(metric, "metric", r.mesh.numVertices());
             return r;
           }),
           py::arg("points"), py::arg("triangles"), py::arg("boundary_edges") = py::none(),
           py::arg("boundary_refs") = py::none(), py::arg("metric") = py::none())
      .def_property_readonly(
          "points", [](py::object self) { return pointsView(self.cast<PyMesh&>().mesh.vertices, self); },
          "(n, 2) float64 vertex coordinates")
      .def_property_readonly(
          "triangles", [](py::object self) { return trianglesView(self.cast<PyMesh&>().mesh.triangles, self); },
          "(m, 3) int32 vertex ids, counter-clockwise")
      .def_property_readonly(
          "boundary_edges",
          [](py::object self) { return boundaryEdgesView(self.cast<PyMesh&>().mesh.boundaryEdges, self); },
          "(k, 2) int32 boundary edges a -> b, the mesh on their left")
      .def_property_readonly(
          "boundary_refs",
          [](py::object self) { return boundaryRefsView(self.cast<PyMesh&>().mesh.boundaryEdges, self); },
          "(k,) int32 ref of each boundary edge (the domain segment's tag)")
      .def_property_readonly(
          "metric",
          [](py::object self) -> py::object {
            const auto& r = self.cast<PyMesh&>();
            if (r.metric.empty()) return py::none();
            return metricsView(r.metric, self);
          },
          "(n, 3) float64 [m11, m12, m22] per vertex (the metric the mesh was built for), or None")
      .def_property_readonly(
          "stats", [](const PyMesh& r) { return r.stats; },
          "dict: the mesher's statistics (the keys of the CLI's --report), vertices, triangles")
      .def_property_readonly("num_vertices", [](const PyMesh& r) { return r.mesh.numVertices(); })
      .def_property_readonly("num_triangles", [](const PyMesh& r) { return r.mesh.numTriangles(); })
      .def_property_readonly(
          "area", [](const PyMesh& r) { return r.mesh.area(); }, "sum of the triangle areas")
      .def("__repr__", [](const PyMesh& r) {
        return "<ablmg.Mesh: " + std::to_string(r.mesh.numVertices()) + " vertices, " +
               std::to_string(r.mesh.numTriangles()) + " triangles, " + std::to_string(r.mesh.boundaryEdges.size()) +
               " boundary edges" + (r.metric.empty() ? "" : ", metric") + ">";
      });

  py::class_<Domain>(m, "Domain", R"(A planar straight-line graph: an outer loop and holes, a ref (tag) per segment.

Domain(outer, holes=(), outer_tags=None, hole_tags=None, smooth=False)
  outer       (n, 2) float64 polygon (either orientation; made counter-clockwise)
  holes       sequence of (k, 2) polygons inside it (made clockwise)
  outer_tags  (n,) integer ref of each segment k (points[k] -> points[k+1]); default all 1
  hole_tags   sequence of (k,) integer refs, one per hole; default all 1
  smooth      the loops sample smooth curves: only corners (tag changes, turns > 30 deg)
              are fixed vertices, the mesher places its own boundary nodes along them
Raises ValueError naming the loop and segment (self-intersection, touching loops, repeated
points, wrong tag count, non-finite coordinates).)")
      .def(py::init([](py::handle outer, py::sequence holes, py::handle outerTags, py::object holeTags, bool smooth) {
             std::vector<BoundaryLoop> hs;
             const auto ht = holeTags.is_none() ? py::list() : py::list(holeTags);
             ABLMG_REQUIRE(ht.empty() || ht.size() == holes.size(),
                           "hole_tags: " << ht.size() << " tag arrays for " << holes.size() << " holes");
             for (std::size_t k = 0; k < holes.size(); ++k)
               hs.push_back(toLoop(holes[k], ht.empty() ? py::none() : py::object(ht[k]), smooth,
                                   ("holes[" + std::to_string(k) + "]").c_str()));
             return Domain(toLoop(outer, outerTags, smooth, "outer"), std::move(hs));
           }),
           py::arg("outer"), py::arg("holes") = py::list(), py::arg("outer_tags") = py::none(),
           py::arg("hole_tags") = py::none(), py::arg("smooth") = false)
      .def_static("rectangle", &Domain::rectangle, py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"),
                  "[x0, x1] x [y0, y1], tags 1 (bottom), 2 (right), 3 (top), 4 (left).")
      .def_static(
          "disk", [](double cx, double cy, double r, int samples) { return Domain::disk(Vec2(cx, cy), r, samples); },
          py::arg("cx"), py::arg("cy"), py::arg("radius"), py::arg("samples") = 2048,
          "Disk sampled by `samples` points on a smooth loop, tag 1.")
      .def_static(
          "problem", [](const std::string& name) { return fem::makeProblem(name).domain; }, py::arg("name"),
          "The domain of a library problem of `ablmg adapt --problem NAME` (fem/test_problems.hpp): "
          "'wavefront', 'peak', 'tanhlayer', ... the unit square (tags 1-4), 'lshape' (-1,1)^2 minus "
          "[0,1)x(-1,0] (tags 1-6 counter-clockwise from (0,0)->(1,0)).")
      .def_property_readonly("area", &Domain::area, "enclosed area (outer minus holes)")
      .def_property_readonly(
          "loops",
          [](const Domain& d) {
            py::list out;
            for (const auto& l : d.loops()) {
              std::vector<int> tags = l.tags.empty() ? std::vector<int>(l.points.size(), 1) : l.tags;
              out.append(
                  py::make_tuple(loopPoints(l), py::array_t<int>(py::ssize_t(tags.size()), tags.data()), l.smooth));
            }
            return out;
          },
          "list of (points (n, 2), tags (n,), smooth): [0] the outer loop (counter-clockwise), then the "
          "holes (clockwise)")
      .def("__repr__", [](const Domain& d) {
        return "<ablmg.Domain: " + std::to_string(d.loops().size()) + " loops, area " + std::to_string(d.area()) + ">";
      });

  py::class_<mesher::MeshOptions>(m, "MeshOptions",
                                  R"(The mesher's options (mesher/mesher.hpp, place_nodes.hpp, improve.hpp).

MeshOptions(preset='mesh', **fields): preset 'mesh' (meshDomain's defaults, `ablmg mesh`),
'remesh' (`ablmg remesh`: quality-plateau stop, no final relaxation), or 'adapt' (the
adaptive loop of `ablmg adapt`: plateau stop, lattice 'short', no defect annealing); then
any field below by keyword. Values are range-checked when a mesh is made.)")
      .def(py::init([](const std::string& name, py::kwargs kw) {
             mesher::MeshOptions o = preset(name);
             py::object self = py::cast(o);
             for (const auto& [k, v] : kw) {
               const std::string key = py::str(k);
               ABLMG_REQUIRE(py::hasattr(self, key.c_str()) && key[0] != '_',
                             "MeshOptions: unknown field '" << key << "'");
               self.attr(key.c_str()) = v;
             }
             return self.cast<mesher::MeshOptions>();
           }),
           py::arg("preset") = "mesh")
      .def_property(
          "seed", [](const mesher::MeshOptions& o) { return o.placement.seed; },
          [](mesher::MeshOptions& o, std::uint64_t s) { o.placement.seed = s; },
          "placement seed: 0 = the nodes as placed, s > 0 = jittered by (s, node) (same seed, same mesh)")
      .def_property(
          "lattice",
          [](const mesher::MeshOptions& o) {
            return std::string(mesher::latticeOrientationName(o.placement.lattice.orientation));
          },
          [](mesher::MeshOptions& o, const std::string& s) {
            o.placement.lattice.orientation = mesher::parseLatticeOrientation(s);
          },
          "orientation of the initial bubble lattice: 'auto', 'axes', 'short' or 'long'")
      .def_property(
          "plateau_steps", [](const mesher::MeshOptions& o) { return o.placement.plateauSteps; },
          [](mesher::MeshOptions& o, int v) { o.placement.plateauSteps = v; },
          "quality-plateau stop window in steps (0 = off)")
      .def_property(
          "plateau_gain", [](const mesher::MeshOptions& o) { return o.placement.plateauGain; },
          [](mesher::MeshOptions& o, double v) { o.placement.plateauGain = v; },
          "share gain that counts as progress for the plateau stop")
      .def_property(
          "final_relax_steps", [](const mesher::MeshOptions& o) { return o.placement.finalRelaxSteps; },
          [](mesher::MeshOptions& o, int v) { o.placement.finalRelaxSteps = v; },
          "steps without population edits after the last edit before an early stop")
      .def_property(
          "defect_passes", [](const mesher::MeshOptions& o) { return o.placement.defectPasses; },
          [](mesher::MeshOptions& o, int v) { o.placement.defectPasses = v; }, "defect-annealing passes (0 = off)")
      .def_property(
          "max_steps", [](const mesher::MeshOptions& o) { return o.placement.maxSteps; },
          [](mesher::MeshOptions& o, int v) { o.placement.maxSteps = v; }, "cap on bubble dynamics steps")
      .def_property(
          "max_nodes", [](const mesher::MeshOptions& o) { return o.placement.maxNodes; },
          [](mesher::MeshOptions& o, long v) { o.placement.maxNodes = v; },
          "refuse (ValueError) a metric asking for more nodes than this")
      .def_property(
          "threads", [](const mesher::MeshOptions& o) { return o.placement.threads; },
          [](mesher::MeshOptions& o, int v) { o.placement.threads = o.connect.threads = v; },
          "OpenMP threads (0 = default); the mesh does not depend on it")
      .def_property(
          "improve", [](const mesher::MeshOptions& o) { return o.improve.enabled; },
          [](mesher::MeshOptions& o, bool v) { o.improve.enabled = v; }, "run the quality post-pass")
      .def_property(
          "quality_threshold", [](const mesher::MeshOptions& o) { return o.improve.qThreshold; },
          [](mesher::MeshOptions& o, double v) { o.improve.qThreshold = v; },
          "the post-pass improves triangles with q below this, in (0, 1]")
      .def("__repr__", [](const mesher::MeshOptions& o) {
        std::ostringstream os;
        os << "<ablmg.MeshOptions seed=" << o.placement.seed
           << " lattice=" << mesher::latticeOrientationName(o.placement.lattice.orientation)
           << " plateau_steps=" << o.placement.plateauSteps << " plateau_gain=" << o.placement.plateauGain
           << " final_relax_steps=" << o.placement.finalRelaxSteps << " defect_passes=" << o.placement.defectPasses
           << ">";
        return os.str();
      });

  m.def(
      "mesh",
      [](const Domain& domain, py::object metric, std::optional<long long> seed, std::optional<std::string> lattice,
         std::optional<mesher::MeshOptions> options, std::optional<double> backgroundVertices) {
        const mesher::MeshOptions o = resolveOptions(options, "mesh", seed, lattice);
        mesher::MeshResult r;
        if (const auto c = constantMetric(metric)) {
          py::gil_scoped_release release;
          r = mesher::meshDomain(domain, ConstantMetricField(*c), o);
        } else if (backgroundVertices) {
          ABLMG_REQUIRE(*backgroundVertices >= 3 && *backgroundVertices <= 1e8,
                        "mesh: background_vertices must be in [3, 1e8], got " << *backgroundVertices);
          const PythonMetricField field(metric);
          mesher::MeshResult bg;
          {
            py::gil_scoped_release release;
            bg = adapt::uniformMesh(domain, *backgroundVertices, o);
          }
          std::vector<Metric2> values(bg.mesh.vertices.size());
          field.evaluate(bg.mesh.vertices, values);  // one call, with the GIL
          py::gil_scoped_release release;
          r = mesher::meshDomain(domain, BackgroundMetricField(std::move(bg.mesh), std::move(values)), o);
        } else {
          PythonMetricField field(metric);
          {
            py::gil_scoped_release release;
            r = mesher::meshDomain(domain, field, o);
          }
          field.rethrowIfFailed();
        }
        return wrap(std::move(r.mesh), std::move(r.metric), cli::meshStatsJson(r.stats));
      },
      kMeshDoc, py::arg("domain"), py::arg("metric"), py::kw_only(), py::arg("seed") = py::none(),
      py::arg("lattice") = py::none(), py::arg("options") = py::none(), py::arg("background_vertices") = py::none());

  m.def(
      "uniform_mesh",
      [](const Domain& domain, double targetVertices, std::optional<long long> seed, std::optional<std::string> lattice,
         std::optional<mesher::MeshOptions> options) {
        const mesher::MeshOptions o = resolveOptions(options, "adapt", seed, lattice);
        ABLMG_REQUIRE(std::isfinite(targetVertices) && targetVertices >= 3,
                      "uniform_mesh: target_vertices must be >= 3, got " << targetVertices);
        mesher::MeshResult r;
        {
          py::gil_scoped_release release;
          r = adapt::uniformMesh(domain, targetVertices, o);
        }
        return wrap(std::move(r.mesh), std::move(r.metric), cli::meshStatsJson(r.stats));
      },
      R"(uniform_mesh(domain, target_vertices, *, seed=None, lattice=None, options=None) -> Mesh

The first mesh of `ablmg adapt`: the isotropic metric of size h = sqrt(area / ((sqrt(3)/2) N))
whose unit mesh has about N = target_vertices vertices (adapt/adaptive_loop.hpp). Options
default to MeshOptions('adapt').)",
      py::arg("domain"), py::arg("target_vertices"), py::kw_only(), py::arg("seed") = py::none(),
      py::arg("lattice") = py::none(), py::arg("options") = py::none());

  m.def(
      "remesh",
      [](py::handle points, py::handle triangles, py::handle metric, py::handle edges, py::handle refs,
         std::optional<double> hmin, std::optional<double> hmax, std::optional<double> hgrad,
         std::optional<long long> seed, std::optional<std::string> lattice, std::optional<mesher::MeshOptions> options,
         std::optional<Domain> domain, std::optional<double> metricQuantum) {
        Mesh2 mesh;
        std::vector<Metric2> metrics;
        if (py::isinstance<PyMesh>(points)) {  // remesh(mesh, metric=None): every field of the Mesh
          const PyMesh& in = points.cast<const PyMesh&>();
          const py::handle given = !metric.is_none() ? metric : triangles;
          ABLMG_REQUIRE(edges.is_none() && refs.is_none() && (metric.is_none() || triangles.is_none()),
                        "remesh(mesh, metric): a Mesh carries its own triangles and boundary");
          ABLMG_REQUIRE(!given.is_none() || !in.metric.empty(), "remesh: no metric given and the Mesh has none");
          mesh = in.mesh;
          metrics = given.is_none() ? in.metric : toMetrics(given, "metric", mesh.numVertices());
          const MeshValidation v = mesh.validate();
          ABLMG_REQUIRE(v.ok, "remesh: invalid mesh: " << v.firstProblem);
        } else {
          if (triangles.is_none() || metric.is_none())  // as a missing argument would
            throw py::type_error("remesh: needs points, triangles and metric (or a Mesh), got None");
          mesh = toMesh(points, triangles, edges, refs, true, "remesh");
          metrics = toMetrics(metric, "metric", mesh.numVertices());
        }
        if (metricQuantum) {
          ABLMG_REQUIRE(std::isfinite(*metricQuantum) && *metricQuantum > 0,
                        "remesh: metric_quantum must be > 0, got " << *metricQuantum);
          adapt::snapMetrics(metrics, *metricQuantum);
        }
        adapt::RemeshOptions o;
        o.mesh = resolveOptions(options, "remesh", seed, lattice);
        o.inputCheck = BackgroundMetricField::MeshCheck::AlreadyValidated;
        if (domain) {
          ABLMG_REQUIRE(!hmin && !hmax && !hgrad,
                        "remesh: with domain= the metric is used as given; hmin, hmax and hgrad must be None "
                        "(bound the metric first, e.g. with hessian_metric)");
          mesher::MeshResult r;
          {
            py::gil_scoped_release release;
            r = adapt::remesh(*domain, mesh, std::move(metrics), o.mesh);
          }
          return wrap(std::move(r.mesh), std::move(r.metric), cli::meshStatsJson(r.stats));
        }
        if (hmin) o.hmin = *hmin;
        if (hmax) o.hmax = *hmax;
        if (hgrad) o.hgrad = *hgrad;
        adapt::validate(o);
        adapt::RemeshResult r;
        {
          py::gil_scoped_release release;
          r = adapt::remesh(std::move(mesh), std::move(metrics), o);
        }
        nlohmann::json stats = cli::meshStatsJson(r.stats);
        stats["clampedMetrics"] = r.clampedMetrics;
        stats["gradedMetrics"] = r.gradation.corrections;
        stats["seconds"] = {{"clamp", r.secondsClamp},
                            {"gradation", r.secondsGradation},
                            {"domain", r.secondsDomain},
                            {"backgroundField", r.secondsBackgroundField},
                            {"meshing", r.secondsMeshing}};
        return wrap(std::move(r.mesh), std::move(r.metric), std::move(stats));
      },
      kRemeshDoc, py::arg("points"), py::arg("triangles") = py::none(), py::arg("metric") = py::none(),
      py::arg("boundary_edges") = py::none(), py::arg("boundary_refs") = py::none(), py::kw_only(),
      py::arg("hmin") = py::none(), py::arg("hmax") = py::none(), py::arg("hgrad") = py::none(),
      py::arg("seed") = py::none(), py::arg("lattice") = py::none(), py::arg("options") = py::none(),
      py::arg("domain") = py::none(), py::arg("metric_quantum") = py::none());
}

}  // namespace ablmg::python
