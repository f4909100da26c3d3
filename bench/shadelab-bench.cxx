// shadelab-bench: the developers' measurements, apart from the user's command.
//   shadelab-bench                         the filter's speed against baselines, by mesh size
//   shadelab-bench --end-to-end MESH       what shadelab shade spends on one mesh, stage by stage
//   shadelab-bench --charts DIR            the accuracy studies, as CSV and PNG charts
//   shadelab-bench --visibility DIR        what casting rays costs, and ambient occlusion's error
//   shadelab-bench --interreflection MESH  interreflection's time and memory against occlusion's
#include "AccuracyStudies.h"
#include "Benchmark.h"
#include "CommandLineParse.h"
#include "EndToEnd.h"
#include "InterreflectionBenchmark.h"
#include "MeshFiles.h"
#include "OffScreenImage.h"
#include "RayBenchmark.h"

#include "SceneFile.h"

#include "vtkSMPTools.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <regex>

namespace
{
using shadelab::app::UserError;

/// "10k", "2.5M" or "300" as a vertex count.
long long parseCount(const std::string& text)
{
  static const std::regex count("([0-9]+(\\.[0-9]*)?)([kKM]?)");
  std::smatch parts;
  double vertices = 0;
  if (std::regex_match(text, parts, count))
  {
    const std::string unit = parts[3];
    vertices = std::stod(parts[1]) * (unit.empty() ? 1 : unit == "M" ? 1e6 : 1e3);
  }
  if (!(vertices >= 100 && vertices <= 1e8))
  {
    throw UserError("--sizes: '" + text + "' is not a vertex count from 100 to 100M, such as 10k or 1M");
  }
  return std::llround(vertices);
}

struct BenchCommand
{
  std::string chartsFolder;
  std::vector<std::string> studyFilters;
  std::string visibilityFolder;
  std::vector<std::string> sizes{ "10k", "100k", "1M", "10M" };
  std::string bunny = "data/meshes/bunny_zipper.ply";
  bool noBunny = false;
  int threads = 0;
  shadelab::app::BenchmarkOptions options;
  shadelab::app::EndToEndOptions endToEnd;
  shadelab::app::InterreflectionBenchmarkOptions interreflection;
};

int run(BenchCommand& command)
{
  if (command.threads > 0)
  {
    vtkSMPTools::Initialize(command.threads);
  }
  if (!command.endToEnd.scene.empty() && command.endToEnd.mesh.empty() && command.interreflection.mesh.empty())
  {
    throw UserError("--scene is the scene of --end-to-end or --interreflection: give one of them");
  }
  if (!command.interreflection.mesh.empty())
  {
    command.interreflection.repeats = command.options.maxRepeats;
    command.interreflection.scene =
      command.endToEnd.scene.empty() ? command.interreflection.scene : command.endToEnd.scene;
    shadelab::app::runInterreflectionBenchmark(command.interreflection);
    return 0;
  }
  if (!command.endToEnd.mesh.empty())
  {
    command.endToEnd.minRepeats = command.options.maxRepeats;
    shadelab::app::runEndToEnd(command.endToEnd);
    return 0;
  }
  command.options.sizes.clear();
  for (const std::string& size : command.sizes)
  {
    command.options.sizes.push_back(parseCount(size));
  }
  if (!command.noBunny)
  {
    if (!std::ifstream(command.bunny))
    {
      throw UserError(command.bunny +
        ": no such file (the subdivided bunny is one of the meshes; "
        "run from the repository's top folder, give --bunny FILE, or pass --no-bunny)");
    }
    command.options.bunnyFile = command.bunny;
  }
  if (!command.visibilityFolder.empty() || !command.chartsFolder.empty())
  {
    shadelab::app::requireDisplay(); // before the minutes of work whose charts it draws
  }
  if (!command.visibilityFolder.empty())
  {
    shadelab::app::RayBenchmarkOptions rays;
    rays.folder = command.visibilityFolder;
    rays.bunnyFile = command.bunny;
    rays.repeats = command.options.maxRepeats;
    shadelab::app::runRayBenchmark(rays);
    return 0;
  }
  if (!command.chartsFolder.empty())
  {
    if (command.noBunny)
    {
      throw UserError("--charts measures on the subdivided bunny: leave out --no-bunny");
    }
    shadelab::app::AccuracyOptions accuracy;
    accuracy.directory = command.chartsFolder;
    accuracy.bunnyFile = command.bunny;
    accuracy.maxRepeats = command.options.maxRepeats;
    accuracy.studyFilters = command.studyFilters;
    shadelab::app::runAccuracyStudies(accuracy);
    return 0;
  }
  shadelab::app::runBenchmark(command.options);
  return 0;
}
}

