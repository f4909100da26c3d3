#pragma once
// The arithmetic a scene is evaluated in, and the ranges of values it can hold safely.
#include <string>

namespace shadelab
{
enum class Precision
{
  Float32,
  Float64,
};

const char* precisionName(Precision precision);

/// The largest finite value of the precision.
double largestFinite(Precision precision);

/// The largest |coordinate| (mesh points, light and viewer positions) that the precision
/// handles: squared distances between such points cannot overflow.
double coordinateLimit(Precision precision);

/// Two significant digits: enough for a message to say how far out of range a value is.
std::string scientific(double x);
}
