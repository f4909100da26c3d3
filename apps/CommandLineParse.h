#pragma once
// Parsing a command line the same way in shadelab and shadelab-bench.
#include "MeshFiles.h"
#include "NearestName.h"
#include "VtkErrorCapture.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// What to say of the options on the command line that its command does not have: each with
/// the nearest option the command has, where one is near enough to be what was meant; "" where
/// every option is known.
inline std::string unknownOptionsAdvice(const CLI::App& cli, int argc, char** argv)
{
  const CLI::App* command = &cli;
  for (int i = 1; i < argc && command == &cli; ++i)
  {
    for (const CLI::App* sub : cli.get_subcommands([](const CLI::App*) { return true; }))
    {
      command = sub->get_name() == argv[i] ? sub : command;
    }
  }
  std::vector<std::string> known{ "help" };
  for (const CLI::Option* option : command->get_options())
  {
    known.insert(known.end(), option->get_lnames().begin(), option->get_lnames().end());
  }
  std::string advice;
  for (int i = 1; i < argc; ++i)
  {
    const std::string word = argv[i];
    const std::string name = word.substr(0, word.find('='));
    if (word.rfind("--", 0) != 0 || name.size() < 3 ||
      std::find(known.begin(), known.end(), name.substr(2)) != known.end())
    {
      continue;
    }
    const std::string meant = nearestName(name.substr(2), known);
    advice += (advice.empty() ? "" : "; ") + ("unknown option " + name) +
      (meant.empty() ? "" : ": did you mean --" + meant + "?");
  }
  const std::string program = std::filesystem::path(argv[0]).filename().string();
  return advice.empty() ? "" : (command == &cli ? program : program + " " + command->get_name()) + ": " + advice;
}

/// Parses argv into cli's options. Returns the exit code when the program ends here (0 after
/// --help, 2 for a command line that does not parse, CLI11's message or the nearest names of
/// unknown options printed), nothing otherwise; then quietens VTK's own output (quietenVtk)
/// unless verbose was set.
inline std::optional<int> parseCommandLine(CLI::App& cli, int argc, char** argv, const bool& verbose)
{
  try
  {
    cli.parse(argc, argv);
  }
  catch (const CLI::ParseError& error)
  {
    const std::string advice =
      dynamic_cast<const CLI::ExtrasError*>(&error) ? unknownOptionsAdvice(cli, argc, argv) : "";
    if (!advice.empty())
    {
      std::cerr << advice << "\nRun with --help for more information.\n";
      return 2;
    }
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
