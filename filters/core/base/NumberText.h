#pragma once
// Numbers as text for messages and generated expressions.
#include <cmath>
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

/// A count in words, to two significant digits or whole: "960", "41 thousand", "2.5 million".
inline std::string roughCount(double count)
{
  auto rough = [](double x) { return x < 100 ? withDigits(x, 2) : std::to_string(std::llround(x)); };
  if (count >= 1e9)
  {
    return rough(count / 1e9) + " billion";
  }
  if (count >= 1e6)
  {
    return rough(count / 1e6) + " million";
  }
  return count >= 1e4 ? rough(count / 1e3) + " thousand" : std::to_string(std::llround(count));
}
}
