// The C interface (ablmg.h) over adapt::remesh. Every entry point runs its body inside
// guarded(), which turns any exception into a status code and the handle's message: nothing
// C++ crosses the boundary. Setters check what they can alone (NULL, counts, finite values,
// SPD tensors, index >= base); ablmg_remesh checks the rest (indices < n, matching counts,
// options together, the mesh itself) before calling adapt::remesh with the options
// `ablmg remesh` uses, so the arrays of a .mesh/.sol pair give that command's output.
#include "ablmg/capi/ablmg.h"

#include "ablmg/adapt/remesh.hpp"
#include "ablmg/adapt/transfer.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/mesher/quality.hpp"

#include <omp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

struct ablmg_handle {
  // Input (as given, 0-based).
  std::vector<ablmg::Vec2> vertices;
  std::vector<int> vertexRefs;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangleRefs;
  std::vector<ablmg::BoundaryEdge> edges;
  std::vector<ablmg::Metric2> metric;
  bool haveVertices = false, haveTriangles = false, haveEdges = false, haveMetric = false;
  // Options (ablmg remesh's defaults).
  double hmin = 0, hmax = std::numeric_limits<double>::infinity(), hgrad = 1.3, metricQuantum = 0;
  long long seed = 0;
  int threads = 0;
  ablmg::adapt::RemeshOptions::WarmStart warmStart = ablmg::adapt::RemeshOptions::WarmStart::IfFits;
  // Last result, the mesh it was made from (the transfer's source), and the message.
  std::optional<ablmg::adapt::RemeshResult> result;
  std::optional<ablmg::Mesh2> source;
  std::optional<ablmg::mesher::MeshQuality> quality;
  std::string error;
};

namespace {

/// A failure with its status code; thrown inside guarded() only.
struct Failure {
  int status;
  std::string message;
};

template <class... Parts>
[[noreturn]] void fail(int status, const Parts&... parts) {
  std::ostringstream os;
  (os << ... << parts);
  throw Failure{status, os.str()};
}

/// Runs body (returning nothing; it throws Failure or anything else to fail) and returns the
/// status, leaving the message in the handle.
template <class Body>
int guarded(ablmg_t* h, const char* function, Body&& body) noexcept {
  if (!h) return ABLMG_ERR_NULL;
  try {
    h->error.clear();
    body();
    return ABLMG_OK;
  } catch (const Failure& f) {
    try {
      h->error = std::string(function) + ": " + f.message;
    } catch (...) {}
    return f.status;
  } catch (const std::bad_alloc&) {
    try {
      h->error = std::string(function) + ": out of memory";
    } catch (...) {}
    return ABLMG_ERR_MEMORY;
  } catch (const ablmg::InputError& e) {
    // The remesher names the input "input": a problem with the mesh itself starts so.
    const std::string what = e.what();
    try {
      h->error = std::string(function) + ": " + what;
    } catch (...) {}
    return what.rfind("input: ", 0) == 0            ? ABLMG_ERR_INVALID_MESH
           : what.rfind("remesh options: ", 0) == 0 ? ABLMG_ERR_ARGUMENT
                                                    : ABLMG_ERR_INPUT;
  } catch (const std::exception& e) {
    try {
      h->error = std::string(function) + ": " + e.what();
    } catch (...) {}
    return ABLMG_ERR_MESHER;
  } catch (...) {
    try {
      h->error = std::string(function) + ": unknown failure";
    } catch (...) {}
    return ABLMG_ERR_MESHER;
  }
}

void requirePointer(const void* p, const char* name) {
  if (!p) fail(ABLMG_ERR_NULL, name, " is NULL");
}

void requireCount(long long n, long long least, long long most, const char* name) {
  if (n < least || n > most) fail(ABLMG_ERR_ARGUMENT, name, " = ", n, " is out of range [", least, ", ", most, "]");
}

void requireBase(int base) {
  if (base != 0 && base != 1) fail(ABLMG_ERR_ARGUMENT, "base = ", base, " must be 0 or 1");
}

/// Index arrays: values >= base; the upper bound (the vertex count) is checked at remesh.
std::vector<int> zeroBased(const int* idx, std::size_t count, int base, const char* name) {
  std::vector<int> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (idx[i] < base) fail(ABLMG_ERR_INPUT, name, "[", i, "] = ", idx[i], " is below the index base ", base);
    out[i] = idx[i] - base;
  }
  return out;
}

