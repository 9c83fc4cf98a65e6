/**
 * @file Vec3.h
 * @brief The small 3-vector algebra the mesh kernels share: dot and cross
 * products, linear combinations and unit vectors on std::array<double, 3>.
 */
#ifndef ShockVec3_h
#define ShockVec3_h

#include <array>
#include <cmath>

namespace shock
{

using Vec3 = std::array<double, 3>;

inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// The 3 values at v as a vector.
inline Vec3 Load(const double* v)
{
  return { v[0], v[1], v[2] };
}

/// a x + b y.
inline Vec3 Combine(double a, const Vec3& x, double b, const Vec3& y)
{
  return { a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2] };
}

/// v / |v|, or the zero vector when v is zero.
inline Vec3 Unit(const Vec3& v)
{
  const double n = std::sqrt(Dot(v, v));
  return n > 0.0 ? Vec3{ v[0] / n, v[1] / n, v[2] / n } : Vec3{ 0.0, 0.0, 0.0 };
}

/// Normalise the 3 values at v in place; false (v unchanged) when the length is zero or not finite.
inline bool Normalise(double* v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0) || !std::isfinite(n))
  {
    return false;
  }
  v[0] /= n;
  v[1] /= n;
  v[2] /= n;
  return true;
}

} // namespace shock

#endif
