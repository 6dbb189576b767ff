#include "ablmg/mesher/triangulation.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <string>

namespace ablmg::mesher {
namespace {

constexpr int next3(int k) { return k == 2 ? 0 : k + 1; }
constexpr int prev3(int k) { return k == 0 ? 2 : k - 1; }

/// d strictly inside the circumcircle of the counter-clockwise triangle abc — answered only
/// when the floating-point determinant is certainly positive (Shewchuk's bound for
/// incircle, iccerrboundA); near-cocircular cases answer false, which keeps Lawson's flips
/// terminating (each flip strictly lowers the lifted triangulation).
bool certainlyInCircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * alift +
                           (std::abs(cdxady) + std::abs(adxcdy)) * blift +
                           (std::abs(adxbdy) + std::abs(bdxady)) * clift;
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;
  constexpr double bound = (10.0 + 96.0 * eps) * eps;
  return det > bound * permanent;
}

/// Hilbert-curve index of (x, y) ∈ [0, 2^16)² (the classic rotate-and-flip form).
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  std::uint64_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += std::uint64_t(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = 65535 - x;
        y = 65535 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

Triangulation::Triangulation(std::span<const Vec2> points) : n_(int(points.size())) {
  ABLMG_REQUIRE(n_ >= 3, "triangulation: at least 3 points are needed, got " + std::to_string(n_));
  Vec2 lo = points[0], hi = points[0];
  for (int i = 0; i < n_; ++i) {
    const Vec2& q = points[i];
    if (!std::isfinite(q.x()) || !std::isfinite(q.y()))
      throw InputError("triangulation: point " + std::to_string(i) + " is not finite");
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const Vec2 centre = 0.5 * (lo + hi);
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-300});
  p_.assign(points.begin(), points.end());
  // Enclosing triangle, far enough that every point is strictly inside it.
  const double r = 64 * extent;
  p_.push_back(centre + Vec2(-2 * r, -r));
  p_.push_back(centre + Vec2(2 * r, -r));
  p_.push_back(centre + Vec2(0, 2 * r));
  tri_.push_back({n_, n_ + 1, n_ + 2});
  nbr_.push_back({-1, -1, -1});
  vtri_.assign(n_ + 3, -1);
  vtri_[n_] = vtri_[n_ + 1] = vtri_[n_ + 2] = 0;
  tri_.reserve(2 * std::size_t(n_) + 8);
  nbr_.reserve(2 * std::size_t(n_) + 8);

  // Insert in Hilbert order so that each walk starts next to its target: O(1) steps each.
  std::vector<std::pair<std::uint64_t, int>> order(n_);
  const double scale = 65535.0 / extent;
  for (int i = 0; i < n_; ++i) {
    const auto hx = std::uint32_t(std::clamp((points[i].x() - lo.x()) * scale, 0.0, 65535.0));
    const auto hy = std::uint32_t(std::clamp((points[i].y() - lo.y()) * scale, 0.0, 65535.0));
    order[i] = {hilbertIndex(hx, hy), i};
  }
  std::sort(order.begin(), order.end());
  for (const auto& [key, v] : order) insert(v);
  lockBits_.assign(tri_.size(), 0);
}

int Triangulation::locate(const Vec2& q, int& onEdge) const {
  int t = last_;
  const long cap = 4L * long(tri_.size()) + 100;
  for (long step = 0; step < cap; ++step) {
    const int k0 = int(step % 3);  // rotating first edge: no cycling on near-degenerate input
    bool moved = false;
    int zeros = 0;
    onEdge = -1;
    for (int i = 0; i < 3; ++i) {
      const int k = (k0 + i) % 3;
      const int o = orient2d(p_[tri_[t][next3(k)]], p_[tri_[t][prev3(k)]], q);
      if (o < 0) {
        t = nbr_[t][k];
        moved = true;
        break;
      }
      if (o == 0) {
        ++zeros;
        onEdge = k;
      }
    }
    if (!moved) {
      if (zeros >= 2) return -1;  // q is a vertex
      return t;
    }
  }
  ABLMG_FAIL("triangulation: point location did not terminate");
}

void Triangulation::setNeighbour(int t, int oldN, int newN) {
  if (t < 0) return;
  for (int k = 0; k < 3; ++k)
    if (nbr_[t][k] == oldN) {
      nbr_[t][k] = newN;
      return;
    }
  ABLMG_FAIL("triangulation: broken neighbour links");
}

void Triangulation::insert(int v) {
  int onEdge = -1;
  const int t = locate(p_[v], onEdge);
  if (t < 0) {
    throw InputError("triangulation: point " + std::to_string(v) + " (" + std::to_string(p_[v].x()) + ", " +
                     std::to_string(p_[v].y()) + ") duplicates another point");
  }
  if (onEdge < 0) {
    const int a = tri_[t][0], b = tri_[t][1], c = tri_[t][2];
    const int na = nbr_[t][0], nb = nbr_[t][1], nc = nbr_[t][2];
    const int t1 = int(tri_.size()), t2 = t1 + 1;
    tri_[t] = {a, b, v};
    nbr_[t] = {t1, t2, nc};
    tri_.push_back({b, c, v});
    nbr_.push_back({t2, t, na});
    tri_.push_back({c, a, v});
    nbr_.push_back({t, t1, nb});
    setNeighbour(na, t, t1);
    setNeighbour(nb, t, t2);
    vtri_[a] = vtri_[b] = vtri_[v] = t;
    vtri_[c] = t1;
    last_ = t;
    legalize(v, t);
    legalize(v, t1);
    legalize(v, t2);
    return;
  }
  // On the edge opposite local vertex k: split the two triangles sharing it into four.
  const int k = onEdge;
  const int a = tri_[t][k], b = tri_[t][next3(k)], c = tri_[t][prev3(k)];
  const int u = nbr_[t][k];
  int j = 0;
  while (nbr_[u][j] != t) ++j;
  const int d = tri_[u][j];
  const int tAB = nbr_[t][prev3(k)], tCA = nbr_[t][next3(k)];
  const int uBD = nbr_[u][next3(j)], uDC = nbr_[u][prev3(j)];
  const int t2 = int(tri_.size()), u2 = t2 + 1;
  tri_[t] = {a, b, v};
  nbr_[t] = {u2, t2, tAB};
  tri_.push_back({a, v, c});
  nbr_.push_back({u, tCA, t});
  tri_[u] = {d, c, v};
  nbr_[u] = {t2, u2, uDC};
  tri_.push_back({d, v, b});
  nbr_.push_back({t, uBD, u});
  setNeighbour(tCA, t, t2);
  setNeighbour(uBD, u, u2);
  vtri_[a] = vtri_[b] = vtri_[v] = t;
  vtri_[c] = t2;
  vtri_[d] = u;
  last_ = t;
  legalize(v, t);
  legalize(v, t2);
  legalize(v, u);
  legalize(v, u2);
}

void Triangulation::legalize(int v, int t0) {
  std::vector<int> stack{t0};
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    int i = 0;
    while (tri_[t][i] != v) ++i;
    const int u = nbr_[t][i];
    if (u < 0) continue;
    int j = 0;
    while (nbr_[u][j] != t) ++j;
    const int d = tri_[u][j];
    if (!certainlyInCircle(p_[tri_[t][0]], p_[tri_[t][1]], p_[tri_[t][2]], p_[d])) continue;
    flip(t, i);  // t = (v, b, d), u = (v, d, c)
    stack.push_back(t);
    stack.push_back(u);
  }
}