/// The triangles counter-clockwise and the boundary edges with the domain on their left, as
/// io::readMesh leaves a medit file's (io/medit.cpp), so arrays and files remesh alike.
void orient(ablmg::Mesh2& mesh) {
  for (auto& t : mesh.triangles) {
    const ablmg::Vec2 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    if (ablmg::cross(b - a, c - a) < 0) std::swap(t[1], t[2]);
  }
  const std::size_t nv = mesh.vertices.size();
  std::vector<int> rowStart(nv + 1, 0), heads(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++rowStart[std::size_t(t[k]) + 1];
  for (std::size_t v = 0; v < nv; ++v) rowStart[v + 1] += rowStart[v];
  std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) heads[std::size_t(fill[std::size_t(t[k])]++)] = t[(k + 1) % 3];
  const auto has = [&](int a, int b) {
    const auto first = heads.begin() + rowStart[std::size_t(a)], last = heads.begin() + rowStart[std::size_t(a) + 1];
    return std::find(first, last, b) != last;
  };
  for (auto& e : mesh.boundaryEdges)
    if (!has(e.a, e.b) && has(e.b, e.a)) std::swap(e.a, e.b);
}

/// The input as a Mesh2 (indices checked against the vertex count) and its metric.
ablmg::Mesh2 inputMesh(const ablmg_handle& h) {
  if (!h.haveVertices) fail(ABLMG_ERR_STATE, "no vertices set (ablmg_set_vertices)");
  if (!h.haveTriangles) fail(ABLMG_ERR_STATE, "no triangles set (ablmg_set_triangles)");
  if (!h.haveEdges) fail(ABLMG_ERR_STATE, "no boundary edges set (ablmg_set_edges)");
  if (!h.haveMetric) fail(ABLMG_ERR_STATE, "no metric set (ablmg_set_metric or ablmg_set_sizes)");
  const int n = int(h.vertices.size());
  if (h.metric.size() != h.vertices.size())
    fail(ABLMG_ERR_ARGUMENT, "the metric has ", h.metric.size(), " values but the mesh has ", n, " vertices");
  for (std::size_t t = 0; t < h.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (h.triangles[t][k] >= n)
        fail(ABLMG_ERR_INPUT, "triangle ", t, " has vertex index ", h.triangles[t][k], " (0-based) but the mesh has ",
             n, " vertices");
  for (std::size_t e = 0; e < h.edges.size(); ++e)
    if (h.edges[e].a >= n || h.edges[e].b >= n)
      fail(ABLMG_ERR_INPUT, "boundary edge ", e, " has vertex index ", std::max(h.edges[e].a, h.edges[e].b),
           " (0-based) but the mesh has ", n, " vertices");
  ablmg::Mesh2 mesh;
  mesh.vertices = h.vertices;
  mesh.vertexRefs = h.vertexRefs;
  mesh.triangles = h.triangles;
  mesh.triangleRefs = h.triangleRefs;
  mesh.boundaryEdges = h.edges;
  orient(mesh);
  return mesh;
}

/// Restores the caller's OpenMP thread count when the remesh returns.
struct ThreadScope {
  explicit ThreadScope(int n) : saved(omp_get_max_threads()), set(n > 0) {
    if (set) omp_set_num_threads(n);
  }
  ~ThreadScope() {
    if (set) omp_set_num_threads(saved);
  }
  int saved;
  bool set;
};

const ablmg::adapt::RemeshResult& resultOf(const ablmg_handle& h) {
  if (!h.result) fail(ABLMG_ERR_STATE, "no result (ablmg_remesh has not succeeded on this input)");
  return *h.result;
}

void requireResultCount(long long given, long long actual, const char* what) {
  if (given != actual)
    fail(ABLMG_ERR_CAPACITY, "count ", given, " is not the result's ", actual, " ", what, " (ablmg_get_sizes)");
}

constexpr long long kMaxCount = INT_MAX / 3;  ///< so that 3 * count fits an int (Fortran's arrays)

}  // namespace

