#include "RenderCommand.h"

#include "MeshFiles.h"
#include "OptionValues.h"
#include "RunWarnings.h"

#include "DefaultLightKit.h"
#include "SceneFrame.h"
#include "ShadeLabMeshExtent.h"

#include <iostream>
#include <sstream>

namespace shadelab::app
{
CLI::App* addRenderCommand(CLI::App& cli, RenderCommandOptions& options)
{
  CLI::App* command = cli.add_subcommand("render",
    "Render one point array of a mesh (usually shade's output) to a PNG, off screen.\n"
    "3-component arrays are drawn as RGB colours clipped to [0, 1] with VTK's lighting off,\n"
    "so the picture is ShadeLab's shading (it counts the vertices drawn clipped); 1-component\n"
    "arrays through a colour map with a legend: flags and integers of a few values as named\n"
    "categories, other values on a colour bar.\n"
    "Needs an X display: on a headless machine run it as xvfb-run -a shadelab render ...");
  command->add_option("mesh", options.mesh, "the mesh to draw")->required();
  command->add_option("--output,-o", options.output, "the PNG to write")->required();
  command->add_option("--array,-a", options.image.array, "the point array to draw")->capture_default_str();
  command->add_option("--scene,-s", options.scene,
    "take the camera from this scene's viewer (default: the default light kit's, which frames the "
    "mesh looking down -z)");
  command->add_option("--size", options.size, "image size, WIDTHxHEIGHT")->capture_default_str();
  command->add_flag("--srgb", options.image.srgb,
    "encode a 3-component array's values with the sRGB transfer function before drawing, as a renderer "
    "does with its linear output: a mesh shaded with its own colours (decoded from sRGB) then shows them");
  command
    ->add_option("--exposure", options.image.exposure,
      "multiply a 3-component array's values by this before drawing them (and before --srgb): values above 1 "
      "are drawn clipped, and render says how many and which exposure brings them into range")
    ->check(finitePositive())
    ->capture_default_str();
  return command;
}

int runRender(const RenderCommandOptions& options)
{
  int width = 0, height = 0;
  char separator = 0;
  std::istringstream size(options.size);
  if (!(size >> width >> separator >> height) || separator != 'x' || width < 16 || height < 16 || width > 8192 ||
    height > 8192)
  {
    throw UserError("--size: '" + options.size + "' is not WIDTHxHEIGHT with each from 16 to 8192");
  }
  RenderOptions image = options.image;
  image.width = width;
  image.height = height;
  const Scene scene = options.scene.empty() ? defaultLightKit() : loadScene(options.scene);
  RunWarnings warnings;
  vtkSmartPointer<vtkPolyData> mesh = readMesh(options.mesh);
  warnings.collect(options.mesh);
  image.viewer = placedOnMesh(scene, meshExtentOf(mesh)).viewer;
  const std::vector<std::string> notes = renderToPng(mesh, options.mesh, image, options.output);
  warnings.show();
  std::cout << "shadelab render: " << image.array << " of " << options.mesh << " -> " << options.output << " (" << width
            << "x" << height << ")\n";
  for (const std::string& note : notes)
  {
    std::cout << "  " << note << "\n";
  }
  return 0;
}
}
