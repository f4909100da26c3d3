#pragma once
// What several subcommands do with their options' values: CLI11 checks for numbers and names
// that say what is wrong in the numbers' own words, the names of a scene file's choices, and
// the scene a --scene option names.
#include "Scene.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// value as a number, when the whole of it is one.
std::optional<double> numberIn(const std::string& value);

/// A CLI11 check for a finite number >= 0 (CLI11's NonNegativeNumber prints its bound, the
/// largest double, in 300 digits, and lets infinity through).
CLI::Validator finiteNonNegative();

/// A CLI11 check for a finite number > 0.
CLI::Validator finitePositive();

/// A CLI11 check that a number lies in [low, high], saying so in the numbers' own words (CLI11's
/// Range prints doubles as 0.000000).
CLI::Validator numberFromTo(double low, double high);

/// A prefix for array names: letters, digits and _, so that every file format and ParaView
/// can store and show the names (VTK 9.1's XML writer does not escape them).
CLI::Validator arrayNamePrefix();

/// The names of a scene file's table of choices (name and value pairs), for CLI::IsMember.
template<typename Table>
std::vector<std::string> namesIn(const Table& table)
{
  std::vector<std::string> names;
  for (const auto& [name, value] : table)
  {
    names.emplace_back(name);
  }
  return names;
}

/// The name a scene file's table of choices gives value.
template<typename Table, typename Value>
std::string nameIn(const Table& table, Value value)
{
  for (const auto& [name, named] : table)
  {
    if (named == value)
    {
      return name;
    }
  }
  return "";
}

/// The scene file an option names; its problems, which name the file and the place in it, as
/// the user's error (UserError).
Scene loadScene(const std::string& fileName);
}