extern "C" {

const char* ablmg_version(void) { return "0.2.0"; }

ablmg_t* ablmg_create(void) { return new (std::nothrow) ablmg_handle; }

void ablmg_free(ablmg_t* handle) { delete handle; }

const char* ablmg_last_error(const ablmg_t* handle) { return handle ? handle->error.c_str() : "null ablmg handle"; }

int ablmg_set_vertices(ablmg_t* h, const double* xy, const int* refs, int n) {
  return guarded(h, "ablmg_set_vertices", [&] {
    h->haveVertices = false;
    requirePointer(xy, "xy");
    requireCount(n, 3, kMaxCount, "n");
    std::vector<ablmg::Vec2> v(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double x = xy[2 * std::size_t(i)], y = xy[2 * std::size_t(i) + 1];
      if (!std::isfinite(x) || !std::isfinite(y))
        fail(ABLMG_ERR_INPUT, "vertex ", i, " (", x, ", ", y, ") is not finite");
      v[std::size_t(i)] = ablmg::Vec2(x, y);
    }
    h->vertices = std::move(v);
    h->vertexRefs = refs ? std::vector<int>(refs, refs + n) : std::vector<int>();
    h->haveVertices = true;
  });
}

int ablmg_set_triangles(ablmg_t* h, const int* tri, const int* refs, int m, int base) {
  return guarded(h, "ablmg_set_triangles", [&] {
    h->haveTriangles = false;
    requirePointer(tri, "tri");
    requireCount(m, 1, kMaxCount, "m");
    requireBase(base);
    const auto idx = zeroBased(tri, 3 * std::size_t(m), base, "tri");
    std::vector<std::array<int, 3>> t(static_cast<std::size_t>(m));
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = {idx[3 * i], idx[3 * i + 1], idx[3 * i + 2]};
    h->triangles = std::move(t);
    h->triangleRefs = refs ? std::vector<int>(refs, refs + m) : std::vector<int>();
    h->haveTriangles = true;
  });
}

int ablmg_set_edges(ablmg_t* h, const int* edges, const int* refs, int k, int base) {
  return guarded(h, "ablmg_set_edges", [&] {
    h->haveEdges = false;
    requirePointer(edges, "edges");
    requireCount(k, 3, kMaxCount, "k");
    requireBase(base);
    const auto idx = zeroBased(edges, 2 * std::size_t(k), base, "edges");
    std::vector<ablmg::BoundaryEdge> e(static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < e.size(); ++i) e[i] = {idx[2 * i], idx[2 * i + 1], refs ? refs[i] : 1};
    h->edges = std::move(e);
    h->haveEdges = true;
  });
}

int ablmg_set_metric(ablmg_t* h, const double* m, int n) {
  return guarded(h, "ablmg_set_metric", [&] {
    h->haveMetric = false;
    requirePointer(m, "m");
    requireCount(n, 1, kMaxCount, "n");
    std::vector<ablmg::Metric2> metric(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double* v = m + 3 * std::size_t(i);
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        fail(ABLMG_ERR_INPUT, "tensor of vertex ", i, " (", v[0], ", ", v[1], ", ", v[2], ") is not finite");
      const ablmg::Metric2 t = ablmg::Metric2::raw(v[0], v[1], v[2]);
      if (!t.isSpd())
        fail(ABLMG_ERR_INPUT, "tensor of vertex ", i, " (", v[0], ", ", v[1], ", ", v[2], ") is not positive definite");
      metric[std::size_t(i)] = ablmg::Metric2::fromTensor(v[0], v[1], v[2], "tensor of vertex " + std::to_string(i));
    }
    h->metric = std::move(metric);
    h->haveMetric = true;
  });
}

int ablmg_set_sizes(ablmg_t* h, const double* sizes, int n) {
  return guarded(h, "ablmg_set_sizes", [&] {
    h->haveMetric = false;
    requirePointer(sizes, "h");
    requireCount(n, 1, kMaxCount, "n");
    std::vector<ablmg::Metric2> metric(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double s = sizes[i];
      if (!std::isfinite(s) || !(s > 0)) fail(ABLMG_ERR_INPUT, "size of vertex ", i, " is ", s, ", must be > 0");
      // As a medit .sol of type 1 is read: M = I / h², refused if 1/h² is not representable.
      const double inv = 1 / (s * s);
      if (!std::isfinite(inv) || !(inv > 0) || !std::isnormal(inv))
        fail(ABLMG_ERR_INPUT, "size of vertex ", i, " is ", s, ": its tensor 1/h² is not representable");
      metric[std::size_t(i)] = ablmg::Metric2::isotropic(s);
    }
    h->metric = std::move(metric);
    h->haveMetric = true;
  });
}

// A C caller may pass any int as an ablmg_option; reading it as the C++ enum would be undefined
// behaviour outside the enumerators' range, so the value is read as the int it is stored as.
static int optionCode(const ablmg_option& option) {
  static_assert(sizeof(ablmg_option) == sizeof(int), "ablmg_option is passed as an int");
  int code;
  std::memcpy(&code, &option, sizeof code);
  return code;
}

int ablmg_set_double(ablmg_t* h, ablmg_option option, double value) {
  return guarded(h, "ablmg_set_double", [&] {
    switch (optionCode(option)) {
      case ABLMG_HMIN:
        if (!std::isfinite(value) || value < 0) fail(ABLMG_ERR_ARGUMENT, "hmin = ", value, " must be finite and >= 0");
        h->hmin = value;
        break;
      case ABLMG_HMAX:
        if (std::isnan(value) || !(value > 0)) fail(ABLMG_ERR_ARGUMENT, "hmax = ", value, " must be > 0 (or HUGE_VAL)");
        h->hmax = value;
        break;
      case ABLMG_HGRAD:
        if (!std::isfinite(value) || (value > 0 && value <= 1))
          fail(ABLMG_ERR_ARGUMENT, "hgrad = ", value, " must be > 1 (or <= 0 to disable the gradation)");
        h->hgrad = value;
        break;
      case ABLMG_METRIC_QUANTUM:
        if (!std::isfinite(value) || value < 0)
          fail(ABLMG_ERR_ARGUMENT, "metric quantum = ", value, " must be finite and >= 0 (0: off)");
        h->metricQuantum = value;
        break;
      default:
        fail(ABLMG_ERR_ARGUMENT, "option ", optionCode(option),
             " is not a double option (ABLMG_HMIN, ABLMG_HMAX, ABLMG_HGRAD, ABLMG_METRIC_QUANTUM)");
    }
  });
}

int ablmg_set_int(ablmg_t* h, ablmg_option option, long long value) {
  return guarded(h, "ablmg_set_int", [&] {
    switch (optionCode(option)) {
      case ABLMG_SEED:
        if (value < 0) fail(ABLMG_ERR_ARGUMENT, "seed = ", value, " must be >= 0");
        h->seed = value;
        break;
      case ABLMG_THREADS:
        if (value < 0 || value > 4096) fail(ABLMG_ERR_ARGUMENT, "threads = ", value, " must be in [0, 4096]");
        h->threads = int(value);
        break;
      case ABLMG_WARM_START:
        if (value < 0 || value > 2)
          fail(ABLMG_ERR_ARGUMENT, "warm start = ", value, " must be 0 (off), 1 (on) or 2 (auto)");
        h->warmStart = value == 0   ? ablmg::adapt::RemeshOptions::WarmStart::Off
                       : value == 1 ? ablmg::adapt::RemeshOptions::WarmStart::On
                                    : ablmg::adapt::RemeshOptions::WarmStart::IfFits;
        break;
      default:
        fail(ABLMG_ERR_ARGUMENT, "option ", optionCode(option),
             " is not an integer option (ABLMG_SEED, ABLMG_THREADS, ABLMG_WARM_START)");
    }
  });
}

int ablmg_remesh(ablmg_t* h) {
  return guarded(h, "ablmg_remesh", [&] {
    h->result.reset();
    h->quality.reset();
    h->source.reset();
    ablmg::Mesh2 mesh = inputMesh(*h);
    // What `ablmg remesh` sets (cli/cmd_remesh.cpp); the rest are RemeshOptions' defaults.
    ablmg::adapt::RemeshOptions options;
    options.hmin = h->hmin;
    options.hmax = h->hmax;
    options.hgrad = h->hgrad;
    options.name = "input";
    options.mesh.placement.seed = std::uint64_t(h->seed);
    options.mesh.placement.threads = h->threads;
    options.mesh.connect.threads = h->threads;
    options.warmStart = h->warmStart;
    options.metricQuantum = h->metricQuantum;
    ablmg::adapt::validate(options);
    const ablmg::MeshValidation check = mesh.validate();
    if (!check.ok) fail(ABLMG_ERR_INVALID_MESH, "input: invalid mesh: ", check.firstProblem);
    options.inputCheck = ablmg::BackgroundMetricField::MeshCheck::AlreadyValidated;
    const ThreadScope threads(h->threads);
    ablmg::Mesh2 source = mesh;
    h->result = ablmg::adapt::remesh(std::move(mesh), h->metric, options);
    h->source = std::move(source);
  });
}

int ablmg_get_sizes(ablmg_t* h, int* nvertices, int* ntriangles, int* nedges) {
  return guarded(h, "ablmg_get_sizes", [&] {
    const auto& r = resultOf(*h);
    if (nvertices) *nvertices = r.mesh.numVertices();
    if (ntriangles) *ntriangles = r.mesh.numTriangles();
    if (nedges) *nedges = int(r.mesh.boundaryEdges.size());
  });
}

int ablmg_get_vertices(ablmg_t* h, double* xy, int* refs, int n) {
  return guarded(h, "ablmg_get_vertices", [&] {
    const auto& r = resultOf(*h);
    requirePointer(xy, "xy");
    requireResultCount(n, r.mesh.numVertices(), "vertices");
    for (int i = 0; i < n; ++i) {
      xy[2 * std::size_t(i)] = r.mesh.vertices[std::size_t(i)].x();
      xy[2 * std::size_t(i) + 1] = r.mesh.vertices[std::size_t(i)].y();
      if (refs) refs[i] = r.mesh.vertexRefs.empty() ? 0 : r.mesh.vertexRefs[std::size_t(i)];
    }
  });
}

int ablmg_get_triangles(ablmg_t* h, int* tri, int* refs, int m, int base) {
  return guarded(h, "ablmg_get_triangles", [&] {
    const auto& r = resultOf(*h);
    requirePointer(tri, "tri");
    requireBase(base);
    requireResultCount(m, r.mesh.numTriangles(), "triangles");
    for (int t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) tri[3 * std::size_t(t) + std::size_t(k)] = r.mesh.triangles[std::size_t(t)][k] + base;
      if (refs) refs[t] = r.mesh.triangleRefs.empty() ? 0 : r.mesh.triangleRefs[std::size_t(t)];
    }
  });
}

