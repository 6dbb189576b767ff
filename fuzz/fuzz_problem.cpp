// Fuzzes the "problem" JSON of `ablmg solve` / `ablmg adapt` (cli/problem_config.hpp):
// problemFromJson on any JSON object with a "problem" key (the commands require one before
// calling it) gives an InputError or a ProblemSetup whose functions (κ, f, Dirichlet and Neumann
// data, exact u and ∇u) can be evaluated at a few points without crashing; every InputError
// names the file ("fuzz.json: ...", the header's promise). Values are not
// checked: a user's expression may well be NaN somewhere (assemble() rejects κ ≤ 0 or NaN).
#include "ablmg/cli/problem_config.hpp"
#include "ablmg/core/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>

namespace {

volatile double sink;  // keeps the evaluations from being optimised away

void evaluate(const ablmg::fem::ScalarData& d) {
  for (double x : {0.0, 0.25, 1.0, -3.5})
    if (d.fn) sink = d.fn(x, 1 - x);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const nlohmann::json config = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (config.is_discarded() || !config.is_object() || !config.contains("problem")) return 0;
  try {
    const ablmg::cli::ProblemSetup s = ablmg::cli::problemFromJson(config, "fuzz.json");
    evaluate(s.problem.kappa);
    evaluate(s.problem.f);
    evaluate(s.problem.dirichletDefault);
    for (const auto& entry : s.problem.dirichlet) evaluate(entry.second);
    for (const auto& entry : s.problem.neumann) evaluate(entry.second);
    for (double x : {0.0, 0.3, 2.0}) {
      if (s.exact.u) sink = s.exact.u(x, x / 2);
      if (s.exact.grad) sink = s.exact.grad(x, x / 2).x();
    }
    if (s.domain && !(s.domain->area() > 0)) __builtin_trap();
  } catch (const ablmg::InputError& e) {
    if (std::string_view(e.what()).substr(0, 10) != "fuzz.json:") __builtin_trap();
  }
  return 0;
}
