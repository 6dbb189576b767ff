#include "ablmg/cli/problem_config.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/test_problems.hpp"

#include <muParser.h>

#include <fstream>
#include <memory>
#include <numbers>

namespace ablmg::cli {
namespace {

using nlohmann::json;

/// A muparser expression in x, y as a ScalarFn. Checked once at (0.5, 0.5) when built.
fem::ScalarFn expression(const std::string& text, const std::string& where) {
  struct Expr {
    mu::Parser parser;
    double x = 0, y = 0;
  };
  auto e = std::make_shared<Expr>();
  try {
    e->parser.DefineVar("x", &e->x);
    e->parser.DefineVar("y", &e->y);
    e->parser.DefineConst("pi", std::numbers::pi);
    e->parser.DefineConst("e", std::numbers::e);
    e->parser.SetExpr(text);
    e->x = e->y = 0.5;
    e->parser.Eval();
  } catch (const mu::Parser::exception_type& ex) {
    ABLMG_REQUIRE(false, where << ": bad expression '" << text << "': " << ex.GetMsg());
  }
  return [e](double x, double y) {
    e->x = x;
    e->y = y;
    return e->parser.Eval();
  };
}

/// An expression given as a JSON string or number.
fem::ScalarFn expressionOf(const json& j, const std::string& where) {
  if (j.is_number()) {
    const double c = j.get<double>();
    return [c](double, double) { return c; };
  }
  ABLMG_REQUIRE(j.is_string(), where << ": expected an expression string or a number, got " << j.type_name());
  return expression(j.get<std::string>(), where);
}

int tagOf(const std::string& key, const std::string& where) {
  std::size_t used = 0;
  int tag = 0;
  try {
    tag = std::stoi(key, &used);
  } catch (const std::exception&) { used = 0; }
  ABLMG_REQUIRE(used == key.size() && !key.empty(), where << ": boundary tag '" << key << "' is not an integer");
  return tag;
}

}  // namespace

json readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  ABLMG_REQUIRE(in, path << ": cannot open");
  try {
    return json::parse(in);
  } catch (const json::parse_error& e) { ABLMG_REQUIRE(false, path << ": invalid JSON: " << e.what()); }
  return {};
}

void requireKeys(const nlohmann::json& j, const std::string& where, std::initializer_list<const char*> allowed) {
  ABLMG_REQUIRE(j.is_object(), where << ": expected an object, got " << j.type_name());
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      ABLMG_REQUIRE(false, where << ": unknown key '" << key << "' (valid: " << list << ")");
    }
  }
}

ProblemSetup problemFromJson(const json& config, const std::string& src) {
  ProblemSetup s;
  const json& p = config.at("problem");
  if (p.is_string()) {
    std::map<std::string, double> params;
    if (config.contains("params")) {
      ABLMG_REQUIRE(config["params"].is_object(), src << ": params: expected an object");
      for (const auto& [k, v] : config["params"].items()) {
        ABLMG_REQUIRE(v.is_number(), src << ": params." << k << ": expected a number, got " << v.type_name());
        params[k] = v.get<double>();
      }
    }
    fem::TestProblem tp;
    try {
      tp = fem::makeProblem(p.get<std::string>(), params);
    } catch (const InputError& e) {
      throw InputError(src + ": " + e.what());  // name the file, as every other error here does
    }
    s.problem = tp.poisson();
    s.exact = tp.exact();
    s.domain = tp.domain;
    s.echo = {{"name", tp.name}, {"u", tp.formula}, {"params", tp.params}};
    return s;
  }
  ABLMG_REQUIRE(!config.contains("params"), src << ": params: only for a named problem");
  const std::string w = src + ": problem";
  requireKeys(p, w, {"kappa", "f", "dirichlet", "neumann", "exact"});
  if (p.contains("kappa")) s.problem.kappa = expressionOf(p["kappa"], w + ".kappa");
  if (p.contains("f")) s.problem.f = expressionOf(p["f"], w + ".f");
  if (p.contains("dirichlet")) {
    ABLMG_REQUIRE(p["dirichlet"].is_object(), w << ".dirichlet: expected an object {tag: expression}");
    for (const auto& [k, v] : p["dirichlet"].items()) {
      if (k == "default")
        s.problem.setDirichletEverywhere(expressionOf(v, w + ".dirichlet.default"));
      else
        s.problem.dirichlet[tagOf(k, w + ".dirichlet")] = expressionOf(v, w + ".dirichlet." + k);
    }
  }
  if (p.contains("neumann")) {
    ABLMG_REQUIRE(p["neumann"].is_object(), w << ".neumann: expected an object {tag: expression}");
    for (const auto& [k, v] : p["neumann"].items())
      s.problem.neumann[tagOf(k, w + ".neumann")] = expressionOf(v, w + ".neumann." + k);
  }
  if (p.contains("exact")) {
    const json& e = p["exact"];
    requireKeys(e, w + ".exact", {"u", "ux", "uy"});
    ABLMG_REQUIRE(e.contains("u"), w << ".exact: needs u");
    s.exact.u = expressionOf(e["u"], w + ".exact.u");
    if (e.contains("ux") || e.contains("uy")) {
      ABLMG_REQUIRE(e.contains("ux") && e.contains("uy"), w << ".exact: give both ux and uy");
      auto ux = expressionOf(e["ux"], w + ".exact.ux"), uy = expressionOf(e["uy"], w + ".exact.uy");
      s.exact.grad = [ux, uy](double x, double y) -> Vec2 { return Vec2(ux(x, y), uy(x, y)); };
    }
  }
  s.echo = p;
  return s;
}

}  // namespace ablmg::cli
