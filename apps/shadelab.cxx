// shadelab: the command line over ShadeLab's filters, one file per subcommand.
//   shadelab shade MESH --scene SCENE.json -o OUT.vtp   per-vertex lighting arrays (ShadeCommand)
//   shadelab arrays --scene SCENE.json                  the arrays a scene can produce (ArraysCommand)
//   shadelab render MESH -o OUT.png                     a picture of one array (RenderCommand)
//   shadelab compare BASELINE RESULT                    two files' arrays value by value (CompareCommand)
//   shadelab relight MESH --envmap MAP -o OUT           prt's transfer under another map (RelightCommand)
// (The developers' benchmark and studies are bench/shadelab-bench.)
#include "ArraysCommand.h"
#include "CommandLineParse.h"
#include "CompareCommand.h"
#include "MeshFiles.h"
#include "RelightCommand.h"
#include "RenderCommand.h"
#include "RunProcesses.h"
#include "ShadeCommand.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <string>

int main(int argc, char** argv)
{
  using namespace shadelab::app;
  // Under mpiexec, the processes shade a mesh split among them; only the first prints.
  const RunProcesses processes(&argc, &argv);
  CLI::App cli{ "ShadeLab: per-vertex lighting and reflectance terms as VTK arrays." };
  cli.require_subcommand(1);
  ShadeOptions shade;
  CLI::App* shadeCommand = addShadeCommand(cli, shade);
  std::string arraysScene;
  CLI::App* arraysCommand = addArraysCommand(cli, arraysScene);
  RenderCommandOptions render;
  CLI::App* renderCommand = addRenderCommand(cli, render);
  CompareOptions compare;
  CLI::App* compareCommand = addCompareCommand(cli, compare);
  RelightOptions relight;
  CLI::App* relightCommand = addRelightCommand(cli, relight);

  bool verbose = false;
  for (CLI::App* command : { shadeCommand, arraysCommand, renderCommand, compareCommand, relightCommand })
  {
    command->add_flag("--verbose,-v", verbose, "also show VTK's own log and error output");
  }

  // Exit codes: 0 done, 1 bad input or a failed run, 2 a command line that does not parse
  // (compare: 0 the files agree, 1 they differ, 2 one cannot be read or an option is wrong).
  if (const std::optional<int> exitCode = parseCommandLine(cli, argc, argv, verbose))
  {
    return *exitCode;
  }
  try
  {
    if (shadeCommand->parsed())
    {
      return runShade(shade);
    }
    if (runProcessCount() > 1)
    {
      throw UserError("only `shadelab shade` runs under mpiexec, a piece of the mesh on each process; run `shadelab " +
        cli.get_subcommands().front()->get_name() + "` without it");
    }
    if (renderCommand->parsed())
    {
      return runRender(render);
    }
    if (compareCommand->parsed())
    {
      return runCompare(compare);
    }
    if (relightCommand->parsed())
    {
      return runRelight(relight);
    }
    return runArrays(arraysScene);
  }
  catch (const UserError& error)
  {
    std::cerr << "shadelab: " << error.what() << "\n";
    return 1;
  }
  // Whatever else ends a run ends it with one line too: a path the system refuses (too long,
  // say), or memory that ran out outside the places that expect it.
  catch (const std::filesystem::filesystem_error& error)
  {
    std::cerr << "shadelab: " << error.path1().string() << ": " << error.code().message() << "\n";
    return 1;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << "shadelab: not enough memory for this run (a smaller mesh, fewer arrays or float32 need less)\n";
    return 1;
  }
  catch (const std::exception& error)
  {
    std::cerr << "shadelab: " << error.what() << "\n";
    return 1;
  }
}
