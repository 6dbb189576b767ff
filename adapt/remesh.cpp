#include "ablmg/adapt/remesh.hpp"
#include "ablmg/adapt/metric_snap.hpp"

#include "ablmg/core/domain_from_mesh.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/quality.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace ablmg::adapt {
namespace {
/// Clamps the sizes h1, h2 of each metric to [hmin, hmax] (directions kept; hmin = 0 means the
/// smallest positive double). Returns how many metrics changed; the others are untouched.
long clampSizes(std::vector<Metric2>& metrics, double hmin, double hmax) {
  long clamped = 0;
  const double lo = std::max(hmin, 1e-300);
  for (auto& m : metrics) {
    const auto e = m.eigen();
    const double h1 = std::clamp(e.h1, lo, hmax), h2 = std::clamp(e.h2, lo, hmax);
    if (h1 != e.h1 || h2 != e.h2) {
      m = Metric2::fromSizes(h1, h2, e.theta);
      ++clamped;
    }
  }
  return clamped;
}
}  // namespace

void validate(const RemeshOptions& o) {
  ABLMG_REQUIRE(std::isfinite(o.hmin) && o.hmin >= 0, "remesh options: hmin must be finite and >= 0, got " << o.hmin);
  ABLMG_REQUIRE(o.hmax > o.hmin, "remesh options: hmax must be > hmin, got hmax " << o.hmax << ", hmin " << o.hmin);
  ABLMG_REQUIRE(o.hgrad <= 0 || (o.hgrad > 1 && std::isfinite(o.hgrad)),
                "remesh options: hgrad must be > 1 (or <= 0 for no gradation), got " << o.hgrad);
  ABLMG_REQUIRE(std::isfinite(o.metricQuantum) && o.metricQuantum >= 0,
                "remesh options: metricQuantum must be >= 0 (0 = off), got " << o.metricQuantum);
}

namespace {
/// RemeshOptions::WarmStart::IfFits: the share of input edges within ±10 % of unit length from
/// which the input counts as fitting its metric (meshes made for it: ≥ 0.9; solver hand-overs
/// to a new metric: ≤ 0.05).
constexpr double kWarmStartFit = 0.5;
}  // namespace