int ablmg_get_edges(ablmg_t* h, int* edges, int* refs, int k, int base) {
  return guarded(h, "ablmg_get_edges", [&] {
    const auto& r = resultOf(*h);
    requirePointer(edges, "edges");
    requireBase(base);
    requireResultCount(k, long(r.mesh.boundaryEdges.size()), "boundary edges");
    for (int e = 0; e < k; ++e) {
      const auto& b = r.mesh.boundaryEdges[std::size_t(e)];
      edges[2 * std::size_t(e)] = b.a + base;
      edges[2 * std::size_t(e) + 1] = b.b + base;
      if (refs) refs[e] = b.ref;
    }
  });
}

int ablmg_get_metric(ablmg_t* h, double* m, int n) {
  return guarded(h, "ablmg_get_metric", [&] {
    const auto& r = resultOf(*h);
    requirePointer(m, "m");
    requireResultCount(n, long(r.metric.size()), "vertices");
    for (int i = 0; i < n; ++i) {
      const auto& t = r.metric[std::size_t(i)];
      m[3 * std::size_t(i)] = t.m11();
      m[3 * std::size_t(i) + 1] = t.m12();
      m[3 * std::size_t(i) + 2] = t.m22();
    }
  });
}

int ablmg_get_quality(ablmg_t* h, ablmg_quality* out) {
  return guarded(h, "ablmg_get_quality", [&] {
    const auto& r = resultOf(*h);
    requirePointer(out, "quality");
    if (!h->quality) h->quality = ablmg::mesher::meshQuality(r.mesh, r.metric);
    const auto& q = *h->quality;
    ablmg_quality s{};
    s.vertices = int(q.vertices);
    s.triangles = int(q.triangles);
    s.edges = int(q.edges);
    s.valid = q.valid ? 1 : 0;
    s.edge_min = q.edgeLengths.min;
    s.edge_mean = q.edgeLengths.mean;
    s.edge_max = q.edgeLengths.max;
    s.edge_in_sqrt2 = q.edgeLengths.inSqrt2;
    s.edge_within_10 = q.edgeLengths.within10;
    std::copy(q.edgeLengths.deviation.begin(), q.edgeLengths.deviation.end(), s.edge_deviation);
    s.quality_min = q.elements.min;
    s.quality_mean = q.elements.mean;
    s.quality_max = q.elements.max;
    std::copy(q.elements.bins.begin(), q.elements.bins.end(), s.quality_bins);
    s.clamped_metrics = int(r.clampedMetrics);
    s.graded_metrics = int(r.gradation.corrections);
    s.repaired_triangles = int(r.stats.connect.repairedTriangles);
    *out = s;
  });
}

