#include "Precision.h"

#include "NumberText.h"

#include <cmath>
#include <limits>

namespace shadelab
{
const char* precisionName(Precision precision)
{
  return precision == Precision::Float32 ? "float32" : "float64";
}

double largestFinite(Precision precision)
{
  return precision == Precision::Float32 ? std::numeric_limits<float>::max() : std::numeric_limits<double>::max();
}

double coordinateLimit(Precision precision)
{
  // |a - b|^2 <= (2 limit)^2 = largest / 16: squared distances keep a margin for rounding.
  return std::sqrt(largestFinite(precision)) / 8;
}

std::string scientific(double x)
{
  return withDigits(x, 2);
}
}
