#include "GaussLegendre.h"

#include <cmath>

namespace shadelab
{
GaussLegendreRule gaussLegendreRule(int n)
{
  constexpr double pi = 3.14159265358979323846;
  GaussLegendreRule rule;
  for (int i = 0; i < n; ++i)
  {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double derivative = 0;
    for (int iteration = 0; iteration < 100; ++iteration)
    {
      // P_n(x) by the three-term recurrence (k + 1) P_{k+1} = (2k + 1) x P_k - k P_{k-1}.
      double previous = 1;
      double current = x;
      for (int k = 1; k < n; ++k)
      {
        const double next = ((2 * k + 1) * x * current - k * previous) / (k + 1);
        previous = current;
        current = next;
      }
      derivative = n * (x * current - previous) / (x * x - 1);
      const double step = current / derivative;
      x -= step;
      if (std::abs(step) < 1e-16)
      {
        break;
      }
    }
    rule.nodes.push_back(x);
    rule.weights.push_back(2 / ((1 - x * x) * derivative * derivative));
  }
  return rule;
}
}
