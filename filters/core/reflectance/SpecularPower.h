#pragma once
// x^eta for the specular lobe (docs/formulas.md sections 4, 5 and 15), x a clamped cosine in [0, 1]
// and eta >= 0: the exact std::pow and two cheaper approximations that a tolerance may
// choose. The approximations are branch-free arithmetic on the float's bits, so that a loop
// of them vectorises, which a loop of std::pow calls does not.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

namespace shadelab
{
enum class PowMethod
{
  Exact,   // std::pow (wholePowers in float for a whole eta): within an ulp or so
  Series,  // exp2(eta log2 x) from short series: relative error about 1e-7 eta
  Schlick, // Schlick's rational x / (eta - eta x + x): a division, errors up to about 0.1
};

std::string powMethodName(PowMethod method);

namespace detail
{
/// The integer type as wide as T, for working on its bits.
template<typename T>
using BitsOf = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;

// always_inline: a call inside a loop stops it vectorising, and GCC's inliner judges the
// series too large to inline on its own.
#define SHADELAB_ALWAYS_INLINE [[gnu::always_inline]] inline

template<typename To, typename From>
SHADELAB_ALWAYS_INLINE To bitCast(From from)
{
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof(To));
  return to;
}

// log2 x for a normal positive x. x = m 2^e with m in [sqrt(1/2), sqrt(2)), and
// ln m = 2 atanh(u), u = (m - 1) / (m + 1), |u| <= 0.172, is the odd series
// 2 (u + u^3/3 + u^5/5 + u^7/7 + ...) (Abramowitz and Stegun 4.1.27). Four terms leave a
// truncation error below 2 |u|^9 / 9 / ln 2 = 4e-8.
template<typename T>
SHADELAB_ALWAYS_INLINE T log2Series(T x)
{
  using Bits = BitsOf<T>;
  constexpr int mantissaBits = std::numeric_limits<T>::digits - 1;
  constexpr Bits exponentBias = Bits(std::numeric_limits<T>::max_exponent - 1);
  constexpr Bits mantissaMask = (Bits(1) << mantissaBits) - 1;
  const Bits bits = bitCast<Bits>(x);
  using Signed = std::make_signed_t<Bits>;
  T exponent = T(static_cast<Signed>(bits >> mantissaBits) - static_cast<Signed>(exponentBias));
  T m = bitCast<T>((bits & mantissaMask) | (exponentBias << mantissaBits)); // in [1, 2)
  const bool halve = m > T(1.41421356237309505);
  m = halve ? m * T(0.5) : m;
  exponent = halve ? exponent + T(1) : exponent;
  const T u = (m - T(1)) / (m + T(1));
  const T u2 = u * u;
  constexpr T twoOverLn2 = T(2.0 / 0.693147180559945309);
  const T series = u * (T(1) + u2 * (T(1.0 / 3) + u2 * (T(1.0 / 5) + u2 * T(1.0 / 7))));
  return exponent + twoOverLn2 * series;
}

// 2^y for y <= 0: y = k + f with k = round(y) and |f| <= 1/2, 2^k built in the exponent bits
// and 2^f = e^(f ln 2) from its Taylor series to degree 7 (truncation below
// (ln 2 / 2)^8 / 8! = 5e-9). Below the smallest normal the result is 0.
template<typename T>
SHADELAB_ALWAYS_INLINE T exp2Series(T y)
{
  using Bits = BitsOf<T>;
  constexpr int mantissaBits = std::numeric_limits<T>::digits - 1;
  constexpr T lowest = T(std::numeric_limits<T>::min_exponent - 1); // 2^lowest: smallest normal
  // Adding and subtracting 1.5 2^mantissaBits rounds to an integer without a library call.
  constexpr T roundingShift = T(1.5) * T(Bits(1) << mantissaBits);
  const bool underflows = y < lowest;
  const T clamped = underflows ? lowest : y;
  const T k = (clamped + roundingShift) - roundingShift;
  const T g = (clamped - k) * T(0.693147180559945309);
  const T power = T(1) +
    g *
      (T(1) +
        g *
          (T(1.0 / 2) +
            g * (T(1.0 / 6) + g * (T(1.0 / 24) + g * (T(1.0 / 120) + g * (T(1.0 / 720) + g * T(1.0 / 5040)))))));
  using Signed = std::make_signed_t<Bits>;
  const Signed biased = static_cast<Signed>(k) + (std::numeric_limits<T>::max_exponent - 1);
  const T scale = bitCast<T>(static_cast<Bits>(biased) << mantissaBits);
  return underflows ? T(0) : power * scale;
}
}

