#pragma once
// The local reflectance terms (docs/formulas.md sections 2 to 6: Lambert 1760, Phong 1975,
// Blinn 1977), each a small named function in the manner of Filament's shading code. n, s, v
// are unit vectors: normal, to-light, to-viewer.
#include "Vec3.h"

#include <algorithm>
#include <cmath>

namespace shadelab
{
// docs/formulas.md section 3: the angle of incidence theta_i between n and s, in degrees.
// Computed as atan2(|n x s|, n.s) rather than acos(n.s): acos loses about half the significant
// digits near 0 and 180 degrees, atan2 of the pair loses none (W. Kahan, "How Futile are
// Mindless Assessments of Roundoff in Floating-Point Computation?", 2006, section 12). A zero
// normal, whose n.s is 0, gets 90 degrees.
template<typename T>
T incidenceAngleDegrees(const Vec3<T>& n, const Vec3<T>& s)
{
  constexpr T degreesPerRadian = T(180.0 / 3.14159265358979323846);
  const T sine = glm::length(glm::cross(n, s));
  const T cosine = glm::dot(n, s);
  if (sine == T(0) && cosine == T(0))
  {
    return T(90);
  }
  return std::atan2(sine, cosine) * degreesPerRadian;
}

// docs/formulas.md section 3, Lambert: I = Ld kd max(0, n.s). This is the max(0, n.s) factor.
template<typename T>
T lambertFactor(T cosIncidence)
{
  return std::max(cosIncidence, T(0));
}

// docs/formulas.md section 4 (Phong 1975): r = 2 (n.s) n - s, the mirror direction of s about n.
template<typename T>
Vec3<T> reflectAboutNormal(const Vec3<T>& s, const Vec3<T>& n, T cosIncidence)
{
  return T(2) * cosIncidence * n - s;
}

// docs/formulas.md sections 5 and 16.2: h = (s + v) / |s + v| is undefined when s = -v.
// Below this |s + v|^2 is pure rounding noise of two opposite unit vectors.
template<typename T>
constexpr T halfVectorUndefinedBelow2 = T(1e-12);

// docs/formulas.md section 5 (Blinn 1977): h = (s + v) / |s + v|, or (0, 0, 0) where it is
// undefined, with `defined` saying which. Without a branch, so that the kernel's loops over
// blocks of vertices vectorise it.
template<typename T>
Vec3<T> halfVectorOrZero(const Vec3<T>& s, const Vec3<T>& v, bool& defined)
{
  const Vec3<T> sum = s + v;
  const T length2 = glm::dot(sum, sum);
  defined = length2 > halfVectorUndefinedBelow2<T>;
  const T length = std::sqrt(defined ? length2 : T(1));
  return defined ? sum / length : Vec3<T>(T(0));
}

// The same, returning false (and leaving h untouched) where h is undefined.
template<typename T>
bool halfVector(const Vec3<T>& s, const Vec3<T>& v, Vec3<T>& h)
{
  bool defined = false;
  const Vec3<T> computed = halfVectorOrZero(s, v, defined);
  h = defined ? computed : h;
  return defined;
}

// docs/formulas.md sections 4 and 5: the specular lobe cos^eta, for Phong (cos = r.v) and
// Blinn-Phong (cos = n.h). Negative cosines are clamped to 0 before pow (section 16.1), and
// cosines that rounding puts above 1 to 1, which a shininess of 1e30 would otherwise raise to
// Inf (and Inf / Inf to NaN where a sampler divides by the lobe's density). Only a lit vertex
// (n.s > 0) has a lobe. eta = 0 follows C++'s pow(0, 0) = 1: the lobe is
// the constant 1 on every lit vertex (section 16.3).
template<typename T>
T specularLobe(bool lit, T cosine, T eta)
{
  return lit ? std::pow(std::clamp(cosine, T(0), T(1)), eta) : T(0);
}
}
