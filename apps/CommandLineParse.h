#pragma once
// Parsing a command line the same way in shadelab and shadelab-bench.
#include "MeshFiles.h"
#include "VtkErrorCapture.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// Parses argv into cli's options. Returns the exit code when the program ends here (0 after
/// --help, 2 for a command line that does not parse, CLI11's message printed), nothing
/// otherwise; then quietens VTK's own output (quietenVtk) unless verbose was set.
inline std::optional<int> parseCommandLine(CLI::App& cli, int argc, char** argv, const bool& verbose)
{
  try
  {
    cli.parse(argc, argv);
  }
  catch (const CLI::ParseError& error)
  {
    return cli.exit(error) == 0 ? 0 : 2;
  }
  if (!verbose)
  {
    quietenVtk();
  }
  return std::nullopt;
}

/// A command's --compression for the .vtp it writes: one of compressionNames, into `name`.
inline CLI::Option* addCompressionOption(CLI::App* command, std::string& name, const std::string& help)
{
  return command->add_option("--compression", name, help)
    ->check(CLI::IsMember(std::vector<std::string>(compressionNames.begin(), compressionNames.end())))
    ->capture_default_str();
}
}
