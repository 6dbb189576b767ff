#include "core/metric_field.hpp"

#include "core/error.hpp"

#include <muParser.h>

#include <cmath>

namespace ablmg {

void MetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out) const {
  ABLMG_ASSERT(points.size() == out.size(), "");
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = at(points[i]);
}

// ---------------------------------------------------------------- analytic (muparser)

struct AnalyticMetricField::Impl {
  Form form;
  std::string source;
  mutable double x = 0, y = 0;
  mu::Parser parsers[3];
};

AnalyticMetricField::AnalyticMetricField(Form form, const std::string& e1, const std::string& e2,
                                         const std::string& e3, const std::string& source)
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
}

AnalyticMetricField::~AnalyticMetricField() = default;

Metric2 AnalyticMetricField::at(const Vec2& p) const {
  impl_->x = p.x();
  impl_->y = p.y();
  double v[3];
  for (int k = 0; k < 3; ++k) {
    try {
      v[k] = impl_->parsers[k].Eval();
    } catch (const mu::Parser::exception_type& e) {
      throw InputError(impl_->source + ": evaluation failed at (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                       "): " + e.GetMsg());
    }
  }
  std::ostringstream where;
  where << impl_->source << " at (" << p.x() << ", " << p.y() << ")";
  return impl_->form == Form::Sizes ? Metric2::fromSizes(v[0], v[1], v[2], where.str())
                                    : Metric2::fromTensor(v[0], v[1], v[2], where.str());
}

// ---------------------------------------------------------------- background mesh

BackgroundMetricField::BackgroundMetricField(Mesh2 mesh, std::vector<Metric2> metrics)
    : mesh_(std::move(mesh)), metrics_(std::move(metrics)) {
  ABLMG_REQUIRE(int(metrics_.size()) == mesh_.numVertices(),
                "background metric: " << metrics_.size() << " tensors for a mesh of " << mesh_.numVertices() << " vertices");
  const MeshValidation v = mesh_.validate();
  ABLMG_REQUIRE(v.ok, "background metric: the background mesh is not valid: " << v.firstProblem);
  logs_.reserve(metrics_.size());
  for (const auto& m : metrics_) logs_.push_back(m.logm());
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

void BackgroundMetricField::evaluate(std::span<const Vec2> points, std::span<Metric2> out) const {
  int hint = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto loc = locator_->locate(points[i], hint);
    hint = loc.triangle;
    out[i] = interpolate(loc);
  }
}

} // namespace ablmg
