#pragma once
/// The "problem" of `ablmg solve` and `ablmg adapt` configs (JSON) → fem::PoissonProblem and,
/// when given, the exact solution:
///
///   "problem": "wavefront", "params": {"alpha": 50}      a library problem (fem/test_problems.hpp):
///                                                        its domain, κ = 1, u on the boundary, exact u
///   "problem": {"kappa": "1", "f": "2*pi^2*sin(pi*x)*sin(pi*y)",
///               "dirichlet": {"1": "0", "default": "0"}, per boundary tag; "default": all others
///               "neumann": {"3": "0"},                   flux κ ∂u/∂n per tag (0 where not given)
///               "exact": {"u": "...", "ux": "...", "uy": "..."}}   optional, for errors
///
/// Expressions are muparser strings in x, y (constants pi, e) or numbers, each checked once at
/// (0.5, 0.5) when read. Expression functions share a parser object, so they are not thread-safe
/// (PoissonProblem::threadSafeFunctions and ExactSolution::threadSafe stay false). Errors are
/// ablmg::InputError naming `src` and the key path: "c.json: problem.f: bad expression ...".
#include "ablmg/core/domain.hpp"
#include "ablmg/fem/error_norms.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <optional>
#include <string>

namespace ablmg::cli {

struct ProblemSetup {
  fem::PoissonProblem problem;
  fem::ExactSolution exact;      ///< empty u when unknown
  std::optional<Domain> domain;  ///< a library problem's own domain
  nlohmann::json echo;           ///< the resolved problem, for reports
};

/// Reads config["problem"] (and config["params"] for a library problem).
ProblemSetup problemFromJson(const nlohmann::json& config, const std::string& src);

/// The JSON object in file `path`; InputError "PATH: cannot open" / "PATH: invalid JSON: ...".
nlohmann::json readJsonFile(const std::string& path);

/// Throws InputError "<where>: unknown key 'k' (valid: ...)" for a key of `j` not in `allowed`,
/// or when `j` is not an object.
void requireKeys(const nlohmann::json& j, const std::string& where, std::initializer_list<const char*> allowed);

}  // namespace ablmg::cli
