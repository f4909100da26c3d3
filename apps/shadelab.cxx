// shadelab: the command line over ShadeLab's filters.
//   shadelab shade MESH --scene SCENE.json -o OUT.vtp   per-vertex lighting arrays
//   shadelab arrays --scene SCENE.json                  the arrays a scene can produce
//   shadelab render MESH -o OUT.png                     a picture of one array
//   shadelab compare BASELINE RESULT                    two files' arrays value by value
// (The developers' benchmark and studies are bench/shadelab-bench.)
#include "CommandLineParse.h"
#include "CompareCommand.h"
#include "MeshFiles.h"
#include "PlanBeforeRun.h"
#include "ProgressLine.h"
#include "RelightCommand.h"
#include "RenderImage.h"
#include "RunWarnings.h"
#include "StageTime.h"
#include "VtkErrorCapture.h"

#include "ArrayCatalog.h"
#include "DefaultLightKit.h"
#include "EnvironmentMap.h"
#include "MaterialArrays.h"
#include "NumberText.h"
#include "SceneFile.h"
#include "SceneFrame.h"
#include "ShadeLabMeshExtent.h"
#include "ShadingFlags.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace
{
using namespace shadelab;
using app::Clock;
using app::RunWarnings;
using app::secondsSince;
using app::UserError;

std::string modelName(const Scene& scene)
{
  return scene.model == ShadingModel::Lecture ? "lecture" : "vtk";
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

std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

/// The names of every array the scene can add to the mesh.
std::vector<std::string> arrayNamesOf(const Scene& scene, const std::string& prefix)
{
  std::vector<std::string> names;
  for (const ArrayDescription& description : availableArrays(scene, prefix))
  {
    names.push_back(description.name);
  }
  const std::vector<std::string> spectral = spectralArrayNames(scene, prefix);
  names.insert(names.end(), spectral.begin(), spectral.end());
  return names;
}

/// How many tuples of a float32 or float64 array have a NaN or Inf component, read through
/// its own type (no virtual call per value); 0 for an integer array.
vtkIdType nonFiniteTuples(vtkDataArray* array)
{
  vtkIdType count = 0;
  auto tally = [&count](auto* typed)
  {
    for (const auto tuple : vtk::DataArrayTupleRange(typed))
    {
      count += std::any_of(tuple.begin(), tuple.end(), [](auto value) { return !std::isfinite(value); }) ? 1 : 0;
    }
  };
  vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(array, tally);
  return count;
}

/// Refuses to write a result with a NaN or Inf in an array the run computed: every estimator
/// is finite over the values a scene file accepts (tests/test_accepted_ranges.cxx), so one
/// here is a defect to report, never a result. The input's own arrays pass through as given.
void refuseNonFinite(vtkPolyData* output, const Scene& scene, const std::string& prefix)
{
  for (const std::string& name : arrayNamesOf(scene, prefix))
  {
    vtkDataArray* array = output->GetPointData()->GetArray(name.c_str());
    const vtkIdType nonFinite = array ? nonFiniteTuples(array) : 0;
    if (nonFinite > 0)
    {
      throw UserError("'" + name + "' is NaN or Inf at " + countOf(std::size_t(nonFinite), "vertex") +
        ", a defect of ShadeLab's: nothing was written; please report it with the mesh and the scene");
    }
  }
}

/// Prints what a person wants to see after a run: the arrays and their ranges, the flags.
void printSummary(vtkPolyData* output, const Scene& scene, const std::string& prefix)
{
  std::cout << "  arrays written (min and max over all components):\n";
  vtkPointData* pointData = output->GetPointData();
  std::vector<std::pair<std::string, vtkDataArray*>> written;
  for (const std::string& name : arrayNamesOf(scene, prefix))
  {
    vtkDataArray* array = pointData->GetArray(name.c_str());
    if (array && name != flagsArrayName(prefix))
    {
      written.emplace_back(name, array);
    }
  }
  // Names in a column 28 wide, or as wide as the longest and a space.
  std::size_t width = 28;
  for (const auto& [name, array] : written)
  {
    width = std::max(width, name.size() + 1);
  }
  for (const auto& [name, array] : written)
  {
    double low = 0, high = 0;
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      double range[2];
      array->GetRange(range, c);
      low = c == 0 ? range[0] : std::min(low, range[0]);
      high = c == 0 ? range[1] : std::max(high, range[1]);
    }
    std::cout << "    " << std::left << std::setw(static_cast<int>(width)) << name << std::right << std::setw(2)
              << array->GetNumberOfComponents() << "  " << std::setw(12) << std::setprecision(6) << low << " "
              << std::setw(12) << high << "\n";
  }
  if (auto* flags = vtkUnsignedCharArray::SafeDownCast(pointData->GetArray(flagsArrayName(prefix).c_str())))
  {
    std::cout << "  " << flagsArrayName(prefix) << ":";
    const unsigned char* values = flags->GetPointer(0);
    const std::size_t directed = std::count_if(scene.lights.begin(), scene.lights.end(),
      [](const NamedLight& light) { return !std::holds_alternative<AmbientLight>(light.source); });
    for (const FlagMeaning& flag : flagMeanings)
    {
      const vtkIdType count = std::count_if(
        values, values + flags->GetNumberOfValues(), [bit = flag.flag](unsigned char v) { return (v & bit) != 0; });
      std::cout << (flag.flag == FlagDegenerateNormal ? " " : ", ") << count << " with " << flag.meaning;
      if (flag.flag == FlagLightBelowHorizon && directed > 1)
      {
        std::cout << " (any one of the " << directed << " lights: most vertices of a closed mesh face away from one)";
      }
    }
    std::cout << "\n";
  }
}

/// `shade --envmap FILE` and its settings: an environment light added to the scene.
struct EnvironmentOption
{
  std::string name = "envmap";
  std::string file;
  std::string estimator = "sh";
  std::string directions; // empty: luminance (cosine for prt, which takes no other)
  int order = 0;          // prt's highest band; 0: not given (the light's default)
  double rotation = 0;
  double intensity = 1;
  std::string samples = std::to_string(Sampling{}.samples); // or "auto"
};

/// A count of samples as --ambient-occlusion and --envmap-samples give it: a number, or "auto"
/// (as many as --tolerance needs, the default count the least).
void setSampleCount(const std::string& count, Sampling& sampling)
{
  sampling.fromTolerance = count == "auto";
  if (!sampling.fromTolerance)
  {
    sampling.samples = std::stoi(count);
  }
}

struct ShadeOptions
{
  std::string mesh;
  std::string scene;
  std::string output;
  std::string arrays = "default";
  std::string precision = "float32";
  std::string prefix;
  std::string compression = "lz4";
  bool rawAppended = false;
  double tolerance = 0;
  int threads = 0;
  bool keepNormals = false;
  bool noWeld = false;
  double featureAngle = 80;
  double weldTolerance = 0;
  std::optional<double> splitAngle; // split sharp edges at this angle before shading
  EnvironmentOption environment;
  bool shadows = false;         // every light that can cast shadows casts them
  std::string selfShadowing;    // "smooth" or "facets"; empty: as the scene says
  std::string ambientOcclusion; // RAYS or "auto"; empty: as the scene says
  std::string colorBy;          // a point array that colours the material; empty: the scene's
  std::string colorMap = "cool to warm";
};

/// The scene with --shadows, --self-shadowing and --ambient-occlusion applied.
Scene withVisibilityOptions(Scene scene, const ShadeOptions& options)
{
  for (NamedLight& light : scene.lights)
  {
    light.shadows = light.shadows || (options.shadows && castsShadows(light.source));
  }
  if (!options.selfShadowing.empty())
  {
    scene.selfShadowing = options.selfShadowing == "facets" ? SelfShadowing::Facets : SelfShadowing::SmoothSurface;
  }
  if (!options.ambientOcclusion.empty())
  {
    AmbientOcclusion occlusion = scene.ambientOcclusion.value_or(AmbientOcclusion{});
    setSampleCount(options.ambientOcclusion, occlusion.sampling);
    scene.ambientOcclusion = occlusion;
  }
  return scene;
}

/// The scene file's lights, plus the --envmap light. Without --scene: the map alone under the
/// default material and viewer, or without a map either, the default light kit.
Scene sceneWithEnvironment(const std::string& sceneFile, const EnvironmentOption& environment)
{
  if (sceneFile.empty() && environment.file.empty())
  {
    return defaultLightKit();
  }
  Scene scene = sceneFile.empty() ? Scene{} : loadScene(sceneFile);
  if (environment.file.empty())
  {
    return scene;
  }
  for (const NamedLight& light : scene.lights)
  {
    if (light.name == environment.name)
    {
      throw UserError("--envmap: " + sceneFile + " already has a light named '" + environment.name +
        "', the name --envmap gives its light: rename that light");
    }
  }
  EnvironmentLight light;
  light.file = environment.file;
  light.rotationDegrees = environment.rotation;
  light.intensity = environment.intensity;
  light.estimator = environment.estimator == "brute_force" ? EnvironmentEstimator::BruteForce
    : environment.estimator == "monte_carlo"               ? EnvironmentEstimator::MonteCarlo
    : environment.estimator == "prt"                       ? EnvironmentEstimator::PrecomputedTransfer
                                                           : EnvironmentEstimator::SphericalHarmonics;
  const bool transfer = light.estimator == EnvironmentEstimator::PrecomputedTransfer;
  if (transfer && !environment.directions.empty() && environment.directions != "cosine")
  {
    throw UserError("--envmap-directions " + environment.directions +
      ": prt draws its shadow rays by the cosine, "
      "the density its transfer vectors are estimated for: leave --envmap-directions out");
  }
  if (!transfer && environment.order != 0)
  {
    throw UserError("--envmap-order: only --envmap-estimator prt has an order");
  }
  light.shOrder = environment.order != 0 ? environment.order : light.shOrder;
  light.directions = environment.directions == "cosine" ? EnvironmentDirections::Cosine
    : environment.directions == "mis"                   ? EnvironmentDirections::Mis
                                                        : EnvironmentDirections::Luminance;
  setSampleCount(environment.samples, light.sampling);
  try
  {
    light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(environment.file));
  }
  catch (const std::runtime_error& error)
  {
    throw UserError(std::string("--envmap: ") + error.what());
  }
  scene.lights.push_back({ environment.name, light });
  const std::vector<SceneProblem> problems = sceneProblems(scene);
  if (!problems.empty())
  {
    throw UserError("--envmap: " + problems.front().message);
  }
  return scene;
}