int ablmg_transfer(ablmg_t* h, const double* oldFields, int nOld, int nfields, int method, double* newFields, int nNew,
                   ablmg_transfer_stats* stats) {
  return guarded(h, "ablmg_transfer", [&] {
    const auto& r = resultOf(*h);
    const ablmg::Mesh2& source = *h->source;
    requirePointer(oldFields, "old_fields");
    requirePointer(newFields, "new_fields");
    if (nOld != source.numVertices())
      fail(ABLMG_ERR_ARGUMENT, "n_old = ", nOld, " is not the ", source.numVertices(),
           " vertices of the mesh the last remesh read");
    requireResultCount(nNew, r.mesh.numVertices(), "vertices");
    requireCount(nfields, 1, kMaxCount / std::max(1, std::max(nOld, nNew)), "nfields");
    if (method < ABLMG_TRANSFER_INTERPOLATION || method > ABLMG_TRANSFER_PROJECTION_BOUNDED)
      fail(ABLMG_ERR_ARGUMENT, "method = ", method,
           " is not an ablmg_transfer_method (0 interpolation, 1 projection, 2 bounded projection)");
    std::vector<Eigen::VectorXd> fields(static_cast<std::size_t>(nfields));
    for (int f = 0; f < nfields; ++f) {
      fields[std::size_t(f)] = Eigen::Map<const Eigen::VectorXd>(oldFields + std::size_t(f) * std::size_t(nOld), nOld);
      for (int i = 0; i < nOld; ++i)
        if (!std::isfinite(fields[std::size_t(f)][i]))
          fail(ABLMG_ERR_INPUT, "field ", f, " at vertex ", i, " is ", fields[std::size_t(f)][i], ", not finite");
    }
    ablmg::adapt::TransferOptions options;
    options.method = method == ABLMG_TRANSFER_INTERPOLATION ? ablmg::adapt::TransferMethod::Interpolation
                                                            : ablmg::adapt::TransferMethod::L2Projection;
    options.boundPreserving = method == ABLMG_TRANSFER_PROJECTION_BOUNDED;
    ablmg::adapt::TransferStats st;
    const ThreadScope threads(h->threads);
    const std::vector<Eigen::VectorXd> out = ablmg::adapt::transferFields(source, r.mesh, fields, options, &st);
    for (int f = 0; f < nfields; ++f)
      std::copy(out[std::size_t(f)].data(), out[std::size_t(f)].data() + nNew,
                newFields + std::size_t(f) * std::size_t(nNew));
    if (stats) {
      ablmg_transfer_stats s{};
      s.supermesh_pieces = st.supermeshPieces;
      s.supermesh_area = st.supermeshArea;
      s.outside_vertices = st.outsideVertices;
      s.solver_iterations = st.solverIterations;
      s.relative_mass_defect = st.maxRelativeMassDefect();
      s.seconds = st.seconds;
      *stats = s;
    }
  });
}

}  // extern "C"