void Triangulation::flip(int t, int k) {
  const int a = tri_[t][k], b = tri_[t][next3(k)], c = tri_[t][prev3(k)];
  const int u = nbr_[t][k];
  int j = 0;
  while (nbr_[u][j] != t) ++j;
  const int d = tri_[u][j];
  const int tCA = nbr_[t][next3(k)], tAB = nbr_[t][prev3(k)];
  const int uBD = nbr_[u][next3(j)], uDC = nbr_[u][prev3(j)];
  std::uint8_t lt = 0, lu = 0;
  if (!lockBits_.empty()) {
    const auto bit = [&](int tt, int kk) { return std::uint8_t((lockBits_[tt] >> kk) & 1); };
    lt = std::uint8_t(bit(u, next3(j)) | (bit(t, prev3(k)) << 2));
    lu = std::uint8_t(bit(u, prev3(j)) | (bit(t, next3(k)) << 1));
  }
  tri_[t] = {a, b, d};
  nbr_[t] = {uBD, u, tAB};
  tri_[u] = {a, d, c};
  nbr_[u] = {uDC, tCA, t};
  setNeighbour(uBD, u, t);
  setNeighbour(tCA, t, u);
  vtri_[a] = vtri_[b] = vtri_[d] = t;
  vtri_[c] = u;
  if (!lockBits_.empty()) {
    lockBits_[t] = lt;
    lockBits_[u] = lu;
  }
}

