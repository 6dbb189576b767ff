// Tests of cli/config.hpp (compiled into test_io by tests/cli/io_cli.cmake): each domain and
// metric form, options, and errors that name the key path.
#include "ablmg/cli/config.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

using namespace ablmg;
static const std::string kData = ABLMG_TEST_DATA;

static std::string errorOf(const std::string& json) {
  try {
    cli::parseConfig(json, "config.json", kData);
  } catch (const InputError& e) { return e.what(); }
  return "(no error)";
}

TEST(Config, RectangleWithAnalyticSizesAndOptions) {
  auto c = cli::parseConfig(R"({"domain": {"rectangle": [0, 0, 2, 1]},
      "metric": {"h1": "0.1", "h2": "0.05 + 0.01*x", "theta": "0.5"},
      "options": {"placement": {"seed": 7, "maxSteps": 12, "tolerance": 1e-4, "bubblesOnly": true}, "connect": {"threads": 1}},
      "outputs": {"mesh": "out.mesh"}})",
                            "config.json", "/base");
  EXPECT_NEAR(c.domain.area(), 2.0, 1e-15);
  const auto e = c.metric->at(Vec2(1, 0)).eigen();
  EXPECT_NEAR(e.h1, 0.1, 1e-12);
  EXPECT_NEAR(e.h2, 0.06, 1e-12);
  EXPECT_EQ(c.options.placement.seed, 7u);
  EXPECT_EQ(c.options.placement.maxSteps, 12);
  EXPECT_TRUE(c.options.placement.bubblesOnly);
  EXPECT_EQ(c.options.connect.threads, 1);
  EXPECT_EQ(c.outputs.mesh, "/base/out.mesh");
  const auto j = cli::meshOptionsToJson(c.options);
  EXPECT_EQ(j["placement"]["maxSteps"], 12);
  EXPECT_EQ(j["placement"]["damping"], mesher::PlacementOptions{}.damping);  // defaults included
}

TEST(Config, DiskLoopsPolyAndBackgroundMetric) {
  auto disk = cli::parseConfig(
      R"({"domain": {"disk": {"center": [1, 2], "radius": 3, "samples": 64}}, "metric": {"h": "0.2"}})", "c", "");
  EXPECT_NEAR(disk.domain.area(), 0.5 * 64 * 9 * std::sin(2 * M_PI / 64), 1e-9);
  auto loops = cli::parseConfig(
      R"({"domain": {"loops": [[[0,0],[4,0],[4,4],[0,4]], [[1,1],[1,2],[2,2],[2,1]]], "tags": [1, [5,5,5,5]]},
                                   "metric": {"m11": "100", "m12": "0", "m22": "400"}})",
      "c", "");
  EXPECT_NEAR(loops.domain.area(), 15.0, 1e-14);
  EXPECT_NEAR(loops.metric->at(Vec2(0, 0)).eigen().h2, 0.05, 1e-15);
  auto poly = cli::parseConfig(
      R"({"domain": {"poly": "square_hole.poly"}, "metric": {"mesh": "square.mesh", "sol": "square.sol"}})", "c",
      kData);
  EXPECT_NEAR(poly.domain.area(), 15.0, 1e-14);
  EXPECT_NEAR(poly.metric->at(Vec2(1, 1)).m11(), 400, 1e-9);  // vertex 3 of square.mesh
}

TEST(Config, SmoothLoops) {
  const char* loops = R"("loops": [[[0,0],[4,0],[4,4],[0,4]], [[1,1],[1,2],[2,2],[2,1]]])";
  const auto parse = [&](const std::string& smooth) {
    return cli::parseConfig(std::string(R"({"domain": {)") + loops + smooth + R"(}, "metric": {"h": "0.2"}})", "c", "");
  };
  const auto plain = parse(""), all = parse(R"(, "smooth": true)");
  for (const auto& l : plain.domain.loops()) EXPECT_FALSE(l.smooth);
  for (const auto& l : all.domain.loops()) EXPECT_TRUE(l.smooth);
  const auto mixed = parse(R"(, "smooth": [false, true])");
  EXPECT_FALSE(mixed.domain.loops()[0].smooth);
  EXPECT_TRUE(mixed.domain.loops()[1].smooth);
  EXPECT_NE(errorOf(std::string(R"({"domain": {)") + loops + R"(, "smooth": [true]}, "metric": {"h": "0.2"}})")
                .find("config.json: domain.smooth: expected boolean or one boolean per loop"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string(R"({"domain": {)") + loops + R"(, "smooth": [1, 0]}, "metric": {"h": "0.2"}})")
                .find("config.json: domain.smooth[0]: expected boolean"),
            std::string::npos);
}

TEST(Config, SmoothPolyLoops) {
  const auto poly = [&](const std::string& smooth) {
    return cli::parseConfig(R"({"domain": {"poly": "square_hole.poly")" + smooth + R"(}, "metric": {"h": "0.2"}})", "c",
                            kData);
  };
  const auto plain = poly("");
  for (const auto& l : plain.domain.loops()) EXPECT_FALSE(l.smooth);
  const auto mixed = poly(R"(, "smooth": [false, true])");
  ASSERT_EQ(mixed.domain.loops().size(), 2u);
  EXPECT_FALSE(mixed.domain.loops()[0].smooth);
  EXPECT_TRUE(mixed.domain.loops()[1].smooth);
  EXPECT_NEAR(mixed.domain.area(), 15.0, 1e-14);
  EXPECT_EQ(mixed.domain.loops()[1].tags, plain.domain.loops()[1].tags);  // the file's markers stay
  try {
    poly(R"(, "smooth": [true, true, true])");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c: domain.smooth: expected boolean or one boolean per loop"),
              std::string::npos)
        << e.what();
  }
}

TEST(Config, ErrorsNameTheKeyPath) {
  EXPECT_EQ(errorOf(R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"h1": 0.1}})"),
            "config.json: metric.h1: expected string, got number");
  EXPECT_NE(errorOf(R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"h1": "0.1"}, "colour": 1})")
                .find("config.json: colour: unknown key"),
            std::string::npos);
  EXPECT_NE(
      errorOf(R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"h1": "0.1"}, "options": {"placement": {"sed": 1}}})")
          .find("config.json: options.placement.sed: unknown key"),
      std::string::npos);
  EXPECT_EQ(
      errorOf(
          R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"h1": "0.1"}, "options": {"placement": {"maxSteps": 1.5}}})"),
      "config.json: options.placement.maxSteps: expected integer, got number");
  EXPECT_EQ(errorOf(R"({"domain": {"rectangle": [0,0,1,"a"]}, "metric": {"h1": "0.1"}})"),
            "config.json: domain.rectangle[3]: expected number, got string");
  EXPECT_EQ(errorOf(R"({"domain": {"disk": {"center": [0,0], "radius": -1}}, "metric": {"h1": "0.1"}})"),
            "config.json: domain.disk.radius: must be > 0, got -1");
  EXPECT_NE(errorOf(R"({"metric": {"h1": "0.1"}})").find("config.json: domain: missing"), std::string::npos);
  EXPECT_NE(
      errorOf(R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"h1": "0.1 +* x"}})").find("config.json: metric"),
      std::string::npos);
  EXPECT_NE(errorOf(R"({"domain": {"rectangle": [0,0,1,1]}, "metric": {"mesh": "square.mesh", "sol": "mismatch.sol"}})")
                .find("3 solution values but the mesh has 5 vertices"),
            std::string::npos);
  EXPECT_NE(errorOf("{\"domain\": ").find("config.json: invalid JSON"), std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("config.json: (top level): expected object, got array"), std::string::npos);
}