int main(int argc, char** argv)
{
  CLI::App cli{ "shadelab-bench: ShadeLab's speed, memory and accuracy, for its developers.\n"
                "By default, times the filter on spheres and the subdivided Stanford bunny, from 10 thousand to 10\n"
                "million vertices, against vtkArrayCalculator evaluating the same expression and against\n"
                "the floor of copying the same bytes; prints a table and optionally writes it as CSV." };
  BenchCommand command;
  cli.add_option("--sizes", command.sizes, "vertex counts, comma-separated (k and M allowed)")
    ->delimiter(',')
    ->capture_default_str();
  cli.add_option("--repeats", command.options.maxRepeats, "runs per measurement at most (median taken)")
    ->check(CLI::Range(1, 100))
    ->capture_default_str();
  cli.add_option("--csv", command.options.csvFile, "also write the table to this CSV file");
  cli.add_option("--bunny", command.bunny, "the bunny mesh to subdivide")->capture_default_str();
  cli.add_flag("--no-bunny", command.noBunny, "spheres only");
  cli.add_option("--case", command.options.caseFilters,
    "only the cases whose names contain this text (repeatable), such as --case lambert");
  CLI::Option* endToEnd = cli.add_option("--end-to-end", command.endToEnd.mesh,
    "instead, time what `shadelab shade MESH` spends, stage by stage (read, normals, orientation, shading, "
    "write; --repeats rounds, medians), against reading with VTK's reader alone and writing with VTK's writer "
    "alone, and print its peak memory against the bytes of the mesh and of the arrays written");
  CLI::Option* interreflection =
    cli
      .add_option("--interreflection", command.interreflection.mesh,
        "instead, shade MESH with 3 bounces of interreflection (64 gather rays per vertex) and with ambient occlusion "
        "at 64 rays per vertex in turn, in this process, and print their times, their peak memory and the ratios "
        "(--repeats rounds, medians; the 2.2M-vertex bunny of docs/dev/benchmarks.md is issue 46's mesh)")
      ->excludes(endToEnd);
  cli.add_option("--scene,-s", command.endToEnd.scene,
    "the scene for --end-to-end (default: the default light kit) or --interreflection (default: "
    "data/scenes/studio.json)");
  cli
    .add_option("--charts", command.chartsFolder,
      "instead, run the accuracy studies (float32, pow methods, a point light as distant, Phong against "
      "Blinn-Phong, tessellation, each at its failure point; the estimators of an area light and of two "
      "environment maps, and the SH estimator's speed; the spectral mode, interreflection, and the lecture's "
      "lobes against VTK's PBR microfacets, a texture at vertices) and write accuracy.csv and one PNG chart per study "
      "into "
      "this folder; reads data/scenes/area_lights.json and data/envmaps/; needs an X display (xvfb-run -a)")
    ->excludes(endToEnd)
    ->excludes(interreflection);
  cli
    .add_option("--study", command.studyFilters,
      "with --charts: only the studies whose names contain this text (repeatable), such as --study 8b; "
      "accuracy.csv then has their rows alone")
    ->needs("--charts");
  cli
    .add_option("--visibility", command.visibilityFolder,
      "instead, time ray casting (the BVH, shadow rays, ambient occlusion at 16, 64 and 256 rays, a softbox's and the "
      "studio map's soft shadows at 64 samples) on the bunny and the bunny subdivided to 2.2M vertices against "
      "vtkStaticCellLocator "
      "and Embree alone, ambient occlusion's error against its time (4 to 1024 rays against 4096) and a penumbra "
      "against its closed form; writes visibility.csv, 9_ambient_occlusion.png and 10_penumbra.png into this "
      "folder; needs an X display (xvfb-run -a); about a minute")
    ->excludes(endToEnd)
    ->excludes(interreflection);
  cli.add_option("--threads,-j", command.threads, "threads (0: all cores)")
    ->check(CLI::Range(0, 256))
    ->capture_default_str();
  bool verbose = false;
  cli.add_flag("--verbose,-v", verbose, "also show VTK's own log and error output");
  if (const std::optional<int> exitCode = shadelab::app::parseCommandLine(cli, argc, argv, verbose))
  {
    return *exitCode;
  }
  try
  {
    return run(command);
  }
  catch (const UserError& error)
  {
    std::cerr << "shadelab-bench: " << error.what() << "\n";
    return 1;
  }
  catch (const shadelab::SceneFileError& error)
  {
    std::cerr << "shadelab-bench: " << error.what() << "\n";
    return 1;
  }
  catch (const std::exception& error)
  {
    std::cerr << "shadelab-bench: " << error.what() << "\n";
    return 1;
  }
}
