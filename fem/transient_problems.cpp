#include "ablmg/fem/transient_problems.hpp"

#include "ablmg/core/error.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace ablmg::fem {
namespace {

std::map<std::string, double> merged(const std::string& name, std::map<std::string, double> defaults,
                                     const std::map<std::string, double>& given) {
  for (const auto& [key, value] : given) {
    auto it = defaults.find(key);
    if (it == defaults.end()) {
      std::ostringstream valid;
      for (const auto& d : defaults) valid << (valid.tellp() ? ", " : "") << d.first;
      ABLMG_REQUIRE(false, "transient problem '" << name << "': unknown parameter '" << key
                                                 << "' (valid: " << valid.str() << ")");
    }
    ABLMG_REQUIRE(std::isfinite(value),
                  "transient problem '" << name << "': parameter " << key << " = " << value << " is not finite");
    it->second = value;
  }
  ABLMG_REQUIRE(defaults.at("kappa") > 0,
                "transient problem '" << name << "': kappa must be > 0 (got " << defaults.at("kappa") << ")");
  return defaults;
}

TransientProblem movingPeak(const std::map<std::string, double>& given) {
  TransientProblem p;
  p.name = "movingpeak";
  p.params =
      merged(p.name,
             {{"alpha", 500}, {"radius", 0.25}, {"omega", std::numbers::pi}, {"xc", 0.5}, {"yc", 0.5}, {"kappa", 0.01}},
             given);
  const double a = p.params["alpha"], r = p.params["radius"], w = p.params["omega"], xc = p.params["xc"],
               yc = p.params["yc"], k = p.params["kappa"];
  ABLMG_REQUIRE(a > 0, "transient problem 'movingpeak': alpha must be > 0 (got " << a << ")");
  p.formula = "exp(-alpha |x - c(t)|^2), c(t) = (xc + radius cos(omega t), yc + radius sin(omega t))";
  p.domain = Domain::rectangle(0, 0, 1, 1);
  p.kappa = k;
  p.tStart = 0;
  p.tEnd = 0.5;
  p.dt = 0.001;
  p.u = [=](double x, double y, double t) {
    const double dx = x - xc - r * std::cos(w * t), dy = y - yc - r * std::sin(w * t);
    return std::exp(-a * (dx * dx + dy * dy));
  };
  p.grad = [=](double x, double y, double t) -> Vec2 {
    const double dx = x - xc - r * std::cos(w * t), dy = y - yc - r * std::sin(w * t);
    const double u = std::exp(-a * (dx * dx + dy * dy));
    return Vec2(-2 * a * dx * u, -2 * a * dy * u);
  };
  p.f = [=](double x, double y, double t) {
    const double dx = x - xc - r * std::cos(w * t), dy = y - yc - r * std::sin(w * t);
    const double d2 = dx * dx + dy * dy, u = std::exp(-a * d2);
    // c'(t) = r ω (−sin ωt, cos ωt); u_t = 2α (x − c)·c' u; Δu = (4α² d² − 4α) u
    const double ut = 2 * a * (dx * (-r * w * std::sin(w * t)) + dy * (r * w * std::cos(w * t))) * u;
    return ut - k * (4 * a * a * d2 - 4 * a) * u;
  };
  return p;
}

TransientProblem front(const std::map<std::string, double>& given) {
  TransientProblem p;
  p.name = "front";
  p.params = merged(
      p.name, {{"epsilon", 0.02}, {"speed", 0.5}, {"offset", 0.25}, {"angle", std::numbers::pi / 6}, {"kappa", 0.01}},
      given);
  const double e = p.params["epsilon"], v = p.params["speed"], c = p.params["offset"], th = p.params["angle"],
               k = p.params["kappa"];
  ABLMG_REQUIRE(e > 0, "transient problem 'front': epsilon must be > 0 (got " << e << ")");
  const double nx = std::cos(th), ny = std::sin(th);
  p.formula = "tanh((x cos(angle) + y sin(angle) - speed t - offset) / epsilon)";
  p.domain = Domain::rectangle(0, 0, 1, 1);
  p.kappa = k;
  p.tStart = 0;
  p.tEnd = 0.6;
  p.dt = 0.001;
  p.u = [=](double x, double y, double t) { return std::tanh((nx * x + ny * y - v * t - c) / e); };
  p.grad = [=](double x, double y, double t) -> Vec2 {
    const double th2 = std::tanh((nx * x + ny * y - v * t - c) / e), s2 = 1 - th2 * th2;
    return Vec2(nx * s2 / e, ny * s2 / e);
  };
  p.f = [=](double x, double y, double t) {
    const double th2 = std::tanh((nx * x + ny * y - v * t - c) / e), s2 = 1 - th2 * th2;
    // u_t = −v/ε sech², Δu = −2 tanh sech² / ε² (|n| = 1)
    return -v / e * s2 + k * 2 * th2 * s2 / (e * e);
  };
  return p;
}

}  // namespace

ExactSolution TransientProblem::exactAt(double t) const {
  const SpaceTimeFn uu = u;
  const SpaceTimeGradientFn gg = grad;
  return {[uu, t](double x, double y) { return uu(x, y, t); },
          [gg, t](double x, double y) -> Vec2 { return gg(x, y, t); },
          true,
          {}};
}

std::vector<std::string> transientProblemNames() { return {"movingpeak", "front"}; }

TransientProblem makeTransientProblem(const std::string& name, const std::map<std::string, double>& params) {
  if (name == "movingpeak") return movingPeak(params);
  if (name == "front") return front(params);
  ABLMG_REQUIRE(false, "unknown transient problem '" << name << "' (valid: movingpeak, front)");
  return {};
}

}  // namespace ablmg::fem
