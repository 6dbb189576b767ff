#include "ablmg/core/metric_field.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ablmg {

void MetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out) const {
  ABLMG_ASSERT(points.size() == out.size(), "");
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = at(points[i]);
}

void MetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out, std::span<int> hints) const {
  (void)hints;
  evaluate(points, out);
}

void MetricField::sqrtDeterminants(std::span<const Vec2> points, std::span<double> out) const {
  ABLMG_ASSERT(points.size() == out.size(), "");
  std::vector<Metric2> ms(points.size());
  evaluate(points, ms);
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = std::sqrt(ms[i].det());
}

namespace {
Vec2 cellCentre(const Vec2& lo, const Vec2& d, int x, int y) {
  return Vec2(lo + Vec2((x + 0.5) * d.x(), (y + 0.5) * d.y()));
}
}  // namespace

void MetricField::gridSqrtDeterminants(const Vec2& lo, const Vec2& d, int gx, int gy, std::span<const char> mask,
                                       std::span<double> out) const {
  ABLMG_ASSERT(mask.size() == std::size_t(gx) * std::size_t(gy) && out.size() == mask.size(), "");
  std::vector<Vec2> pts;
  std::vector<std::size_t> at;
  for (int y = 0; y < gy; ++y)
    for (int x = 0; x < gx; ++x)
      if (const std::size_t i = std::size_t(y) * std::size_t(gx) + std::size_t(x); mask[i]) {
        pts.push_back(cellCentre(lo, d, x, y));
        at.push_back(i);
      }
  std::vector<double> v(pts.size());
  sqrtDeterminants(pts, v);
  for (std::size_t k = 0; k < at.size(); ++k) out[at[k]] = v[k];
}

Vec2 MetricField::latticeRow(const Vec2&, int&) const { return Vec2::Zero(); }

// ---------------------------------------------------------------- background mesh

BackgroundMetricField::BackgroundMetricField(Mesh2 mesh, std::vector<Metric2> metrics, std::vector<Vec2> rows,
                                             MeshCheck check)
    : BackgroundMetricField(std::move(mesh), std::move(metrics), check) {
  ABLMG_REQUIRE(
      rows.empty() || long(rows.size()) == long(mesh_.numVertices()),
      "background metric: " << rows.size() << " lattice rows for a mesh of " << mesh_.numVertices() << " vertices");
  for (std::size_t v = 0; v < rows.size(); ++v)
    ABLMG_REQUIRE(rows[v].allFinite() && rows[v].norm() <= 1 + 1e-12,
                  "background metric: lattice row " << v << " (" << rows[v].x() << ", " << rows[v].y()
                                                    << ") must be finite with norm <= 1");
  rows_ = std::move(rows);
}

Vec2 BackgroundMetricField::latticeRow(const Vec2& p, int& hint) const {
  if (rows_.empty()) return Vec2::Zero();
  const auto loc = locator_->locate(p, locator_->startNear(p, hint));
  hint = loc.triangle;
  const auto& tr = mesh_.triangles[loc.triangle];
  return loc.bary[0] * rows_[tr[0]] + loc.bary[1] * rows_[tr[1]] + loc.bary[2] * rows_[tr[2]];
}

BackgroundMetricField::BackgroundMetricField(Mesh2 mesh, std::vector<Metric2> metrics, MeshCheck check)
    : mesh_(std::move(mesh)), metrics_(std::move(metrics)) {
  ABLMG_REQUIRE(
      int(metrics_.size()) == mesh_.numVertices(),
      "background metric: " << metrics_.size() << " tensors for a mesh of " << mesh_.numVertices() << " vertices");
  if (check == MeshCheck::Validate) {
    const MeshValidation v = mesh_.validate();
    ABLMG_REQUIRE(v.ok, "background metric: the background mesh is not valid: " << v.firstProblem);
  }
  logs_.resize(metrics_.size());
  const long n = long(metrics_.size());
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long i = 0; i < n; ++i) logs_[std::size_t(i)] = metrics_[std::size_t(i)].logm();
  locator_ = std::make_unique<PointLocator>(mesh_);
}

