#pragma once
// Which tolerance applies to which array. Rules are written "PATTERN:VALUE", or "VALUE" for
// every array; patterns are shell wildcards (* ? [...]) matched against the whole name. The
// last rule that matches wins, so a general rule comes first and its exceptions after it:
//   --rtol 1e-6 --rtol '*_std_error:1e-3'
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadelab
{
/// A tolerance as written: a number, or a number times the array's range ("1e-3*range", the
/// baseline's largest value less its smallest over every component).
struct ToleranceValue
{
  double value = 0;
  bool timesRange = false;

  double of(double range) const { return timesRange ? value * range : value; }
};

/// The text before the last ':' and after it; no ':' gives the pattern "*".
std::pair<std::string, std::string> splitRule(const std::string& rule);

/// "1e-6" or "1e-3*range", >= 0. Throws std::invalid_argument with a message that quotes it.
ToleranceValue parseToleranceValue(const std::string& text);

/// A count of units in the last place, an integer >= 0. Throws std::invalid_argument.
long long parseUlps(const std::string& text);

/// Whether the shell wildcard pattern matches the whole of name.
bool wildcardMatches(const std::string& pattern, const std::string& name);

/// Rules of one kind, in the order given.
template<typename Value>
class PatternRules
{
public:
  void add(std::string pattern, Value value) { rules_.push_back({ std::move(pattern), std::move(value) }); }

  /// The value of the last rule whose pattern matches name, if any.
  std::optional<Value> find(const std::string& name) const
  {
    for (auto rule = rules_.rbegin(); rule != rules_.rend(); ++rule)
    {
      if (wildcardMatches(rule->first, name))
      {
        return rule->second;
      }
    }
    return std::nullopt;
  }

private:
  std::vector<std::pair<std::string, Value>> rules_;
};
}
