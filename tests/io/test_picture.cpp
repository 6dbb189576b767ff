// Tests of io/picture.hpp: the PNGs exist, have the requested width, and show what was drawn
// where it should be (pixels read back through cairo).
#include "ablmg/io/picture.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>

#include "png_pixels.hpp"

#include <filesystem>

using namespace ablmg;

namespace {
using test::Png;
std::string tmp(const std::string& n) { return test::tempPath("ablmg_pic_", n); }
}  // namespace

TEST(Picture, MeshColouredByValue) {
  const Mesh2 m = io::readMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh");
  const auto p = tmp("mesh.png");
  const std::vector<double> values = {0, 1, 2, 3};  // bottom triangle lowest (blue), left highest (red)
  io::PictureOptions o;
  o.width = 400;
  io::drawMesh(p, m, values, "value", o);
  Png png(p);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.width(), 400);
  // Bottom triangle (around (0.5, 0.15)) is blue; the drawing area is 400-60-110 = 230 px wide.
  const double s = 230.0;
  const auto blue = png.rgb(int(30 + 0.5 * s), int(png.height() - 30 - 0.15 * s));
  EXPECT_GT(blue[2], 110);  // the ramp starts at dark blue (0, 0, 128)
  EXPECT_LT(blue[0], 80);
  const auto red = png.rgb(int(30 + 0.15 * s), int(png.height() - 30 - 0.5 * s));
  EXPECT_GT(red[0], 110);  // and ends at dark red (128, 0, 0)
  EXPECT_LT(red[2], 80);
  std::filesystem::remove(p);
}

TEST(Picture, BubblesAreHalfUnitEllipses) {
  const Domain d = Domain::rectangle(0, 0, 1, 1);
  const std::vector<Vec2> c = {Vec2(0.5, 0.5)};
  const std::vector<Metric2> m = {Metric2::fromSizes(0.8, 0.2, 0)};  // semi-axes 0.4 (x), 0.1 (y)
  io::PictureOptions o;
  o.width = 260;
  o.margin = 30;  // 200 px for 1 unit
  const auto p = tmp("bubbles.png");
  io::drawBubbles(p, d, c, m, nullptr, o);
  Png png(p);
  ASSERT_TRUE(png.ok());
  const auto inX = png.rgb(30 + 170, 130);   // x = 0.85 inside (0.5 + 0.4 > 0.85)
  const auto outY = png.rgb(130, 130 - 30);  // y = 0.65 outside (0.5 + 0.1 < 0.65)
  EXPECT_LT(inX[0], 240);
  EXPECT_EQ(outY[0], 255);
  std::filesystem::remove(p);
}

TEST(Picture, LogLogPlotWritesPng) {
  const auto p = tmp("plot.png");
  io::drawLogLogPlot(p,
                     {{"L2", {100, 1000, 10000}, {1e-2, 1e-3, 1e-4}}, {"H1", {100, 1000, 10000}, {1e-1, 3e-2, 1e-2}}},
                     {-1, -0.5}, "N", "error", "convergence");
  Png png(p);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.width(), 1200);
  EXPECT_THROW(io::drawLogLogPlot(p, {{"bad", {1}, {}}}), ablmg::InputError);
  std::filesystem::remove(p);
}

TEST(Picture, TilePicturesPlacesEachScaledPictureInItsCell) {
  // Two 400-px plots and one mesh, two per row at 600 px: each scaled to 300 px, captions above.
  const auto a = tmp("tile_a.png"), b = tmp("tile_b.png"), m = tmp("tile_m.png"), out = tmp("tiles.png");
  io::PictureOptions small;
  small.width = 400;
  io::drawLogLogPlot(a, {{"L2", {100, 1000}, {1e-2, 1e-3}}}, {}, "N", "error", "", small);  // 400 × 300
  io::drawLogLogPlot(b, {{"H1", {100, 1000}, {1e-1, 3e-2}}}, {}, "N", "error", "", small);
  io::drawMesh(m, io::readMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh"), {}, "", small);
  io::PictureOptions o;
  o.width = 600;
  io::tilePictures(out, {a, b, m}, 2, {"left", "right", "mesh"}, o);
  Png png(out), mesh(m);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.width(), 600);
  EXPECT_EQ(png.height(), 26 + 225 + 26 + mesh.height() * 300 / 400);  // row heights: band + scaled picture
  EXPECT_THROW(io::tilePictures(out, {a, b}, 2, {"only one"}), ablmg::InputError);
  EXPECT_THROW(io::tilePictures(out, {a, "/nonexistent/x.png"}, 2), ablmg::InputError);
  EXPECT_THROW(io::tilePictures(out, {a}, 0), ablmg::InputError);
  for (const auto& p : {a, b, m, out}) std::filesystem::remove(p);
}
