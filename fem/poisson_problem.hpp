#pragma once
/// PoissonProblem: the data of  −∇·(κ ∇u) = f  in Ω,
///   u = g_D            on the boundary edges whose tag has Dirichlet data,
///   κ ∂u/∂n = g_N      on the other boundary edges (g_N = 0 unless given).
///
/// Every datum is a ScalarData: a function of (x, y), or per-vertex values of the mesh it
/// will be used with (interpolated linearly on each triangle / edge), or a constant.
/// Functions are plain std::function; expression strings (muparser) are parsed by cli/.
/// Units: those of the coordinates; κ > 0 is required everywhere (checked at quadrature
/// points by assemble(), which throws InputError otherwise).
#include <functional>
#include <map>
#include <type_traits>
#include <vector>

namespace ablmg::fem {

using ScalarFn = std::function<double(double x, double y)>;

/// A scalar field given as a function, as per-vertex values, or as a constant.
/// Exactly one form is used: `fn` if set, else `vertexValues` if non-empty, else `constant`.
struct ScalarData {
  ScalarFn fn;
  std::vector<double> vertexValues;  ///< one per mesh vertex
  double constant = 0;

  ScalarData() = default;
  ScalarData(double c) : constant(c) {}         // NOLINT: implicit by design
  ScalarData(ScalarFn f) : fn(std::move(f)) {}  // NOLINT
  /// Any callable double(double, double), e.g. a lambda: `p.f = [](double x, double y) {…};`
  template <class F, std::enable_if_t<std::is_invocable_r_v<double, F, double, double> &&
                                          !std::is_convertible_v<F, double> && !std::is_same_v<F, ScalarFn>,
                                      int> = 0>
  ScalarData(F f) : fn(std::move(f)) {}  // NOLINT
  static ScalarData values(std::vector<double> v) {
    ScalarData d;
    d.vertexValues = std::move(v);
    return d;
  }
  bool isFunction() const { return bool(fn); }
  bool isVertexValues() const { return !fn && !vertexValues.empty(); }
  bool isConstant() const { return !fn && vertexValues.empty(); }
};

struct PoissonProblem {
  ScalarData kappa = 1.0;  ///< diffusion coefficient κ > 0
  ScalarData f = 0.0;      ///< right-hand side; functions are integrated by a degree-5 rule
  /// Per subdomain (material) data, keyed by triangle ref (Mesh2::triangleRefs; 0 when the mesh
  /// has none). When non-empty, triangle t uses kappaBySubdomain.at(ref of t) instead of
  /// `kappa` (and fBySubdomain likewise instead of `f`), so κ and f may jump across the
  /// interfaces between subdomains (Mitchell's battery). A ref with no entry is an InputError
  /// naming it. Vertex values are per vertex of the whole mesh.
  std::map<int, ScalarData> kappaBySubdomain, fBySubdomain;
  /// Dirichlet data per boundary reference tag (BoundaryEdge::ref).
  std::map<int, ScalarData> dirichlet;
  /// When `hasDirichletDefault`: Dirichlet data for every boundary tag listed neither in
  /// `dirichlet` nor in `neumann` (e.g. the exact u on the whole boundary).
  ScalarData dirichletDefault;
  bool hasDirichletDefault = false;
  /// Neumann flux g_N = κ ∂u/∂n per tag; tags with no entry (and no Dirichlet) get g_N = 0.
  std::map<int, ScalarData> neumann;

  /// True when every `fn` above may be called from several threads at once (pure functions,
  /// e.g. C++ lambdas; not a shared muparser object). assemble() then evaluates elements in
  /// parallel (OpenMP); the result is bitwise identical either way.
  bool threadSafeFunctions = false;

  /// Convenience: Dirichlet data g on every boundary edge.
  void setDirichletEverywhere(ScalarData g) {
    dirichletDefault = std::move(g);
    hasDirichletDefault = true;
  }
};

}  // namespace ablmg::fem
