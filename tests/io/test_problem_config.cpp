// Tests of cli/problem_config.hpp (compiled into test_io by tests/cli/io_cli.cmake): the
// "problem" of `ablmg solve` / `ablmg adapt` configs, and errors that name the file.
#include "ablmg/cli/problem_config.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

using namespace ablmg;

static std::string errorOf(const std::string& text) {
  try {
    cli::problemFromJson(nlohmann::json::parse(text), "fuzz.json");
  } catch (const InputError& e) { return e.what(); }
  return "(no error)";
}

TEST(ProblemConfig, ExpressionsEvaluateAndNamedProblemsHaveTheirDomain) {
  const auto s = cli::problemFromJson(nlohmann::json::parse(R"({"problem": {"kappa": "1+x", "f": 2,
      "dirichlet": {"1": "x*y", "default": "0"}, "neumann": {"3": "y"}, "exact": {"u": "x^2", "ux": "2*x", "uy": 0}}})"),
                                      "c.json");
  EXPECT_DOUBLE_EQ(s.problem.kappa.fn(0.5, 0), 1.5);
  EXPECT_DOUBLE_EQ(s.problem.f.fn(0, 0), 2);
  EXPECT_DOUBLE_EQ(s.problem.dirichlet.at(1).fn(2, 3), 6);
  EXPECT_DOUBLE_EQ(s.problem.neumann.at(3).fn(0, 0.25), 0.25);
  EXPECT_DOUBLE_EQ(s.exact.grad(1.5, 0).x(), 3);
  EXPECT_FALSE(s.domain);
  const auto w =
      cli::problemFromJson(nlohmann::json::parse(R"({"problem": "wavefront", "params": {"alpha": 20}})"), "c.json");
  ASSERT_TRUE(w.domain);
  EXPECT_NEAR(w.domain->area(), 1.0, 1e-15);
}

TEST(ProblemConfig, LibraryProblemErrorsNameTheFile) {
  // Found by fuzz_problem (the exact input): the library's "unknown problem" and parameter
  // errors came without the config file's name, unlike every other error of the config.
  EXPECT_EQ(
      errorOf(R"({"problem": "sin-ee", "s": {"ala": 10}})").rfind("fuzz.json: unknown problem 'sin-ee' (valid: ", 0),
      0u)
      << errorOf(R"({"problem": "sin-ee", "s": {"ala": 10}})");
  EXPECT_EQ(errorOf(R"({"problem": "peak", "params": {"beta": 1}})")
                .rfind("fuzz.json: problem 'peak': unknown parameter 'beta'", 0),
            0u)
      << errorOf(R"({"problem": "peak", "params": {"beta": 1}})");
  EXPECT_EQ(
      errorOf(R"({"problem": "peak", "params": {"alpha": -1}})").rfind("fuzz.json: problem 'peak': alpha = -1", 0), 0u)
      << errorOf(R"({"problem": "peak", "params": {"alpha": -1}})");
  EXPECT_EQ(errorOf(R"({"problem": {"f": "sin("}})").rfind("fuzz.json: problem.f: bad expression 'sin('", 0), 0u);
}
