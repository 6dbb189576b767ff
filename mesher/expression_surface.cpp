// makeExpressionSurface: the muparser-backed parametric surface of surface.hpp. Kept apart
// from surface.cpp so that ablmg_mesher links no expression parser (this file is in ablmg_expr).
#include "ablmg/core/error.hpp"
#include "ablmg/mesher/surface.hpp"

#include <muParser.h>

#include <numbers>
#include <string>

namespace ablmg::mesher {
namespace {

constexpr double kPi = std::numbers::pi;

class ExpressionSurface final : public ParametricSurface {
 public:
  ExpressionSurface(const std::string& x, const std::string& y, const std::string& z, Domain domain,
                    const std::string& source, bool periodic)
      : domain_(std::move(domain)), text_("x=" + x + ", y=" + y + ", z=" + z), periodic_(periodic) {
    const std::string* e[3] = {&x, &y, &z};
    const char* names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      try {
        p_[k].DefineVar("u", &u_);
        p_[k].DefineVar("v", &v_);
        p_[k].DefineConst("pi", kPi);
        p_[k].SetExpr(*e[k]);
        p_[k].Eval();
      } catch (const mu::Parser::exception_type& err) {
        throw InputError(source + "." + names[k] + ": bad expression '" + *e[k] + "': " + err.GetMsg());
      }
    }
  }
  Vec3 point(const Vec2& uv) const override {
    u_ = uv.x();
    v_ = uv.y();
    Vec3 r(p_[0].Eval(), p_[1].Eval(), p_[2].Eval());
    ABLMG_REQUIRE(r.allFinite(), "surface: r(" << uv.x() << ", " << uv.y() << ") is not finite");
    return r;
  }
  const Domain& parameterDomain() const override { return domain_; }
  std::string description() const override { return text_; }
  bool periodic() const override { return periodic_; }

 private:
  Domain domain_;
  std::string text_;
  bool periodic_;
  mutable double u_ = 0, v_ = 0;
  mu::Parser p_[3];
};

}  // namespace

std::unique_ptr<ParametricSurface> makeExpressionSurface(const std::string& x, const std::string& y,
                                                         const std::string& z, double u0, double v0, double u1,
                                                         double v1, const std::string& source, bool periodic) {
  return std::make_unique<ExpressionSurface>(x, y, z, Domain::rectangle(u0, v0, u1, v1), source, periodic);
}

}  // namespace ablmg::mesher
