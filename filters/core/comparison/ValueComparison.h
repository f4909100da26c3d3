#pragma once
// Two arrays compared value by value (docs/formulas.md section 21). A value passes when
//   |a - b| <= max(rtol * max(|a|, |b|), atol),
// or, in ULP mode, when a and b are at most that many representable numbers of the array's
// type apart; integers must be equal. NaN equals NaN only where both are NaN, and an infinity
// only the same infinity. Where the standard errors of both files' values are known
// (statistical mode), the values with a combined standard error > 0 are judged together as
// Monte Carlo noise (NoiseTest.h), component by component; the others by the rule.
#include "NoiseTest.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace shadelab
{
/// The type of an array's values: it sets the default tolerance and the rule.
enum class ValueType
{
  Float32,
  Float64,
  Integer,
};

/// One array's values, tuple by tuple (components of a tuple together). Integers are kept in
/// `integers`, floating-point values in `reals`.
struct ArrayValues
{
  ValueType type = ValueType::Float64;
  int components = 1;
  std::vector<double> reals;
  std::vector<std::int64_t> integers;

  std::size_t size() const { return type == ValueType::Integer ? integers.size() : reals.size(); }
  std::size_t tuples() const { return components > 0 ? size() / static_cast<std::size_t>(components) : 0; }
  /// The largest finite value less the smallest, over every component (0 if none is finite).
  double range() const;
};

/// The default relative tolerance: a few units in the last place of the type (4 epsilon:
/// 4.8e-7 for float32, 8.9e-16 for float64), and 0 for integers, which must be equal.
double defaultRelativeTolerance(ValueType type);

/// How the values of one array are judged.
struct ValueRule
{
  double absolute = 0;
  double relative = 0;
  std::optional<long long> ulps; // ULP mode: replaces absolute and relative
  /// Statistical mode: k, the combined standard errors beyond which a value counts as outside.
  std::optional<double> standardErrors;
  /// Statistical mode: the chance that two honest runs fail, for the whole array.
  double significance = 0.001;
};

/// The differences between two arrays of the same type and shape.
struct ArrayDifference
{
  std::size_t values = 0;  // compared
  std::size_t failing = 0; // values that do not pass the rule (in statistical mode, of those judged by it)
  std::size_t nanInBoth = 0, nanInOne = 0;
  double largest = 0; // of |a - b| over values that are not NaN in both
  double sumOfSquares = 0;
  /// The failing value with the largest difference, or, if none fails, the value with the
  /// largest difference (none if all are equal): its index, tuple * components + component.
  std::optional<std::size_t> worst;
  /// Integers: how many values differ in each bit.
  std::array<std::size_t, 64> bitCounts{};
  /// Statistical mode: values with a combined standard error > 0, and how many of them lie
  /// within 1, 2 and 3 of it.
  std::size_t withStandardError = 0;
  std::array<std::size_t, 3> withinStandardErrors{};
  /// Statistical mode: the values whose standard errors are both 0, judged by the rule.
  std::size_t exactValues = 0;
  /// Statistical mode: the noise checks of each component (empty otherwise).
  std::vector<NoiseCheck> noise;
  /// Per tuple: whether every component passes (in statistical mode, lies within k standard
  /// errors or passes the rule).
  std::vector<unsigned char> tuplePasses;

  bool passes() const;
  double rms() const;
  double l2() const;
};

/// Compares a and b (the same type, components and size) by the rule. errorsA and errorsB are
/// the standard errors of each value (floating-point, the same shape), used in statistical
/// mode; other error arrays are ignored.
ArrayDifference compareArrays(const ArrayValues& a, const ArrayValues& b, const ValueRule& rule,
  const ArrayValues* errorsA = nullptr, const ArrayValues* errorsB = nullptr);

/// The number of representable values of the type from a to b (0 where equal, -0 and +0
/// alike); a NaN or a difference beyond 2^62 gives 2^62. For Float32, a and b are the array's
/// values, floats held as doubles (others are rounded to float first).
long long ulpDistance(double a, double b, ValueType type);
}