int runShade(const ShadeOptions& options)
{
  // Everything that can be checked before the slow work is checked first.
  const Scene scene = withVisibilityOptions(sceneWithEnvironment(options.scene, options.environment), options);
  const std::vector<std::string> selection = splitList(options.arrays);
  try
  {
    selectArrays(scene, selection);
  }
  catch (const std::invalid_argument& error)
  {
    throw UserError(std::string("--arrays: ") + error.what());
  }
  app::checkOutputFile(options.output, app::meshExtensions);

  if (options.threads > 0)
  {
    vtkSMPTools::Initialize(options.threads);
  }
  RunWarnings warnings;
  const Clock::time_point readStart = Clock::now();
  std::string ignored;
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(options.mesh, &ignored);
  warnings.collect(options.mesh);
  const double readSeconds = secondsSince(readStart);
  if (mesh->GetNumberOfPoints() == 0)
  {
    throw UserError(options.mesh + ": the mesh has no points"); // the filter passes an empty mesh on
  }

  vtkNew<vtkLocalReflectanceFilter> filter;
  vtkNew<vtkShadingNormalsFilter> splitter;
  vtkNew<app::VtkErrorCapture> errors;
  if (options.splitAngle)
  {
    // Splitting adds points, so it runs as a step of its own, before the shading filter: the
    // shading filter keeps point ids and count.
    splitter->SetInputData(mesh);
    splitter->KeepInputNormalsOff();
    splitter->SplitSharpEdgesOn();
    splitter->SetSplitAngle(*options.splitAngle);
    splitter->SetOrientOutward(!options.keepNormals);
    splitter->SetNormalsName(options.prefix + "Normals");
    errors->watch(splitter);
    filter->SetInputConnection(splitter->GetOutputPort());
  }
  else
  {
    filter->SetInputData(mesh);
  }
  filter->SetScene(scene);
  filter->SetArraySelection(selection);
  filter->SetArrayPrefix(options.prefix);
  filter->SetColorByArray(!options.colorBy.empty());
  filter->SetMaterialColorArray(options.colorBy);
  filter->SetMaterialColorMap(options.colorMap);
  filter->SetOutputPrecision(
    options.precision == "float64" ? vtkAlgorithm::DOUBLE_PRECISION : vtkAlgorithm::SINGLE_PRECISION);
  filter->SetOrientNormalsOutward(!options.keepNormals);
  filter->SetWeldCoincidentPoints(!options.noWeld);
  filter->SetFeatureAngle(options.featureAngle);
  filter->SetWeldTolerance(options.weldTolerance);
  filter->SetTolerance(options.tolerance);
  errors->watch(filter);
  vtkNew<app::ProgressLine> progress;
  progress->watch(filter, "shading");
  vtkNew<app::PlanBeforeRun> planBeforeRun;
  planBeforeRun->watch(filter);
  const Clock::time_point shadeStart = Clock::now();
  filter->Update();
  const double shadeSeconds = secondsSince(shadeStart);
  warnings.collect(options.mesh);
  if (errors->failed())
  {
    // A problem of the scene's values names the scene's source, as the scene file's own
    // checks do; any other, the mesh.
    const std::string sceneProblem = filter->GetSceneProblem();
    // Occlusion's rays, when --ambient-occlusion set them, are the option's problem.
    const std::string occlusionRays = "/ambient_occlusion/rays: ";
    if (!options.ambientOcclusion.empty() && sceneProblem.rfind(occlusionRays, 0) == 0)
    {
      throw UserError(
        "--ambient-occlusion " + options.ambientOcclusion + ": " + sceneProblem.substr(occlusionRays.size()));
    }
    if (!sceneProblem.empty())
    {
      const std::string source = !options.scene.empty() ? options.scene
        : options.environment.file.empty()              ? "the default light kit"
                                                        : "--envmap " + options.environment.file;
      throw UserError(source + ": " + sceneProblem);
    }
    throw UserError(options.mesh + ": " + errors->message());
  }
  vtkPolyData* output = filter->GetOutput();
  refuseNonFinite(output, scene, options.prefix);

  const Clock::time_point writeStart = Clock::now();
  app::writeMesh(output, options.output, app::compressionNamed(options.compression),
    options.rawAppended ? app::VtpLayout::RawAppended : app::VtpLayout::Inline);
  warnings.collect(options.output);
  const double writeSeconds = secondsSince(writeStart);

  warnings.show();
  std::cout << "shadelab shade: " << options.mesh << " -> " << options.output << "\n"
            << "  mesh: " << output->GetNumberOfPoints() << " vertices, "
            << output->GetNumberOfPolys() + output->GetNumberOfStrips() << " polygons and strips\n"
            << (ignored.empty() ? "" : "  ignored: " + ignored + "\n") << "  scene: "
            << (!options.scene.empty()                ? options.scene
                   : options.environment.file.empty() ? "the default light kit, placed on the mesh"
                                                      : "default material and viewer")
            << (options.environment.file.empty() ? "" : " + --envmap " + options.environment.file) << " ("
            << modelName(scene) << " model, " << countOf(scene.lights.size(), "light") << ")\n"
            << "  normals: " << (options.splitAngle ? splitter->GetReport() + " " : "") << filter->GetNormalsReport()
            << "\n";
  if (!filter->GetVisibilityReport().empty())
  {
    std::cout << "  visibility: " << filter->GetVisibilityReport() << "\n";
  }
  if (filter->GetMethodPlan())
  {
    const std::vector<std::string> lines = filter->GetMethodPlan()->describe();
    const std::size_t shown = planBeforeRun->shownLines();
    std::cout << "  methods:" << (shown ? " as printed before shading, then\n" : "\n");
    for (std::size_t l = shown; l < lines.size(); ++l)
    {
      std::cout << "    " << lines[l] << "\n";
    }
    for (const std::string& line : filter->GetSamplingReport())
    {
      std::cout << "    " << line << "\n";
    }
  }
  printSummary(output, scene, options.prefix);
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::cout << std::setprecision(3) << "  time: read " << readSeconds << " s, shade " << shadeSeconds << " s ("
            << threads << (threads == 1 ? " thread, " : " threads, ")
            << (options.tolerance > 0 ? "methods above" : options.precision) << "), write " << writeSeconds << " s\n";
  return 0;
}

