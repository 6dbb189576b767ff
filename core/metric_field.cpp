#include "ablmg/core/metric_field.hpp"

#include "ablmg/core/error.hpp"

#include <muParser.h>

#include <algorithm>
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

// ---------------------------------------------------------------- analytic (muparser)

struct AnalyticMetricField::Impl {
  Form form;
  std::string source;
  mutable double x = 0, y = 0;
  mu::Parser parsers[3];
  bool constant = false;  ///< no expression uses x or y: evaluated once
  Metric2 value;
  Metric2 evalAt(const Vec2& p) const;
};

AnalyticMetricField::AnalyticMetricField(Form form, const std::string& e1, const std::string& e2, const std::string& e3,
                                         const std::string& source)
    : impl_(std::make_unique<Impl>()) {
  impl_->form = form;
  impl_->source = source;
  const std::string names[2][3] = {{"h1", "h2", "theta"}, {"m11", "m12", "m22"}};
  const std::string* exprs[3] = {&e1, &e2, &e3};
  for (int k = 0; k < 3; ++k) {
    auto& p = impl_->parsers[k];
    const std::string field = source + "." + names[form == Form::Tensor][k];
    try {
      p.DefineVar("x", &impl_->x);
      p.DefineVar("y", &impl_->y);
      p.DefineConst("pi", M_PI);
      p.SetExpr(*exprs[k]);
      p.Eval();  // forces parsing: syntax errors and unknown variables surface here
    } catch (const mu::Parser::exception_type& e) {
      throw InputError(field + ": bad expression '" + *exprs[k] + "': " + e.GetMsg());
    }
  }
  // Constant field (e.g. "h1": "0.5"): the mesher then skips every re-evaluation.
  bool usesXY = false;
  for (auto& p : impl_->parsers) {
    const auto& used = p.GetUsedVar();
    usesXY = usesXY || used.count("x") || used.count("y");
  }
  if (!usesXY) {
    impl_->value = impl_->evalAt(Vec2::Zero());  // a bad constant (h1 = -1) fails here, naming the field
    impl_->constant = true;
  }
}

AnalyticMetricField::~AnalyticMetricField() = default;

Metric2 AnalyticMetricField::at(const Vec2& p) const {
  if (impl_->constant) return impl_->value;
  return impl_->evalAt(p);
}

Metric2 AnalyticMetricField::Impl::evalAt(const Vec2& p) const {
  x = p.x();
  y = p.y();
  double v[3];
  for (int k = 0; k < 3; ++k) {
    try {
      v[k] = parsers[k].Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw InputError(source + ": evaluation failed at (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                       "): " + e.GetMsg());
    }
  }
  // The location is formatted only on failure: building it per call was ~5 % of a meshing run.
  try {
    return form == Form::Sizes ? Metric2::fromSizes(v[0], v[1], v[2], source)
                               : Metric2::fromTensor(v[0], v[1], v[2], source);
  } catch (const InputError&) {
    std::ostringstream where;
    where << source << " at (" << p.x() << ", " << p.y() << ")";
    if (form == Form::Sizes) return Metric2::fromSizes(v[0], v[1], v[2], where.str());
    return Metric2::fromTensor(v[0], v[1], v[2], where.str());
  }
}

bool AnalyticMetricField::isConstant() const { return impl_->constant; }

// ---------------------------------------------------------------- background mesh

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
  const long n = long(points.size());
#pragma omp parallel for schedule(static) if (n > 256)
  for (long i = 0; i < n; ++i) {
    const int h = hints[std::size_t(i)];
    const auto loc = locator_->locate(points[std::size_t(i)], h >= 0 && h < mesh_.numTriangles() ? h : -1);
    hints[std::size_t(i)] = loc.triangle;
    out[std::size_t(i)] = interpolate(loc);
  }
}

void BackgroundMetricField::sqrtDeterminants(std::span<const Vec2> points, std::span<double> out) const {
  ABLMG_ASSERT(points.size() == out.size(), "");
  constexpr long kChunk = 512;
  const long n = long(points.size()), chunks = (n + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(static) if (n >= 2048)
  for (long c = 0; c < chunks; ++c) {
    int hint = -1;
    for (long i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) {
      const auto loc = locator_->locate(points[std::size_t(i)], hint);
      hint = loc.triangle;
      const auto& tr = mesh_.triangles[loc.triangle];
      double halfTrace = 0;
      for (int k = 0; k < 3; ++k) halfTrace += loc.bary[k] * 0.5 * (logs_[tr[k]].m11() + logs_[tr[k]].m22());
      out[std::size_t(i)] = std::exp(halfTrace);
    }
  }
}

void BackgroundMetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out) const {
  int hint = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto loc = locator_->locate(points[i], hint);
    hint = loc.triangle;
    out[i] = interpolate(loc);
  }
}

}  // namespace ablmg