RemeshResult remesh(Mesh2 mesh, std::vector<Metric2> metric, const RemeshOptions& options) {
  validate(options);
  const std::string& name = options.name;
  ABLMG_REQUIRE(long(metric.size()) == long(mesh.numVertices()), name << ": " << metric.size() << " metrics for "
                                                                      << mesh.numVertices()
                                                                      << " vertices (one per vertex needed)");
  for (std::size_t v = 0; v < metric.size(); ++v)
    ABLMG_REQUIRE(metric[v].isSpd(), name << ": metric[" << v << "] (" << metric[v].m11() << ", " << metric[v].m12()
                                          << ", " << metric[v].m22() << ") is not positive definite");
  if (mesh.numTriangles() == 0 && !mesh.boundaryEdges.empty()) {  // a boundary discretization: its first mesh
    BoundaryTriangulation b = triangulateBoundary(mesh, name, options.interiorLoops);
    std::vector<Metric2> kept;
    kept.reserve(b.inputVertex.size());
    for (int v : b.inputVertex) kept.push_back(metric[std::size_t(v)]);
    mesh = std::move(b.mesh);
    metric = std::move(kept);
  }
  RemeshResult r;
  const long inputVertices = long(metric.size());
  const auto report = [&](const char* stage) {
    if (options.mesh.progress) options.mesh.progress({.stage = stage, .nodes = inputVertices});
  };
  report("validation");
  Stopwatch watch;
  if (options.inputCheck == BackgroundMetricField::MeshCheck::Validate) {
    const MeshValidation v = mesh.validate();
    ABLMG_REQUIRE(v.ok, name << ": invalid mesh: " << v.firstProblem);
    r.secondsValidate = watch.seconds();
  }
  // 1. Sizes clamped to [hmin, hmax] (after the snap to a grid, when asked for).
  watch.restart();
  if (options.metricQuantum > 0) snapMetrics(metric, options.metricQuantum);
  r.clampedMetrics = clampSizes(metric, options.hmin, options.hmax);
  r.secondsClamp = watch.seconds();
  // 2. Gradation: sizes grow by at most ≈ hgrad per unit metric length along the input edges.
  report("gradation");
  watch.restart();
  if (options.hgrad > 1) r.gradation = limitGradation(mesh, metric, {.hgrad = options.hgrad});
  r.secondsGradation = watch.seconds();
  // 3. The domain from the input's boundary; with subdomains, interfaces or required
  // entities, the subdomains one by one (remeshSubdomains).
  if (needsSubdomains(mesh)) {
    watch.restart();
    const BackgroundMetricField field(std::move(mesh), std::move(metric),
                                      BackgroundMetricField::MeshCheck::AlreadyValidated);
    r.secondsBackgroundField = watch.seconds();
    watch.restart();
    remeshSubdomains(field.mesh(), field, options.mesh, name, r);
    r.secondsMeshing = watch.seconds();
    return r;
  }
  watch.restart();
  const Domain domain = domainFromMeshBoundary(mesh, name);
  r.secondsDomain = watch.seconds();
  // 4. The input mesh and metric as the background field (validated above or by the caller;
  // the clamp, gradation and domain do not change the mesh).
  report("background");
  watch.restart();
  mesher::MeshOptions meshOptions = options.mesh;
  if (options.warmStart == RemeshOptions::WarmStart::IfFits && meshOptions.placement.warmStart.empty())
    r.inputWithin10 = mesher::edgeLengthStats(mesher::edgeMetricLengths(mesh, metric)).within10;
  r.warmStarted = meshOptions.placement.warmStart.empty() &&
                  (options.warmStart == RemeshOptions::WarmStart::On ||
                   (options.warmStart == RemeshOptions::WarmStart::IfFits && r.inputWithin10 >= kWarmStartFit));
  if (r.warmStarted) {
    std::vector<char> onBoundary(std::size_t(mesh.numVertices()), 0);
    for (const auto& e : mesh.boundaryEdges) onBoundary[std::size_t(e.a)] = onBoundary[std::size_t(e.b)] = 1;
    for (int v = 0; v < mesh.numVertices(); ++v)
      if (!onBoundary[std::size_t(v)]) meshOptions.placement.warmStart.push_back(mesh.vertices[std::size_t(v)]);
  }
  const BackgroundMetricField field(std::move(mesh), std::move(metric),
                                    BackgroundMetricField::MeshCheck::AlreadyValidated);
  r.secondsBackgroundField = watch.seconds();
  // 5. The new mesh.
  watch.restart();
  mesher::MeshResult m = mesher::meshDomain(domain, field, meshOptions);
  r.secondsMeshing = watch.seconds();
  r.mesh = std::move(m.mesh);
  r.metric = std::move(m.metric);
  r.stats = m.stats;
  return r;
}

mesher::MeshResult remesh(const Domain& domain, const Mesh2& mesh, std::vector<Metric2> metric,
                          const mesher::MeshOptions& options, std::vector<Vec2> rows) {
  const BackgroundMetricField field(mesh, std::move(metric), std::move(rows));
  const bool subdomains =
      !mesh.interfaceEdges.empty() || std::adjacent_find(mesh.triangleRefs.begin(), mesh.triangleRefs.end(),
                                                         std::not_equal_to<>()) != mesh.triangleRefs.end();
  if (!subdomains) return mesher::meshDomain(domain, field, options);
  RemeshResult r;  // the subdomains and interfaces are the mesh's: remeshed from it
  remeshSubdomains(field.mesh(), field, options, "mesh", r);
  return {std::move(r.mesh), std::move(r.metric), r.stats};
}

void requireBoundaryEdges(Mesh2& mesh) {
  std::set<std::array<int, 2>> have;
  for (const auto& e : mesh.requiredEdges) have.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  const auto add = [&](const BoundaryEdge& e) {
    if (have.insert({std::min(e.a, e.b), std::max(e.a, e.b)}).second) mesh.requiredEdges.push_back({e.a, e.b});
  };
  for (const auto& e : mesh.boundaryEdges) add(e);
  for (const auto& e : mesh.interfaceEdges) add(e);
}

}  // namespace ablmg::adapt
