#include "ToleranceRules.h"

#include <fnmatch.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace shadelab
{
std::pair<std::string, std::string> splitRule(const std::string& rule)
{
  const std::size_t colon = rule.rfind(':');
  if (colon == std::string::npos)
  {
    return { "*", rule };
  }
  return { rule.substr(0, colon), rule.substr(colon + 1) };
}

namespace
{
/// The whole of text as a finite double, or nothing.
std::optional<double> wholeNumber(const std::string& text)
{
  if (text.empty())
  {
    return std::nullopt;
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value))
  {
    return std::nullopt;
  }
  return value;
}
}

ToleranceValue parseToleranceValue(const std::string& text)
{
  static const std::string rangeSuffix = "*range";
  ToleranceValue tolerance;
  std::string number = text;
  if (number.size() > rangeSuffix.size() &&
    number.compare(number.size() - rangeSuffix.size(), rangeSuffix.size(), rangeSuffix) == 0)
  {
    tolerance.timesRange = true;
    number.resize(number.size() - rangeSuffix.size());
  }
  const std::optional<double> value = wholeNumber(number);
  if (!value || *value < 0)
  {
    throw std::invalid_argument(
      "'" + text + "' is not a tolerance: write a number >= 0 (1e-6), or one times the array's range (1e-3*range)");
  }
  tolerance.value = *value;
  return tolerance;
}

long long parseUlps(const std::string& text)
{
  const std::optional<double> value = wholeNumber(text);
  if (!value || *value < 0 || *value != std::floor(*value) || *value > 1e18)
  {
    throw std::invalid_argument("'" + text + "' is not a count of units in the last place: write a whole number >= 0");
  }
  return static_cast<long long>(*value);
}

bool wildcardMatches(const std::string& pattern, const std::string& name)
{
  return ::fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}
}