struct RenderCommand
{
  std::string mesh;
  std::string output;
  std::string scene;
  std::string size = "800x600";
  app::RenderOptions options;
};

int runRender(RenderCommand& command)
{
  int width = 0, height = 0;
  char separator = 0;
  std::istringstream size(command.size);
  if (!(size >> width >> separator >> height) || separator != 'x' || width < 16 || height < 16 || width > 8192 ||
    height > 8192)
  {
    throw UserError("--size: '" + command.size + "' is not WIDTHxHEIGHT with each from 16 to 8192");
  }
  command.options.width = width;
  command.options.height = height;
  const Scene scene = command.scene.empty() ? defaultLightKit() : loadScene(command.scene);
  RunWarnings warnings;
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(command.mesh);
  warnings.collect(command.mesh);
  command.options.viewer = placedOnMesh(scene, meshExtentOf(mesh)).viewer;
  const std::vector<std::string> notes = app::renderToPng(mesh, command.mesh, command.options, command.output);
  warnings.show();
  std::cout << "shadelab render: " << command.options.array << " of " << command.mesh << " -> " << command.output
            << " (" << width << "x" << height << ")\n";
  for (const std::string& note : notes)
  {
    std::cout << "  " << note << "\n";
  }
  return 0;
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

/// value as a number, when the whole of it is one.
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

/// A CLI11 check for a finite number >= 0 (CLI11's NonNegativeNumber prints its bound, the
/// largest double, in 300 digits, and lets infinity through).
CLI::Validator finiteNonNegative()
{
  return CLI::Validator(
    [](std::string& value)
    {
      const std::optional<double> number = numberIn(value);
      return number && std::isfinite(*number) && *number >= 0 ? std::string()
                                                              : "'" + value + "' is not a finite number >= 0";
    },
    "NUMBER >= 0");
}

/// A prefix for array names: letters, digits and _, so that every file format and ParaView
/// can store and show the names (VTK 9.1's XML writer does not escape them).
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

/// A CLI11 check that a number lies in [low, high], saying so in the numbers' own words (CLI11's
/// Range prints doubles as 0.000000).
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
/// `shade`'s options, read into options.
CLI::App* addShadeCommand(CLI::App& cli, ShadeOptions& options)
{
  CLI::App* command = cli.add_subcommand("shade",
    "Shade a mesh under a scene and write the terms as point-data arrays.\n"
    "Reads .vtp, .vtk, .ply, .obj, .stl; writes .vtp (binary, compressed) or legacy .vtk\n(binary).");
  command->add_option("mesh", options.mesh, "the mesh to shade")->required();
  command->add_option("--scene,-s", options.scene,
    "scene file (JSON; schema in docs/guide/scene-files.md); without it, a three-point light kit with a "
    "little ambient light, placed and scaled to fit the mesh, or with --envmap, the map alone under the "
    "default material and a viewer at infinity looking down -z");
  command->add_option("--output,-o", options.output, "output file, .vtp or .vtk")->required();
  command
    ->add_option("--arrays,-a", options.arrays,
      "comma-separated arrays to compute: default (totals and shading_flags), totals, all, "
      "*_TERM (that term for every light, e.g. *_cos_incidence) or full names (e.g. key_diffuse); "
      "'shadelab arrays --scene FILE' lists them")
    ->capture_default_str();
  CLI::Option* precisionOption = command->add_option("--precision", options.precision, "arithmetic and output arrays")
                                   ->check(CLI::IsMember({ "float32", "float64" }))
                                   ->capture_default_str();
  command
    ->add_option("--tolerance", options.tolerance,
      "largest absolute error allowed in the shaded values: ShadeLab then chooses the cheapest "
      "precision and, per light, approximations (a point light as distant, a faster pow) whose "
      "predicted errors fit, and with ambient occlusion the rays' share (the sampled part at 95% "
      "confidence; --ambient-occlusion auto draws as many rays as it needs), and prints what it chose before the run, "
      "with a forecast of the samples, rays and time where it samples; "
      "0 (default): exact methods")
    ->check(finiteNonNegative())
    ->excludes(precisionOption);
  command->add_option("--threads,-j", options.threads, "threads (0: all cores)")
    ->check(CLI::Range(0, 256))
    ->capture_default_str();
  app::addCompressionOption(
    command, options.compression, ".vtp compression: lz4 is fastest, zlib gives files about a third smaller");
  command->add_flag("--raw-appended", options.rawAppended,
    ".vtp with its data raw in one block at the end: a quarter smaller and faster to write, but "
    "Debian 12's ParaView 5.11 reads it as empty since its Expat security update (docs/guide/command-line.md, 'Files "
    "ParaView opens')");
  CLI::Option* colorBy = command->add_option("--color-by", options.colorBy,
    "colour the material (kd, and ka with it) by this point array of the mesh instead of the scene's kd: RGB or "
    "RGBA colours as they are (8-bit ones decoded from sRGB, except in the vtk model, which reads them as VTK "
    "does), a 1-component field through --colormap over its range (docs/guide/scene-files.md, 'A material from "
    "the mesh's arrays')");
  command->add_option("--colormap", options.colorMap, "the colour map of a --color-by field")
    ->check(CLI::IsMember(shadelab::colorMapNames()))
    ->needs(colorBy)
    ->capture_default_str();
  command
    ->add_option("--prefix", options.prefix,
      "prepended to every array name written (to keep clear of the input's own arrays): letters, digits and _")
    ->check(arrayNamePrefix());
  command->add_flag(
    "--keep-normal-orientation", options.keepNormals, "do not flip normals that point into a closed mesh");
  command->add_flag("--no-weld", options.noWeld,
    "computed normals: give each point the normal of its own polygons only, even where several points "
    "share a position (by default they share one, as if the file had not split them at seams)");
  command
    ->add_option("--feature-angle", options.featureAngle,
      "computed normals: points at one position whose polygons meet at an edge sharper than this many "
      "degrees keep their own normals, so that edges the file split on purpose stay sharp")
    ->check(numberFromTo(0, 180))
    ->capture_default_str();
  command
    ->add_option("--weld-tolerance", options.weldTolerance,
      "computed normals: points closer than this fraction of the mesh's bounding-box diagonal count as "
      "one position (default 0: the same coordinates, as files store the copies of a split point)")
    ->check(numberFromTo(0, 0.1))
    ->capture_default_str();
  command
    ->add_option("--split-sharp-edges", options.splitAngle,
      "DEGREES (30 is usual): compute normals after duplicating the points of edges sharper than this "
      "(vtkPolyDataNormals' splitting), so that each side of a sharp edge gets its own normal, for a mesh "
      "that stores such edges' points once; the output then has MORE points than the input, and the "
      "mesh's own normals are replaced")
    ->check(numberFromTo(0, 180));
  command->add_flag("--shadows", options.shadows,
    "the mesh casts the shadows of every " + shadowCastingTypeNames() +
      " light (rays against its own "
      "triangles; a local light's <light>_visibility, 0 or 1, multiplies its diffuse and specular terms; an area "
      "light's or a map's is the visible fraction of its irradiance, from a ray per sample)");
  command
    ->add_option("--self-shadowing", options.selfShadowing,
      "smooth or facets, as the scene's \"self_shadowing\" (default smooth): with smooth, a vertex's own facets do "
      "not hide a light its normal faces (no speckles at the shadow terminator of a bumpy mesh); with facets, every "
      "facet hides what it blocks")
    ->check(CLI::IsMember({ "smooth", "facets" }));
  command
    ->add_option("--ambient-occlusion", options.ambientOcclusion,
      "RAYS per vertex, or auto: the ambient term becomes ka La times the cosine-weighted fraction of the sky "
      "each vertex sees past the mesh (arrays ambient_occlusion and its _std_error; bent_normal and "
      "sky_view_factor on request, -a all); 64 is usual. auto (with --tolerance): each vertex draws rays in "
      "rounds until its standard error is within its share of the tolerance, at most the scene's max_rays "
      "(4096), and ambient_occlusion_rays says how many it drew")
    ->check(CLI::Range(2, maxSamplesPerVertex) | CLI::IsMember({ "auto" }));
  EnvironmentOption& environment = options.environment;
  CLI::Option* envmapOption = command->add_option("--envmap", environment.file,
    "add an environment light named 'envmap' from this equirectangular map (.hdr, .exr: twice as wide "
    "as high, +y up, the image centre toward -z; docs/guide/lights-and-estimators.md)");
  command
    ->add_option("--envmap-estimator", environment.estimator,
      "its irradiance: sh (9 spherical-harmonic coefficients), monte_carlo (sampled, as --envmap-directions "
      "says), brute_force (every texel of the map downsampled to 128x64) or prt (precomputed radiance transfer: "
      "the array envmap_sh_transfer holds each vertex's transfer vector, with --shadows from --envmap-samples "
      "cosine-weighted shadow rays, and `shadelab relight` lights it with any other map)")
    ->check(CLI::IsMember({ "sh", "monte_carlo", "brute_force", "prt" }))
    ->capture_default_str()
    ->needs(envmapOption);
  command
    ->add_option("--envmap-order", environment.order,
      "prt's highest spherical-harmonic band, 2 to 4: (order + 1)^2 transfer coefficients per vertex (default 2)")
    ->check(CLI::Range(2, largestShOrder))
    ->needs(envmapOption);
  command
    ->add_option("--envmap-rotation", environment.rotation,
      "turn the map about +y by this many degrees (anticlockwise seen from above)")
    ->capture_default_str()
    ->needs(envmapOption);
  command->add_option("--envmap-intensity", environment.intensity, "multiply the map's radiance")
    ->check(finiteNonNegative())
    ->capture_default_str()
    ->needs(envmapOption);
  command
    ->add_option("--envmap-directions", environment.directions,
      "where its samples' directions come from: luminance (importance sampling of the map), cosine "
      "(cosine-weighted about the normal) or mis (half each way, weighted by both densities: robust where a "
      "shadow hides the bright part of the map); for monte_carlo, and with --shadows for every estimator's rays "
      "(default luminance; prt's are always cosine)")
    ->check(CLI::IsMember({ "luminance", "cosine", "mis" }))
    ->needs(envmapOption);
  command
    ->add_option("--envmap-samples", environment.samples,
      "Monte Carlo samples per vertex (monte_carlo, the specular term of sh and prt, and with --shadows every "
      "estimator's shadow rays, from which prt estimates its transfer vectors), or auto with --tolerance: as many as "
      "each vertex needs for the map's share of the tolerance, at least 64 and at most 4096 (with --shadows, their "
      "shadow rays drawn with them; not for prt with --shadows, whose count is fixed)")
    ->check(CLI::Range(2, maxSamplesPerVertex) | CLI::IsMember({ "auto" }))
    ->capture_default_str()
    ->needs(envmapOption);
  envmapOption->check(CLI::Validator(
    [](std::string& file) { return file.empty() ? std::string("needs the map's file name") : std::string(); }, "FILE"));
  return command;
}

/// `arrays`'s option, read into sceneFile.
CLI::App* addArraysCommand(CLI::App& cli, std::string& sceneFile)
{
  CLI::App* command = cli.add_subcommand("arrays", "List the arrays a scene can produce.");
  command->add_option("--scene,-s", sceneFile, "scene file (JSON)")->required();
  return command;
}

/// `render`'s options, read into options.
CLI::App* addRenderCommand(CLI::App& cli, RenderCommand& options)
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
  command->add_option("--array,-a", options.options.array, "the point array to draw")->capture_default_str();
  command->add_option("--scene,-s", options.scene,
    "take the camera from this scene's viewer (default: the default light kit's, which frames the "
    "mesh looking down -z)");
  command->add_option("--size", options.size, "image size, WIDTHxHEIGHT")->capture_default_str();
  command->add_flag("--srgb", options.options.srgb,
    "encode a 3-component array's values with the sRGB transfer function before drawing, as a renderer "
    "does with its linear output: a mesh shaded with its own colours (decoded from sRGB) then shows them");
  command
    ->add_option("--exposure", options.options.exposure,
      "multiply a 3-component array's values by this before drawing them (and before --srgb): values above 1 "
      "are drawn clipped, and render says how many and which exposure brings them into range")
    ->check(CLI::Validator(
      [](std::string& value)
      {
        const std::optional<double> number = numberIn(value);
        return number && std::isfinite(*number) && *number > 0 ? std::string()
                                                               : "'" + value + "' is not a finite number > 0";
      },
      "NUMBER > 0"))
    ->capture_default_str();
  return command;
}

}

