// Tests of io/poly.hpp: loops, holes, markers → tags; bad files name the vertex/segment.
#include "ablmg/io/poly.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

using namespace ablmg;
static const std::string kData = ABLMG_TEST_DATA;

TEST(Poly, SquareWithHole) {
  const Domain d = io::readPoly(kData + "/square_hole.poly");
  ASSERT_EQ(d.loops().size(), 2u);
  EXPECT_NEAR(d.area(), 16.0 - 1.0, 1e-14);
  EXPECT_EQ(d.outer().points.size(), 4u);
  for (int t : d.loops()[1].tags) EXPECT_EQ(t, 5);
  std::vector<int> outerTags = d.outer().tags;
  std::sort(outerTags.begin(), outerTags.end());
  EXPECT_EQ(outerTags, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_FALSE(d.contains(Vec2(1.5, 1.5)));
  EXPECT_TRUE(d.contains(Vec2(3, 3)));
}

TEST(Poly, ZeroBasedWithoutMarkers) {
  const Domain d = io::parsePoly("3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 0\n0 0 1\n1 1 2\n2 2 0\n0\n", "tri.poly");
  EXPECT_NEAR(d.area(), 0.5, 1e-15);
  for (int t : d.outer().tags) EXPECT_EQ(t, 1);
}

TEST(Poly, ErrorsNameTheProblem) {
  try {
    io::readPoly(kData + "/open_loop.poly");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not closed at vertex"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("open_loop.poly:"), std::string::npos) << e.what();
  }
  try {
    io::parsePoly("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n3 0\n1 1 2\n2 2 9\n3 3 1\n0\n", "bad.poly");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.poly:7: segment 2: endpoint 9 out of range [1, 3]"), std::string::npos)
        << e.what();
  }
  // Inner loop with no hole point.
  EXPECT_THROW(
      io::parsePoly(
          "6 2 0 0\n1 0 0\n2 4 0\n3 0 4\n4 1 1\n5 2 1\n6 1 2\n6 0\n1 1 2\n2 2 3\n3 3 1\n4 4 5\n5 5 6\n6 6 4\n0\n",
          "x.poly"),
      InputError);
  EXPECT_THROW(io::parsePoly("", "empty.poly"), InputError);
  EXPECT_THROW(io::parsePoly("3 2 0 0\n1 0 0\n2 1 0\n", "trunc.poly"), InputError);
}
