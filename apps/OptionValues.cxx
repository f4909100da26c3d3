#include "OptionValues.h"

#include "MeshFiles.h"
#include "SceneFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace shadelab::app
{
namespace
{
/// A CLI11 check for a finite number > 0, or >= 0 where zeroAllowed; relation says which in
/// words (">= 0").
CLI::Validator finiteNumberCheck(bool zeroAllowed, const std::string& relation)
{
  return CLI::Validator(
    [zeroAllowed, relation](std::string& value)
    {
      const std::optional<double> number = numberIn(value);
      const bool valid = number && std::isfinite(*number) && (*number > 0 || (zeroAllowed && *number == 0));
      return valid ? std::string() : "'" + value + "' is not a finite number " + relation;
    },
    "NUMBER " + relation);
}
}

std::optional<double> numberIn(const std::string& value)
{
  double number = 0;
  std::istringstream in(value);
  if ((in >> number) && (in >> std::ws).eof())
  {
    return number;
  }
  return std::nullopt;
}

CLI::Validator finiteNonNegative()
{
  return finiteNumberCheck(true, ">= 0");
}

CLI::Validator finitePositive()
{
  return finiteNumberCheck(false, "> 0");
}

CLI::Validator numberFromTo(double low, double high)
{
  std::ostringstream range;
  range << low << " to " << high;
  return CLI::Validator(
    [low, high, text = range.str()](std::string& value)
    {
      const std::optional<double> number = numberIn(value);
      return number && *number >= low && *number <= high ? std::string() : "Value " + value + " not in range " + text;
    },
    "NUMBER in [" + range.str() + "]");
}

CLI::Validator arrayNamePrefix()
{
  return CLI::Validator(
    [](std::string& value)
    {
      const bool valid = value.size() <= 64 &&
        std::all_of(
          value.begin(), value.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
      return valid ? std::string() : "use at most 64 letters, digits and _";
    },
    "PREFIX");
}

Scene loadScene(const std::string& fileName)
{
  try
  {
    return readSceneFile(fileName);
  }
  catch (const SceneFileError& error)
  {
    throw UserError(error.what());
  }
}
}
