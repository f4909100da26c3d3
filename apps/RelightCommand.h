#pragma once
// shadelab relight MESH --envmap MAP -o OUT: the irradiance under another map from the transfer
// vectors a mesh was shaded with ("estimator": "prt"), without tracing a ray
// (docs/guide/relighting.md).
#include <CLI/CLI.hpp>

#include <string>

namespace shadelab::app
{
struct RelightOptions
{
  std::string mesh, output;
  std::string environmentMap;
  double rotation = 0;
  double intensity = 1;
  std::string transferArray; // "": the one array ending in sh_transfer
  std::string outputArray = "relit_irradiance";
  bool directOnly = false; // leave out the transfer's indirect part where the mesh has it
  std::string compression = "lz4";
};

CLI::App* addRelightCommand(CLI::App& cli, RelightOptions& options);

/// Exit code 0 done; throws UserError for bad input.
int runRelight(const RelightOptions& options);
}
