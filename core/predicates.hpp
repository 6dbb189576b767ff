#pragma once
/// Robust geometric predicates. Every orientation or crossing decision in ablmg goes through
/// these; no ad-hoc epsilon tests elsewhere.
///
/// orient2d is exact: a floating-point filter (Shewchuk's error bound A) answers almost
/// always; otherwise the determinant is expanded into six products, each split exactly into
/// two doubles with std::fma, and summed as a non-overlapping floating-point expansion, whose
/// most significant component has the sign of the exact result. Written here (about 60 lines)
/// because Debian ships no small, maintained predicates library; CGAL would be a heavy
/// dependency for two functions. Tested on near-degenerate inputs (tests/core/test_predicates).
#include "ablmg/core/vec2.hpp"

namespace ablmg {

/// Sign of the exact determinant |b−a, c−a|: +1 if a,b,c turn counter-clockwise, −1 if
/// clockwise, 0 if exactly collinear.
int orient2d(const Vec2& a, const Vec2& b, const Vec2& c);

/// Twice the signed area of triangle abc (floating point, not exact: for magnitudes only).
inline double signedArea2(const Vec2& a, const Vec2& b, const Vec2& c) { return cross(b - a, c - a); }

/// True iff the closed segments pq and rs meet anywhere other than at an endpoint they share:
/// a proper crossing, a collinear overlap of positive length, or an endpoint of one lying in
/// the interior of the other. Two segments meeting only at a common endpoint do not cross.
bool segmentsCross(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s);

/// True iff the closed segments pq and rs have any point in common (endpoints included).
bool segmentsIntersect(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s);

}  // namespace ablmg