// x^eta = 2^(eta log2 x) from the two series above. x is raised to the smallest normal first,
// so x = 0 gives 0 for eta >= 1 and 1 for eta = 0 (C++'s pow(0, 0) = 1), and no log of 0.
template<typename T>
SHADELAB_ALWAYS_INLINE T powSeries(T x, T eta)
{
  const T smallest = std::numeric_limits<T>::min();
  const T clamped = x < smallest ? smallest : (x > T(1) ? T(1) : x);
  return detail::exp2Series(eta * detail::log2Series(clamped));
}

// Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", Computer Graphics
// Forum 13(3), 1994, section 5: x^eta ~ x / (eta - eta x + x) for x in [0, 1]. Exact at
// x = 0 and x = 1 and for eta = 1; broader than the true lobe in between. At eta = 0 it gives 1
// for x > 0 and 0/0 at x = 0, which is taken as 1 to agree with pow(0, 0).
template<typename T>
SHADELAB_ALWAYS_INLINE T powSchlick(T x, T eta)
{
  const T denominator = eta - eta * x + x;
  return denominator > T(0) ? x / denominator : T(1);
}

/// Calls use(power) with the method's x -> x^eta as a function object, so that a loop inside
/// use() is compiled once per method with no branch on the method in it.
template<typename T, typename Use>
void withPowMethod(PowMethod method, T eta, Use&& use)
{
  switch (method)
  {
    case PowMethod::Exact: use([eta](T x) { return std::pow(x, eta); }); break;
    case PowMethod::Series: use([eta](T x) { return powSeries(x, eta); }); break;
    case PowMethod::Schlick: use([eta](T x) { return powSchlick(x, eta); }); break;
  }
}

/// Whether wholePowers can raise to eta: a whole number from 0 to 2^16.
inline bool isWholeExponent(double eta)
{
  return eta >= 0 && eta <= 65536 && eta == std::floor(eta);
}

/// y[i] = x[i]^eta for i < count, x[i] in [0, 1] and eta a whole number (isWholeExponent):
/// the exact method in float for the usual shininesses, several times faster than std::pow
/// a value. Binary exponentiation (Knuth, TAOCP vol. 2, section 4.6.3) in double: each
/// product rounds by 2^-53 and squaring doubles the error carried in, so the double is within
/// about eta 1.1e-16 of x^eta, relative, and the float it rounds to is within 0.5 + 2e-9 eta
/// ulp (0.50013 at eta = 2^16): the nearest float but for values within that margin of
/// halfway between two floats; glibc's powf is within 0.82. x and y may be the same array.
void wholePowers(const float* x, float* y, std::size_t count, unsigned eta);

/// y[i] = x[i]^eta by the method for i < count: the approximations in the kernel's vectorised
/// loops, Exact as std::pow a value (the kernel's float path for a non-whole eta). What
/// `shadelab-bench --charts` times.
void evaluatePowers(PowMethod method, const float* x, float* y, std::size_t count, float eta);

/// The largest |approximation - pow(x, eta)| over x in [0, 1] for this eta, in arithmetic of
/// type T (float or double), found on a dense grid refined around the worst point: the error
/// a tolerance compares against. For Exact it is the rounding of std::pow itself.
/// Remembered per method and finite eta.
template<typename T>
double largestPowError(PowMethod method, double eta);

/// The same search for wholePowers (float): its largest |x^eta - pow(x, eta)| over [0, 1].
double largestWholePowerError(unsigned eta);
}
