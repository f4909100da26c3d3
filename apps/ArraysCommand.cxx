#include "ArraysCommand.h"

#include "OptionValues.h"

#include "ArrayCatalog.h"

#include <iomanip>
#include <iostream>

namespace shadelab::app
{
CLI::App* addArraysCommand(CLI::App& cli, std::string& sceneFile)
{
  CLI::App* command = cli.add_subcommand("arrays", "List the arrays a scene can produce.");
  command->add_option("--scene,-s", sceneFile, "scene file (JSON)")->required();
  return command;
}

int runArrays(const std::string& sceneFile)
{
  const Scene scene = loadScene(sceneFile);
  std::cout << "Arrays for " << sceneFile << " (select them with shade --arrays):\n";
  for (const ArrayDescription& array : availableArrays(scene))
  {
    std::cout << "  " << std::left << std::setw(28) << array.name << " " << array.components << "  "
              << array.description << "\n";
  }
  if (scene.spectral)
  {
    std::cout << "The scene is spectral: shade also writes each total it computes in XYZ as "
              << totalXyzArrayName("", TotalTerm::Ambient) << " and so on, and always "
              << totalArrayName("", TotalTerm::Total) << ", " << totalXyzArrayName("", TotalTerm::Total) << " and "
              << rgbDifferenceArrayName("") << " (the spectral total less the RGB model's), 3 components each.\n";
  }
  return 0;
}
}
