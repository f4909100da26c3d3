#include "SequentialSampling.h"

#include <algorithm>
#include <cmath>

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
  return ruleOfThree >= maximum ? SamplingTarget{ error, maximum, maximum } : atLeast(error, static_cast<int>(std::ceil(ruleOfThree)), maximum);
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
}