std::pair<int, int> Triangulation::findDirectedEdge(int a, int b) const {
  const int start = vtri_[a];
  int t = start;
  for (int guard = 0; guard < 100000; ++guard) {  // counter-clockwise around a
    int i = 0;
    while (tri_[t][i] != a) ++i;
    if (tri_[t][next3(i)] == b) return {t, prev3(i)};
    t = nbr_[t][next3(i)];
    if (t == start) return {-1, -1};
    if (t < 0) break;
  }
  t = start;  // a is on the hull (an enclosing vertex): clockwise too
  for (int guard = 0; guard < 100000 && t >= 0; ++guard) {
    int i = 0;
    while (tri_[t][i] != a) ++i;
    if (tri_[t][next3(i)] == b) return {t, prev3(i)};
    t = nbr_[t][prev3(i)];
  }
  return {-1, -1};
}

void Triangulation::lock(int a, int b) {
  auto [t, k] = findDirectedEdge(a, b);
  if (t < 0) std::tie(t, k) = findDirectedEdge(b, a);
  ABLMG_ASSERT(t >= 0, "lock: no such edge");
  lockBits_[t] |= std::uint8_t(1u << k);
  const int u = nbr_[t][k];
  if (u >= 0) {
    int j = 0;
    while (nbr_[u][j] != t) ++j;
    lockBits_[u] |= std::uint8_t(1u << j);
  }
}

bool Triangulation::isLocked(int a, int b) const {
  auto [t, k] = findDirectedEdge(a, b);
  if (t < 0) std::tie(t, k) = findDirectedEdge(b, a);
  return t >= 0 && edgeLocked(t, k);
}

bool Triangulation::recoverEdge(int a, int b) {
  if (hasEdge(a, b)) {
    lock(a, b);
    return true;
  }
  const Vec2 &pa = p_[a], &pb = p_[b];
  // The triangle around a that segment ab enters: (a, x, y) with b strictly inside angle x-a-y.
  int t = vtri_[a], x = -1, y = -1;
  for (int guard = 0;; ++guard) {
    if (guard > 100000) return false;
    int i = 0;
    while (tri_[t][i] != a) ++i;
    const int xi = tri_[t][next3(i)], yi = tri_[t][prev3(i)];
    const int ox = orient2d(pa, p_[xi], pb), oy = orient2d(pa, p_[yi], pb);
    if (ox == 0 && (p_[xi] - pa).dot(pb - pa) > 0) return false;  // a vertex on the segment
    if (ox > 0 && oy < 0) {
      x = xi;
      y = yi;
      break;
    }
    t = nbr_[t][next3(i)];
    if (t < 0) return false;
  }
  // Edges crossed by ab, in order (x right of a→b, y left).
  std::deque<std::array<int, 2>> crossed;
  for (int guard = 0;; ++guard) {
    if (guard > 1000000) return false;
    int k = 0;
    while (tri_[t][k] == x || tri_[t][k] == y) ++k;
    if (edgeLocked(t, k)) return false;
    crossed.push_back({x, y});
    const int u = nbr_[t][k];
    int j = 0;
    while (nbr_[u][j] != t) ++j;
    const int z = tri_[u][j];
    if (z == b) break;
    const int o = orient2d(pa, pb, p_[z]);
    if (o == 0) return false;
    if (o > 0)
      y = z;
    else
      x = z;
    t = u;
  }
  // Sloan: flip crossed edges whose quadrilateral is strictly convex until none crosses ab.
  long budget = 64L * long(crossed.size() * crossed.size()) + 1000;
  while (!crossed.empty()) {
    if (--budget < 0) return false;
    const auto [ex, ey] = crossed.front();
    crossed.pop_front();
    auto [tt, k] = findDirectedEdge(ex, ey);
    if (tt < 0) std::tie(tt, k) = findDirectedEdge(ey, ex);
    if (tt < 0) continue;
    const int u = nbr_[tt][k];
    int j = 0;
    while (nbr_[u][j] != tt) ++j;
    const int c = tri_[tt][k], d = tri_[u][j];
    const int o1 = orient2d(p_[c], p_[d], p_[ex]), o2 = orient2d(p_[c], p_[d], p_[ey]);
    if (o1 * o2 >= 0) {  // not strictly convex: later
      crossed.push_back({ex, ey});
      continue;
    }
    flip(tt, k);
    if (c != a && c != b && d != a && d != b) {
      const int oc = orient2d(pa, pb, p_[c]), od = orient2d(pa, pb, p_[d]);
      if (oc * od < 0) crossed.push_back({c, d});
    }
  }
  if (!hasEdge(a, b)) return false;
  lock(a, b);
  return true;
}

