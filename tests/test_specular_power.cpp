// The specular lobe's x^eta: the series and Schlick approximations against std::pow, and the
// error bound a tolerance relies on.
#include "SpecularPower.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace
{
using namespace shadelab;

TEST(SpecularPower, SeriesAgreesWithPowWithinItsTruncationError)
{
  // In double the series' own truncation dominates: log2 to 4e-8 absolute, exp2 to 5e-9
  // relative, so relative error below about 3e-8 eta + 5e-9 (measured 3.3e-8 eta at worst).
  for (const double eta : { 1.0, 7.5, 30.0, 1000.0 })
  {
    for (int k = 1; k <= 1000; ++k)
    {
      const double x = k / 1000.0;
      const double exact = std::pow(x, eta);
      if (exact > 1e-300)
      {
        EXPECT_LE(std::abs(powSeries(x, eta) - exact), exact * (4e-8 * eta + 1e-8)) << "x " << x << " eta " << eta;
      }
    }
  }
}

TEST(SpecularPower, SeriesAtItsFailurePoints)
{
  // C++'s pow(0, 0) = 1, x = 0 gives 0, x = 1 gives 1, and results below the smallest
  // normal number (1 - 1e-3)^1e5 = 3.5e-44 underflow to 0 rather than to garbage.
  EXPECT_EQ(powSeries(0.0, 0.0), 1.0);
  EXPECT_EQ(powSeries(0.0f, 0.0f), 1.0f);
  EXPECT_EQ(powSeries(0.0f, 5.0f), 0.0f);
  EXPECT_EQ(powSeries(1.0, 1000.0), 1.0);
  EXPECT_EQ(powSeries(0.999f, 1e5f), 0.0f);
  EXPECT_EQ(powSeries(0.7, 0.0), 1.0);
}

TEST(SpecularPower, WholePowersAreTheNearestFloat)
{
  // Binary exponentiation in double, rounded once to float: within 0.5 + 2e-9 eta ulp of the
  // true x^eta (long double pow, 64-bit mantissa), so the nearest float at every x of a grid
  // uniform in [0, 1], dense below 1, and at the smallest floats, where the power underflows.
  // glibc's powf is allowed 0.82 ulp; wholePowers is held to the nearest float here.
  std::vector<float> x;
  for (int k = 0; k <= 4096; ++k)
  {
    x.push_back(k / 4096.0f);
  }
  for (int j = 1; j <= 2000; ++j)
  {
    x.push_back(1.0f - j * 0x1p-24f);
  }
  for (const float tiny : { 0x1p-149f, 1e-30f, 0x1p-75f, 0x1.000002p-75f, 0x1p-5f })
  {
    x.push_back(tiny);
  }
  std::vector<float> y(x.size());
  for (const unsigned eta : { 0u, 1u, 2u, 3u, 30u, 32u, 100u, 1000u, 65536u })
  {
    wholePowers(x.data(), y.data(), x.size(), eta);
    int differ = 0;
    std::ostringstream first;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
      const float nearest = static_cast<float>(std::pow(static_cast<long double>(x[i]), static_cast<long double>(eta)));
      if (y[i] != nearest && differ++ == 0)
      {
        first << "x " << x[i] << ": " << y[i] << " instead of " << nearest;
      }
    }
    EXPECT_EQ(differ, 0) << "eta " << eta << ", first at " << first.str();
  }
  // Its largest error over [0, 1] is float rounding (half an ulp of 1 is 3e-8), as powf's.
  EXPECT_LT(largestWholePowerError(30), 3.0e-8);
  EXPECT_LT(largestWholePowerError(65536), 3.0e-8);
  // pow(0, 0) = 1; x^1 = x down to the smallest subnormal; 2^-150 is halfway to the smallest
  // float and rounds to even, 0, while anything above it rounds up.
  const float edge[] = { 0.0f, 0x1p-149f, 0x1p-75f, 0x1.000002p-75f };
  float out[4];
  wholePowers(edge, out, 4, 0);
  EXPECT_EQ(out[0], 1.0f);
  wholePowers(edge, out, 4, 1);
  EXPECT_EQ(out[1], 0x1p-149f);
  wholePowers(edge, out, 4, 2);
  EXPECT_EQ(out[2], 0.0f);
  EXPECT_EQ(out[3], 0x1p-149f);
}

TEST(SpecularPower, WholeExponents)
{
  EXPECT_TRUE(isWholeExponent(0));
  EXPECT_TRUE(isWholeExponent(30));
  EXPECT_TRUE(isWholeExponent(65536));
  EXPECT_FALSE(isWholeExponent(7.5));
  EXPECT_FALSE(isWholeExponent(65537));
  EXPECT_FALSE(isWholeExponent(-1));
}

TEST(SpecularPower, SchlickAtKnownPoints)
{
  EXPECT_DOUBLE_EQ(powSchlick(0.5, 10.0), 0.5 / 5.5); // x / (eta - eta x + x)
  EXPECT_DOUBLE_EQ(powSchlick(0.3, 1.0), 0.3);        // exact for eta = 1
  EXPECT_EQ(powSchlick(1.0, 1000.0), 1.0);
  EXPECT_EQ(powSchlick(0.0, 1000.0), 0.0);
  EXPECT_EQ(powSchlick(0.0, 0.0), 1.0); // 0/0 taken as pow(0, 0) = 1
}

TEST(SpecularPower, LargestErrorsOverTheLobe)
{
  // std::pow in double is exact to rounding; in float, to rounding of a float (2^-24 ~ 6e-8).
  EXPECT_LT(largestPowError<double>(PowMethod::Exact, 30), 1e-15);
  EXPECT_LT(largestPowError<float>(PowMethod::Exact, 30), 6e-8);
  // The series: within about twice float rounding in float.
  for (const double eta : { 1.0, 30.0, 1000.0, 10000.0 })
  {
    EXPECT_LT(largestPowError<float>(PowMethod::Series, eta), 1.2e-7) << eta;
    EXPECT_LT(largestPowError<double>(PowMethod::Series, eta), 3e-8) << eta;
  }
  // Schlick's form is much broader than x^eta: its largest error grows from 0 at eta = 1
  // towards 0.2 (0.155 at eta = 5, 0.195 at 30, 0.203 at 1000).
  EXPECT_EQ(largestPowError<double>(PowMethod::Schlick, 1), 0.0);
  EXPECT_NEAR(largestPowError<double>(PowMethod::Schlick, 5), 0.155, 0.001);
  EXPECT_NEAR(largestPowError<double>(PowMethod::Schlick, 1000), 0.203, 0.001);
}
}
