#include "SequentialSampling.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace shadelab
{
namespace
{
/// n rounded up to whole rounds.
int wholeRounds(double n)
{
  return samplingRound * static_cast<int>(std::ceil(n / samplingRound));
}
}

SamplingTarget SamplingTarget::forFraction(double error, int maximum)
{
  const double ruleOfThree = 3 / error;
  return ruleOfThree >= maximum ? SamplingTarget{ error, maximum, maximum }
                                : atLeast(error, static_cast<int>(std::ceil(ruleOfThree)), maximum);
}

SamplingTarget SamplingTarget::atLeast(double error, int samples, int maximum)
{
  return { error, std::min(maximum, std::max(samplingRound, wholeRounds(samples))), maximum };
}

int SamplingTarget::nextRound(int drawn, double standardErrorSoFar) const
{
  if (drawn >= maximum)
  {
    return 0;
  }
  if (drawn < minimum)
  {
    return minimum - drawn;
  }
  if (standardErrorSoFar <= standardError())
  {
    return 0;
  }
  const double ratio = standardErrorSoFar / standardError();
  const double needed = std::min(double(drawn) * ratio * ratio, double(maximum)) - drawn;
  return std::min({ maximum - drawn, drawn, std::max(samplingRound, wholeRounds(needed)) });
}

double estimatedErrorQuantile(std::vector<double> standardErrors, double fraction)
{
  for (double& s : standardErrors)
  {
    s = std::isnan(s) ? std::numeric_limits<double>::infinity() : s;
  }
  std::sort(standardErrors.begin(), standardErrors.end(), std::greater<double>());
  const double vertices = double(standardErrors.size());
  // The expected share of the vertices beyond x: a vertex whose standard error is below x / 9
  // adds less than 1e-18 (erfc(9 / sqrt 2)), so the sum stops there.
  auto shareBeyond = [&](double x)
  {
    double sum = 0;
    for (const double s : standardErrors)
    {
      if (!(s > x / 9))
      {
        break;
      }
      sum += std::erfc(x / (s * std::sqrt(2.0)));
    }
    return sum / vertices;
  };
  if (standardErrors.empty() || !(standardErrors.front() > 0) || !(shareBeyond(0) > 1 - fraction))
  {
    return 0;
  }
  // Bisection, to a billionth of x: the share beyond x falls from the share of non-zero
  // standard errors at 0 to below 1e-18 at 9 times the largest finite one (an infinite one
  // stays beyond every x).
  const auto largestFinite =
    std::find_if(standardErrors.begin(), standardErrors.end(), [](double s) { return std::isfinite(s); });
  double below = 0, above = largestFinite == standardErrors.end() ? 0 : 9 * *largestFinite;
  if (!(shareBeyond(above) <= 1 - fraction))
  {
    return std::numeric_limits<double>::infinity(); // more than 1 - fraction of them unbounded
  }
  while (above - below > 1e-9 * above)
  {
    const double x = (below + above) / 2;
    (shareBeyond(x) > 1 - fraction ? below : above) = x;
  }
  return above;
}
}