Metric2 BackgroundMetricField::interpolate(const PointLocator::Location& loc) const {
  const auto& tr = mesh_.triangles[loc.triangle];
  const Metric2& m0 = metrics_[tr[0]];
  if (metrics_[tr[1]].m11() == m0.m11() && metrics_[tr[1]].m12() == m0.m12() && metrics_[tr[1]].m22() == m0.m22() &&
      metrics_[tr[2]].m11() == m0.m11() && metrics_[tr[2]].m12() == m0.m12() && metrics_[tr[2]].m22() == m0.m22())
    return m0;
  Metric2 l = Metric2::raw(0, 0, 0);
  for (int k = 0; k < 3; ++k) l = l + loc.bary[k] * logs_[tr[k]];
  return l.expm();
}

Metric2 BackgroundMetricField::at(const Vec2& p) const { return interpolate(locator_->locate(p)); }

void BackgroundMetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out, std::span<int> hints) const {
  ABLMG_ASSERT(points.size() == out.size() && points.size() == hints.size(), "");
  // Fixed chunks of consecutive points (the same answers for any thread count); a point
  // starts at its hint (without one: the chunk's previous answer) or at the grid's start
  // (PointLocator::startNear), whichever is closer: a stale hint costs no long walk.
  // One chunk is evaluated outside any OpenMP region: the lattice and the post-pass ask for one
  // point at a time, and entering even an if(false) region costs ~1 µs (a team set up and torn
  // down): the lattice of a 10⁶-triangle remesh took 2.2 s instead of 1.3 s.
  constexpr long kChunk = 256;
  const long n = long(points.size()), chunks = (n + kChunk - 1) / kChunk;
  const auto chunk = [&](long c) {
    int previous = -1;
    for (long i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      const Vec2& p = points[std::size_t(i)];
      const int h = hints[std::size_t(i)];
      const auto loc = locator_->locate(p, locator_->startNear(p, h >= 0 ? h : previous));
      previous = hints[std::size_t(i)] = loc.triangle;
      out[std::size_t(i)] = interpolate(loc);
    }
  };
  if (chunks <= 1) {
    if (chunks == 1) chunk(0);
    return;
  }
  // Point location allocates on its rescue path: a failure (std::bad_alloc) is rethrown after
  // the region, the lowest chunk's (core/parallel_failure.hpp).
  ParallelFailure failure;
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c) failure.run(c, [&] { chunk(c); });
  failure.rethrow();
}

void BackgroundMetricField::sqrtDeterminants(std::span<const Vec2> points, std::span<double> out) const {
  ABLMG_ASSERT(points.size() == out.size(), "");
  constexpr long kChunk = 512;
  const long n = long(points.size()), chunks = (n + kChunk - 1) / kChunk;
  ParallelFailure failure;  // as in evaluate()
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long c = 0; c < chunks; ++c)
    failure.run(c, [&] {
      int hint = -1;
      for (long i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
        const auto loc = locator_->locate(points[std::size_t(i)], hint);
        hint = loc.triangle;
        const auto& tr = mesh_.triangles[loc.triangle];
        double halfTrace = 0;
        for (int k = 0; k < 3; ++k) halfTrace += loc.bary[k] * 0.5 * (logs_[tr[k]].m11() + logs_[tr[k]].m22());
        out[std::size_t(i)] = std::exp(halfTrace);
      }
    });
  failure.rethrow();
}

