#pragma once
/// The 2D point/vector type used everywhere (Eigen, 16 bytes, value semantics).
#include <Eigen/Core>

namespace ablmg {
using Vec2 = Eigen::Vector2d;

/// 2D cross product u1 v2 − u2 v1 (the "×" of paper eq. 10–12).
inline double cross(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }
}  // namespace ablmg