int main(int argc, char** argv)
{
  CLI::App cli{ "ShadeLab: per-vertex lighting and reflectance terms as VTK arrays." };
  cli.require_subcommand(1);
  ShadeOptions shade;
  CLI::App* shadeCommand = addShadeCommand(cli, shade);
  std::string arraysScene;
  CLI::App* arraysCommand = addArraysCommand(cli, arraysScene);
  RenderCommand render;
  CLI::App* renderCommand = addRenderCommand(cli, render);
  shadelab::app::CompareOptions compare;
  CLI::App* compareCommand = shadelab::app::addCompareCommand(cli, compare);
  shadelab::app::RelightOptions relight;
  CLI::App* relightCommand = shadelab::app::addRelightCommand(cli, relight);

  bool verbose = false;
  for (CLI::App* command : { shadeCommand, arraysCommand, renderCommand, compareCommand, relightCommand })
  {
    command->add_flag("--verbose,-v", verbose, "also show VTK's own log and error output");
  }

  // Exit codes: 0 done, 1 bad input or a failed run, 2 a command line that does not parse
  // (compare: 0 the files agree, 1 they differ, 2 one cannot be read or an option is wrong).
  if (const std::optional<int> exitCode = shadelab::app::parseCommandLine(cli, argc, argv, verbose))
  {
    return *exitCode;
  }
  try
  {
    if (shadeCommand->parsed())
    {
      return runShade(shade);
    }
    if (renderCommand->parsed())
    {
      return runRender(render);
    }
    if (compareCommand->parsed())
    {
      return shadelab::app::runCompare(compare);
    }
    if (relightCommand->parsed())
    {
      return shadelab::app::runRelight(relight);
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
