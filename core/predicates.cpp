#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ablmg {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
constexpr double kErrBoundA = (3.0 + 16.0 * kEps) * kEps;            // Shewchuk's ccwerrboundA

// x + y = s + e exactly (Knuth's TwoSum).
inline void twoSum(double x, double y, double& s, double& e) {
  s = x + y;
  const double bv = s - x;
  const double av = s - bv;
  e = (x - av) + (y - bv);
}

// Adds one double to a non-overlapping expansion (Shewchuk's Grow-Expansion), dropping zeros.
inline int growExpansion(const double* e, int n, double b, double* h) {
  double q = b;
  int m = 0;
  for (int i = 0; i < n; ++i) {
    double s, err;
    twoSum(q, e[i], s, err);
    q = s;
    if (err != 0.0) h[m++] = err;
  }
  if (q != 0.0 || m == 0) h[m++] = q;
  return m;
}

int orient2dExact(const Vec2& a, const Vec2& b, const Vec2& c) {
  // det = ax·by − ax·cy − cx·by − ay·bx + ay·cx + cy·bx (the cx·cy terms cancel).
  const double px[6] = {a.x(), -a.x(), -c.x(), -a.y(), a.y(), c.y()};
  const double py[6] = {b.y(), c.y(), b.y(), b.x(), c.x(), b.x()};
  double e[16], h[16];
  int n = 0;
  for (int k = 0; k < 6; ++k) {
    const double p = px[k] * py[k];
    const double err = std::fma(px[k], py[k], -p);  // exact low part of the product
    n = growExpansion(e, n, p, h);
    std::copy(h, h + n, e);
    n = growExpansion(e, n, err, h);
    std::copy(h, h + n, e);
  }
  const double top = e[n - 1];
  return (top > 0) - (top < 0);
}

int sign(double x) { return (x > 0) - (x < 0); }

bool onSegment(const Vec2& p, const Vec2& q, const Vec2& r) {
  // r collinear with pq: is it within the bounding box of pq?
  return std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) && std::min(p.y(), q.y()) <= r.y() &&
         r.y() <= std::max(p.y(), q.y());
}

}  // namespace

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double detLeft = (a.x() - c.x()) * (b.y() - c.y());
  const double detRight = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detLeft - detRight;
  double detSum;
  if (detLeft > 0) {
    if (detRight <= 0) return sign(det);
    detSum = detLeft + detRight;
  } else if (detLeft < 0) {
    if (detRight >= 0) return sign(det);
    detSum = -detLeft - detRight;
  } else {
    return sign(det);
  }
  if (std::abs(det) >= kErrBoundA * detSum) return sign(det);
  return orient2dExact(a, b, c);
}

bool segmentsCross(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
  const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  if (o1 == 0 && o2 == 0) {                     // collinear: overlap of positive length?
    const bool useX = p.x() != q.x();
    auto key = [&](const Vec2& v) { return useX ? v.x() : v.y(); };
    const double lo1 = std::min(key(p), key(q)), hi1 = std::max(key(p), key(q));
    const double lo2 = std::min(key(r), key(s)), hi2 = std::max(key(r), key(s));
    return std::min(hi1, hi2) > std::max(lo1, lo2);
  }
  // an endpoint of one lying strictly inside the other also counts as crossing
  if (o1 == 0 && r != p && r != q && onSegment(p, q, r) && o3 * o4 <= 0) return true;
  if (o2 == 0 && s != p && s != q && onSegment(p, q, s) && o3 * o4 <= 0) return true;
  if (o3 == 0 && p != r && p != s && onSegment(r, s, p) && o1 * o2 <= 0) return true;
  if (o4 == 0 && q != r && q != s && onSegment(r, s, q) && o1 * o2 <= 0) return true;
  return false;
}

bool segmentsIntersect(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
  const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && onSegment(p, q, r)) return true;
  if (o2 == 0 && onSegment(p, q, s)) return true;
  if (o3 == 0 && onSegment(r, s, p)) return true;
  if (o4 == 0 && onSegment(r, s, q)) return true;
  return false;
}

}  // namespace ablmg
