// Tests of io/surface_picture.hpp: the PNG exists with the requested width, the face turned
// to the light is brighter than one seen edge-on, the nearer of two overlapping triangles is
// the one drawn (painter's order), and bad input throws without leaving a file.
#include "ablmg/io/surface_picture.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include "png_pixels.hpp"

#include <filesystem>
#include <unistd.h>

using namespace ablmg;
using V3 = Eigen::Vector3d;

namespace {
using test::Png;
std::string tmp(const std::string& n) { return test::tempPath("ablmg_surfpic_", n); }
}  // namespace

TEST(SurfacePicture, WritesPngOfRequestedWidth) {
  const std::vector<V3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::array<int, 3>> t = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const auto p = tmp("tet.png");
  io::SurfaceViewOptions o;
  o.width = 300;
  io::drawSurface(p, v, t, o);
  Png png(p);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(png.width(), 300);
  EXPECT_GT(png.height(), 50);
  std::filesystem::remove(p);
}

TEST(SurfacePicture, NearerTriangleHidesFartherOne) {
  // Looking straight down (elevation 90°, screen axes = x, y): the near triangle (z = 1,
  // facing the viewer) and a far, steep one (different shade) both cover the image centre;
  // whatever the input order, the centre shows the near one's colour.
  const std::vector<V3> v = {{-1, -1, 1}, {1, -1, 1},   {0, 1, 1},      // near, horizontal
                             {-1, -1, 0}, {1, -1, 0.0}, {0, 1, -1.9}};  // far, steep
  const std::vector<std::array<int, 3>> nearFirst = {{0, 1, 2}, {3, 4, 5}};
  const std::vector<std::array<int, 3>> farFirst = {{3, 4, 5}, {0, 1, 2}};
  io::SurfaceViewOptions o;
  o.width = 200;
  o.margin = 0;
  o.elevationDeg = 90;
  o.azimuthDeg = -90;
  o.edges = false;
  const auto a = tmp("a.png"), b = tmp("b.png"), c = tmp("c.png");
  io::drawSurface(a, v, nearFirst, o);
  io::drawSurface(b, v, farFirst, o);
  io::drawSurface(c, v, {{0, 1, 2}, {3, 3, 3}}, o);  // the near triangle alone (+ a degenerate one)
  Png pa(a), pb(b), pc(c);
  ASSERT_TRUE(pa.ok() && pb.ok() && pc.ok());
  const auto centre = [](const Png& p) { return p.rgb(p.width() / 2, p.height() / 2); };
  EXPECT_EQ(centre(pa), centre(pc));
  EXPECT_EQ(centre(pb), centre(pc));
  for (const auto& f : {a, b, c}) std::filesystem::remove(f);
}

TEST(SurfacePicture, LitFaceBrighterThanGrazingFace) {
  // Two faces side by side seen from above: one horizontal (faces the viewer and mostly the
  // light), one almost vertical; Lambert shading makes the first brighter.
  const std::vector<V3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2, 1, 3}};
  const std::vector<std::array<int, 3>> t = {{0, 1, 2}, {3, 4, 5}};
  io::SurfaceViewOptions o;
  o.width = 400;
  o.elevationDeg = 90;
  o.azimuthDeg = -90;
  o.edges = false;
  const auto p = tmp("lit.png");
  io::drawSurface(p, v, t, o);
  Png png(p);
  ASSERT_TRUE(png.ok());
  // Pixel inside each triangle: centroids (1/3, 1/3) and (7/3, 1/3) in x, y.
  const double s = (o.width - 2.0 * o.margin) / 3.0;
  const int y = int(png.height() - o.margin - (1.0 / 3) * s);
  const auto flat = png.rgb(int(o.margin + (1.0 / 3) * s), y), steep = png.rgb(int(o.margin + (7.0 / 3) * s), y);
  EXPECT_GT(flat[0] + flat[1] + flat[2], steep[0] + steep[1] + steep[2] + 30);
  std::filesystem::remove(p);
}

TEST(SurfacePicture, BadInputThrowsAndLeavesNoFile) {
  const auto p = tmp("bad.png");
  const std::vector<V3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(io::drawSurface(p, v, {{0, 1, 3}}), InputError);
  EXPECT_THROW(io::drawSurface(p, {}, {}), InputError);
  const std::vector<V3> nan = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
  EXPECT_THROW(io::drawSurface(p, nan, {{0, 1, 2}}), InputError);
  EXPECT_FALSE(std::filesystem::exists(p));
}
