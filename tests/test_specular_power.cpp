// The specular lobe's x^eta: the series and Schlick approximations against std::pow, and the
// error bound a tolerance relies on.
#include "SpecularPower.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(SpecularPower, SchlickAtKnownPoints)
{
  EXPECT_DOUBLE_EQ(powSchlick(0.5, 10.0), 0.5 / 5.5); // x / (eta - eta x + x)
  EXPECT_DOUBLE_EQ(powSchlick(0.3, 1.0), 0.3);         // exact for eta = 1
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