void Triangulation::classify(std::span<const std::array<int, 2>> boundary) {
  std::vector<signed char> label(tri_.size(), -1);
  std::vector<int> stack;
  auto seed = [&](int t, signed char l) {
    if (t < 0) return;
    if (label[t] >= 0 && label[t] != l) ABLMG_FAIL("connect: the boundary does not separate inside from outside");
    if (label[t] < 0) {
      label[t] = l;
      stack.push_back(t);
    }
  };
  for (const auto& [a, b] : boundary) {
    const auto [ti, ki] = findDirectedEdge(a, b);
    const auto [to, ko] = findDirectedEdge(b, a);
    ABLMG_REQUIRE(ti >= 0 && edgeLocked(ti, ki), "connect: boundary edge " + std::to_string(a) + "-" +
                                                     std::to_string(b) + " is missing from the triangulation");
    seed(ti, 1);
    seed(to, 0);
  }
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k)
      if (!edgeLocked(t, k)) seed(nbr_[t][k], label[t]);
  }
  inside_.assign(tri_.size(), 0);
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    if (label[t] != 1) continue;
    for (int k = 0; k < 3; ++k)
      ABLMG_REQUIRE(tri_[t][k] < n_, "connect: the boundary is not closed (an inside triangle reaches infinity)");
    inside_[t] = 1;
  }
}

long Triangulation::flipWhile(const std::function<bool(int, int, int, int)>& shouldFlip, long maxFlips, bool& capHit) {
  capHit = false;
  std::deque<std::array<int, 2>> queue;
  for (int t = 0; t < int(tri_.size()); ++t) {
    if (!inside_[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int u = nbr_[t][k];
      if (u > t && inside_[u] && !edgeLocked(t, k)) queue.push_back({tri_[t][next3(k)], tri_[t][prev3(k)]});
    }
  }
  long flips = 0;
  while (!queue.empty()) {
    int x = queue.front()[0], z = queue.front()[1];
    queue.pop_front();
    auto [t, k] = findDirectedEdge(x, z);
    if (t < 0 || !inside_[t]) {
      std::swap(x, z);
      std::tie(t, k) = findDirectedEdge(x, z);
    }
    if (t < 0 || edgeLocked(t, k) || !inside_[t]) continue;
    const int u = nbr_[t][k];
    if (u < 0 || !inside_[u]) continue;
    int j = 0;
    while (nbr_[u][j] != t) ++j;
    const int y = tri_[t][k], w = tri_[u][j];
    if (orient2d(p_[y], p_[w], p_[x]) * orient2d(p_[y], p_[w], p_[z]) >= 0) continue;  // not strictly convex
    if (!shouldFlip(x, z, y, w)) continue;
    if (flips >= maxFlips) {
      capHit = true;
      break;
    }
    flip(t, k);
    ++flips;
    queue.push_back({x, y});
    queue.push_back({y, z});
    queue.push_back({z, w});
    queue.push_back({w, x});
  }
  return flips;
}

}  // namespace ablmg::mesher
