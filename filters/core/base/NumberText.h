#pragma once
// Numbers as text for messages and generated expressions.
#include <cstddef>
#include <sstream>
#include <string>

namespace shadelab
{
/// x with this many significant digits: 2 say how far out of range a value is in a message,
/// 17 give a double back exactly.
inline std::string withDigits(double x, int digits)
{
  std::ostringstream text;
  text.precision(digits);
  text << x;
  return text.str();
}

/// "1 light", "3 lights": a count and its noun, plural where the count is not 1.
inline std::string countOf(std::size_t count, const std::string& noun)
{
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}
}
