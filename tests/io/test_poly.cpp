// Tests of io/poly.hpp: loops, holes, markers → tags; bad files name the vertex/segment.
#include "ablmg/io/poly.hpp"

#include "ablmg/core/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>

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
  try {
    io::parsePoly(
        "6 2 0 0\n1 0 0\n2 4 0\n3 0 4\n4 1 1\n5 2 1\n6 1 2\n6 0\n1 1 2\n2 2 3\n3 3 1\n4 4 5\n5 5 6\n6 6 4\n0\n",
        "x.poly");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "x.poly: inner loop through (1, 1) contains no hole point (interior constraint "
              "loops are not supported)");
  }
  EXPECT_THROW(io::parsePoly("", "empty.poly"), InputError);
  EXPECT_THROW(io::parsePoly("3 2 0 0\n1 0 0\n2 1 0\n", "trunc.poly"), InputError);
}

TEST(Poly, SlitsAsHangingChainsOrZeroWidthGaps) {
  // (−1,1)² with a chain from the right side's midpoint (vertex 5) to the centre (vertex 6),
  // marker 9: both lips tagged 9; and a free chain 7–8 inside, marker 4.
  const std::string square =
      "8 2 0 0\n1 -1 -1\n2 1 -1\n3 1 1\n4 -1 1\n5 1 0\n6 0 0\n7 -0.5 0.5\n8 -0.5 -0.5\n"
      "7 1\n1 1 2 1\n2 2 5 2\n3 5 3 2\n4 3 4 3\n5 4 1 4\n6 5 6 9\n7 7 8 4\n0\n";
  const Domain d = io::parsePoly(square, "slit.poly");
  EXPECT_TRUE(d.hasSlits());
  EXPECT_NEAR(d.area(), 4.0, 1e-15);
  ASSERT_EQ(d.loops().size(), 2u);         // the outer loop with its slit, the free slit
  EXPECT_EQ(d.outer().points.size(), 7u);  // 5 points, the attachment twice, the tip
  EXPECT_EQ(std::count(d.outer().tags.begin(), d.outer().tags.end(), 9), 2);
  // The same slit as a zero-width gap: vertex 5 and 7 at (1, 0), lips marked 9 and 10.
  const std::string gap =
      "7 2 0 0\n1 -1 -1\n2 1 -1\n3 1 1\n4 -1 1\n5 1 0\n6 0 0\n7 1 0\n"
      "7 1\n1 1 2 1\n2 2 5 2\n3 5 6 9\n4 6 7 10\n5 7 3 2\n6 3 4 3\n7 4 1 4\n0\n";
  const Domain g = io::parsePoly(gap, "gap.poly");
  EXPECT_TRUE(g.hasSlits());
  EXPECT_EQ(g.loops().size(), 1u);
  // An open boundary is still an open boundary, not a slit.
  EXPECT_THROW(io::parsePoly("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n2 0\n1 1 2\n2 2 3\n0\n", "open.poly"), InputError);
  // A hanging chain that leaves the domain: named.
  try {
    io::parsePoly("5 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 2 0.5\n5 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n5 3 5\n0\n",
                  "out.poly");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("from vertex 3 to vertex 5"), std::string::npos) << e.what();
  }
}