void BackgroundMetricField::gridSqrtDeterminants(const Vec2& lo, const Vec2& d, int gx, int gy,
                                                 std::span<const char> mask, std::span<double> out) const {
  ABLMG_ASSERT(mask.size() == std::size_t(gx) * std::size_t(gy) && out.size() == mask.size(), "");
  ABLMG_ASSERT(d.x() > 0 && d.y() > 0, "");
  // The triangles bucketed by bands of kBand grid rows (in triangle order within a band), from
  // the rows of the cell centres in their bounding boxes (a centre that rounding puts just out
  // of a box lies on an edge or a vertex, so also in a neighbour, or is located below).
  constexpr int kBand = 16;
  const int bands = (gy + kBand - 1) / kBand, nt = mesh_.numTriangles();
  const auto cellRange = [](double a, double b, double o, double h, int g) {
    const int i0 = std::max(0, int(std::ceil((a - o) / h - 0.5)));
    const int i1 = std::min(g - 1, int(std::floor((b - o) / h - 0.5)));
    return std::pair{i0, i1};
  };
  std::vector<int> first(std::size_t(bands) + 1, 0), ids;
  std::vector<std::array<int, 2>> rows(static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const auto& tr = mesh_.triangles[std::size_t(t)];
    const Vec2 &a = mesh_.vertices[tr[0]], &b = mesh_.vertices[tr[1]], &c = mesh_.vertices[tr[2]];
    const auto [y0, y1] =
        cellRange(std::min({a.y(), b.y(), c.y()}), std::max({a.y(), b.y(), c.y()}), lo.y(), d.y(), gy);
    rows[std::size_t(t)] = {y0, y1};
    if (y0 <= y1)
      for (int band = y0 / kBand; band <= y1 / kBand; ++band) ++first[std::size_t(band) + 1];
  }
  for (int band = 0; band < bands; ++band) first[std::size_t(band) + 1] += first[std::size_t(band)];
  ids.resize(std::size_t(first.back()));
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (int t = 0; t < nt; ++t)
    if (rows[std::size_t(t)][0] <= rows[std::size_t(t)][1])
      for (int band = rows[std::size_t(t)][0] / kBand; band <= rows[std::size_t(t)][1] / kBand; ++band)
        ids[std::size_t(fill[std::size_t(band)]++)] = t;
  std::vector<char> done(mask.size(), 0);
#pragma omp parallel for schedule(dynamic, 1) if (bands > 1 && nt >= 2048)
  for (int band = 0; band < bands; ++band)
    for (int j = first[std::size_t(band)]; j < first[std::size_t(band) + 1]; ++j) {
      const int t = ids[std::size_t(j)];
      const auto& tr = mesh_.triangles[std::size_t(t)];
      const Vec2 &a = mesh_.vertices[tr[0]], &b = mesh_.vertices[tr[1]], &c = mesh_.vertices[tr[2]];
      const auto [x0, x1] =
          cellRange(std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}), lo.x(), d.x(), gx);
      const int y0 = std::max(rows[std::size_t(t)][0], band * kBand);
      const int y1 = std::min(rows[std::size_t(t)][1], band * kBand + kBand - 1);
      const double area2 = signedArea2(a, b, c);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const std::size_t i = std::size_t(y) * std::size_t(gx) + std::size_t(x);
          if (!mask[i] || done[i]) continue;
          const Vec2 p = cellCentre(lo, d, x, y);
          if (orient2d(b, c, p) < 0 || orient2d(c, a, p) < 0 || orient2d(a, b, p) < 0) continue;
          // PointLocator's barycentric weights (clamped to ≥ 0, normalised) and the sum of
          // sqrtDeterminants, in the same order: the same bits.
          double w[3] = {signedArea2(p, b, c) / area2, signedArea2(a, p, c) / area2, signedArea2(a, b, p) / area2};
          double s = 0;
          for (double& v : w) s += (v = std::max(0.0, v));
          double halfTrace = 0;
          for (int k = 0; k < 3; ++k)
            halfTrace += (s > 0 ? w[k] / s : 1.0 / 3.0) * 0.5 * (logs_[tr[k]].m11() + logs_[tr[k]].m22());
          out[i] = std::exp(halfTrace);
          done[i] = 1;
        }
    }
  // Centres outside every triangle: located (and extrapolated) one by one.
  std::vector<char> rest(mask.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    rest[i] = char(mask[i] && !done[i]);
    any = any || rest[i];
  }
  if (any) MetricField::gridSqrtDeterminants(lo, d, gx, gy, rest, out);
}

void BackgroundMetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out) const {
  int previous = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto loc = locator_->locate(points[i], locator_->startNear(points[i], previous));
    previous = loc.triangle;
    out[i] = interpolate(loc);
  }
}

}  // namespace ablmg
