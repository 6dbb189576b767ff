#include "convert.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

namespace ablmg::python {
namespace {

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// np.asarray(obj), refusing dtypes that are not real numbers (or not integers, with `integer`).
py::array asArray(py::handle obj, const char* name, bool integer) {
  if (obj.is_none()) throw py::type_error(std::string(name) + ": expected an array, got None");
  py::array a = py::module_::import("numpy").attr("asarray")(obj);
  const char kind = a.dtype().kind();
  const bool ok = integer ? (kind == 'i' || kind == 'u') : (kind == 'f' || kind == 'i' || kind == 'u');
  if (!ok)
    throw py::type_error(std::string(name) + ": expected " + (integer ? "an integer array" : "a real (float64) array") +
                         ", got dtype " + std::string(py::str(a.dtype())));
  return a;
}

void requireShape(const py::array& a, const char* name, long rows, long cols, const char* expected) {
  const bool ok = cols < 0 ? a.ndim() == 1 : (a.ndim() == 2 && a.shape(1) == cols);
  ABLMG_REQUIRE(ok && (rows < 0 || a.shape(0) == rows),
                name << ": expected shape " << expected << ", got " << shapeText(a));
}

py::array_t<double> asDoubles(py::handle obj, const char* name) {
  return py::array_t<double, py::array::forcecast>::ensure(asArray(obj, name, false));
}
py::array_t<long long> asIndices(py::handle obj, const char* name) {
  return py::array_t<long long, py::array::forcecast>::ensure(asArray(obj, name, true));
}

void requireFinite(double v, const char* name, py::ssize_t i, py::ssize_t j) {
  ABLMG_REQUIRE(std::isfinite(v),
                name << "[" << i << (j >= 0 ? ", " + std::to_string(j) : "") << "] is not finite (" << v << ")");
}

py::array readOnly(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

}  // namespace

std::vector<Vec2> toPoints(py::handle obj, const char* name) {
  const auto a = asDoubles(obj, name);
  requireShape(a, name, -1, 2, "(n, 2)");
  ABLMG_REQUIRE(a.shape(0) > 0, name << ": no points");
  const auto r = a.unchecked<2>();
  std::vector<Vec2> out(std::size_t(a.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    for (py::ssize_t j = 0; j < 2; ++j) requireFinite(r(i, j), name, i, j);
    out[std::size_t(i)] = Vec2(r(i, 0), r(i, 1));
  }
  return out;
}

std::vector<std::array<int, 3>> toTriangles(py::handle obj, const char* name, long numVertices) {
  const auto a = asIndices(obj, name);
  requireShape(a, name, -1, 3, "(m, 3)");
  ABLMG_REQUIRE(a.shape(0) > 0, name << ": no triangles");
  const auto r = a.unchecked<2>();
  std::vector<std::array<int, 3>> out(std::size_t(a.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (py::ssize_t j = 0; j < 3; ++j) {
      const long long v = r(i, j);
      ABLMG_REQUIRE(v >= 0 && v < numVertices, name << "[" << i << ", " << j << "] = " << v
                                                    << " is not a vertex id in [0, " << numVertices << ")");
      out[std::size_t(i)][std::size_t(j)] = int(v);
    }
  return out;
}

std::vector<double> toValues(py::handle obj, const char* name, long expected) {
  const auto a = asDoubles(obj, name);
  requireShape(a, name, expected, -1, ("(" + std::to_string(expected) + ",)").c_str());
  const auto r = a.unchecked<1>();
  std::vector<double> out(std::size_t(a.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    requireFinite(r(i), name, i, -1);
    out[std::size_t(i)] = r(i);
  }
  return out;
}

std::vector<int> toInts(py::handle obj, const char* name, long expected) {
  const auto a = asIndices(obj, name);
  requireShape(a, name, expected, -1, ("(" + std::to_string(expected) + ",)").c_str());
  const auto r = a.unchecked<1>();
  std::vector<int> out(std::size_t(a.shape(0)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    ABLMG_REQUIRE(r(i) >= -2147483647LL && r(i) <= 2147483647LL,
                  name << "[" << i << "] = " << r(i) << " overflows int32");
    out[std::size_t(i)] = int(r(i));
  }
  return out;
}

std::vector<Metric2> toMetrics(py::handle obj, const char* name, long expected) {
  const auto a = asDoubles(obj, name);
  const std::string n = std::to_string(expected);
  ABLMG_REQUIRE(
      (a.ndim() == 1 || (a.ndim() == 2 && a.shape(1) == 3)) && a.shape(0) == expected,
      name << ": expected shape (" << n << ", 3) [m11, m12, m22] or (" << n << ",) sizes, got " << shapeText(a));
  std::vector<Metric2> out(static_cast<std::size_t>(expected));
  const std::string entry = std::string(name) + "[";
  if (a.ndim() == 1) {
    const auto r = a.unchecked<1>();
    for (py::ssize_t i = 0; i < r.shape(0); ++i) {
      ABLMG_REQUIRE(std::isfinite(r(i)) && r(i) > 0,
                    name << "[" << i << "]: size " << r(i) << " must be positive and finite");
      out[std::size_t(i)] = Metric2::fromSizes(r(i), r(i), 0.0, entry + std::to_string(i) + "]");
    }
  } else {
    const auto r = a.unchecked<2>();
    for (py::ssize_t i = 0; i < r.shape(0); ++i)
      out[std::size_t(i)] = Metric2::fromTensor(r(i, 0), r(i, 1), r(i, 2), entry + std::to_string(i) + "]");
  }
  return out;
}

Mesh2 toMesh(py::handle points, py::handle triangles, py::handle boundaryEdges, py::handle boundaryRefs, bool validate,
             const char* what) {
  Mesh2 mesh;
  mesh.vertices = toPoints(points, "points");
  mesh.triangles = toTriangles(triangles, "triangles", mesh.numVertices());
  for (auto& t : mesh.triangles)
    if (orient2d(mesh.vertices[std::size_t(t[0])], mesh.vertices[std::size_t(t[1])], mesh.vertices[std::size_t(t[2])]) <
        0)
      std::swap(t[1], t[2]);
  // Directed triangle edges a→b, keyed a·n + b.
  const auto key = [n = std::uint64_t(mesh.numVertices())](int a, int b) {
    return std::uint64_t(a) * n + std::uint64_t(b);
  };
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[key(t[k], t[(k + 1) % 3])];
  const auto has = [&](int a, int b) { return directed.count(key(a, b)) > 0; };
  if (boundaryEdges.is_none()) {
    ABLMG_REQUIRE(boundaryRefs.is_none(), "boundary_refs given without boundary_edges");
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (!has(t[(k + 1) % 3], t[k])) mesh.boundaryEdges.push_back({t[k], t[(k + 1) % 3], 1});
  } else {
    const auto e = asIndices(boundaryEdges, "boundary_edges");
    requireShape(e, "boundary_edges", -1, 2, "(k, 2)");
    const auto r = e.unchecked<2>();
    const long k = long(e.shape(0));
    const std::vector<int> refs =
        boundaryRefs.is_none() ? std::vector<int>(std::size_t(k), 1) : toInts(boundaryRefs, "boundary_refs", k);
    for (long i = 0; i < k; ++i) {
      int ab[2];
      for (int j = 0; j < 2; ++j) {
        const long long v = r(i, j);
        ABLMG_REQUIRE(v >= 0 && v < mesh.numVertices(), "boundary_edges[" << i << ", " << j << "] = " << v
                                                                          << " is not a vertex id in [0, "
                                                                          << mesh.numVertices() << ")");
        ab[j] = int(v);
      }
      if (!has(ab[0], ab[1]) && has(ab[1], ab[0])) std::swap(ab[0], ab[1]);
      mesh.boundaryEdges.push_back({ab[0], ab[1], refs[std::size_t(i)]});
    }
  }
  if (validate) {
    const MeshValidation v = mesh.validate();
    ABLMG_REQUIRE(v.ok, what << ": invalid mesh: " << v.firstProblem);
  }
  return mesh;
}

py::array pointsView(const std::vector<Vec2>& points, py::handle owner) {
  static_assert(sizeof(Vec2) == 2 * sizeof(double));
  return readOnly(py::array_t<double>({py::ssize_t(points.size()), py::ssize_t(2)},
                                      {py::ssize_t(sizeof(Vec2)), py::ssize_t(sizeof(double))},
                                      points.empty() ? nullptr : points.front().data(), owner));
}

py::array trianglesView(const std::vector<std::array<int, 3>>& triangles, py::handle owner) {
  static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));
  return readOnly(py::array_t<int>({py::ssize_t(triangles.size()), py::ssize_t(3)},
                                   {py::ssize_t(3 * sizeof(int)), py::ssize_t(sizeof(int))},
                                   triangles.empty() ? nullptr : triangles.front().data(), owner));
}

py::array boundaryEdgesView(const std::vector<BoundaryEdge>& edges, py::handle owner) {
  static_assert(sizeof(BoundaryEdge) == 3 * sizeof(int) && offsetof(BoundaryEdge, b) == sizeof(int));
  return readOnly(py::array_t<int>({py::ssize_t(edges.size()), py::ssize_t(2)},
                                   {py::ssize_t(sizeof(BoundaryEdge)), py::ssize_t(sizeof(int))},
                                   edges.empty() ? nullptr : &edges.front().a, owner));
}

py::array boundaryRefsView(const std::vector<BoundaryEdge>& edges, py::handle owner) {
  return readOnly(py::array_t<int>({py::ssize_t(edges.size())}, {py::ssize_t(sizeof(BoundaryEdge))},
                                   edges.empty() ? nullptr : &edges.front().ref, owner));
}

namespace {
/// Metric2 stores m11, m12, m22 as its three doubles, in that order.
py::array metricsArray(const std::vector<Metric2>& metrics, py::handle owner) {
  static_assert(sizeof(Metric2) == 3 * sizeof(double));
  return py::array_t<double>({py::ssize_t(metrics.size()), py::ssize_t(3)},
                             {py::ssize_t(sizeof(Metric2)), py::ssize_t(sizeof(double))},
                             metrics.empty() ? nullptr : reinterpret_cast<const double*>(metrics.data()), owner);
}
}  // namespace

py::array metricsView(const std::vector<Metric2>& metrics, py::handle owner) {
  return readOnly(metricsArray(metrics, owner));
}

py::array ownedArray(std::vector<Metric2> metrics) {
  auto* owned = new std::vector<Metric2>(std::move(metrics));
  py::capsule capsule(owned, [](void* p) { delete static_cast<std::vector<Metric2>*>(p); });
  return metricsArray(*owned, capsule);  // writeable: the caller owns it
}

py::object toPython(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = toPython(v);
      return d;
    }
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(toPython(v));
      return l;
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.get<double>());
    default:
      return py::none();
  }
}

}  // namespace ablmg::python
