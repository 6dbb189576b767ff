// AnalyticMetricField: the muparser-backed metric field of metric_field.hpp. Kept apart from
// metric_field.cpp so that ablmg_core links no expression parser (this file is in ablmg_expr).
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"

#include <muParser.h>

#include <cmath>
#include <sstream>
#include <string>

namespace ablmg {

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

}  // namespace ablmg
