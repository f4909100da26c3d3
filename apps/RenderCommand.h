#pragma once
// shadelab render MESH -o OUT.png: a picture of one point array of a mesh, off screen (the
// picture itself is RenderImage's).
#include "RenderImage.h"

#include <CLI/CLI.hpp>

#include <string>

namespace shadelab::app
{
struct RenderCommandOptions
{
  std::string mesh;
  std::string output;
  std::string scene; // whose viewer places the camera; "": the default light kit's
  std::string size = "800x600";
  RenderOptions image;
};

CLI::App* addRenderCommand(CLI::App& cli, RenderCommandOptions& options);

/// Exit code 0 done; throws UserError for bad input.
int runRender(const RenderCommandOptions& options);
}
