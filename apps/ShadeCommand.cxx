#include "ShadeCommand.h"

#include "CommandLineParse.h"
#include "GltfScene.h"
#include "MeshFiles.h"
#include "OptionValues.h"
#include "PieceFiles.h"
#include "PlanBeforeRun.h"
#include "ProgressLine.h"
#include "RunProcesses.h"
#include "RunWarnings.h"
#include "ShadeReport.h"
#include "StageTime.h"
#include "VtkErrorCapture.h"

#include "ArrayCatalog.h"
#include "DefaultLightKit.h"
#include "MaterialArrays.h"
#include "MethodChoice.h"
#include "NumberText.h"
#include "SceneFile.h"
#include "ShBands.h"
#include "ShadeLabImportedParts.h"
#include "ShadeLabMeshPieces.h"
#include "ShadingFlags.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace shadelab::app
{
namespace
{
/// The mesh, the scene, the output file and its arrays.
void addFileOptions(CLI::App* command, ShadeOptions& options)
{
  command->add_option("mesh", options.mesh, "the mesh to shade")->required();
  command->add_option("--scene,-s", options.scene,
    "scene file (JSON; schema in docs/guide/scene-files.md); without it, a three-point light kit with a "
    "little ambient light, placed and scaled to fit the mesh, or with --envmap, the map alone under the "
    "default material and a viewer at infinity looking down -z");
  command->add_option("--output,-o", options.output, "output file, .vtp, .pvtp or .vtk (under mpiexec, .pvtp)")
    ->required();
  command
    ->add_option("--arrays,-a", options.arrays,
      "comma-separated arrays to compute: default (totals and shading_flags), totals, all, "
      "*_TERM (that term for every light, e.g. *_cos_incidence) or full names (e.g. key_diffuse); "
      "'shadelab arrays --scene FILE' lists them")
    ->capture_default_str();
}

/// The arithmetic: its precision, or a tolerance that chooses it, and the threads.
void addPrecisionOptions(CLI::App* command, ShadeOptions& options)
{
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
}

/// The output's file layout, the material's colour from a point array, the arrays' names.
void addOutputOptions(CLI::App* command, ShadeOptions& options)
{
  addCompressionOption(
    command, options.compression, ".vtp compression: lz4 is fastest, zlib gives files about a third smaller");
  command->add_flag("--raw-appended", options.rawAppended,
    ".vtp with its data raw in one block at the end: a quarter smaller and faster to write, but "
    "Debian 12's ParaView 5.11 reads it as empty since its Expat security update (docs/guide/command-line.md, 'Files "
    "ParaView opens')");
  CLI::Option* colorBy = command->add_option("--color-by", options.colorBy,
    "colour the material (kd, and ka with it; the vtk_pbr model's base colour) by this point array of the mesh "
    "instead of the scene's: RGB or RGBA colours as they are (8-bit ones decoded from sRGB, except in the vtk and "
    "vtk_pbr models, which read them as VTK does), a 1-component field through --colormap over its range "
    "(docs/guide/scene-files.md, 'A material from "
    "the mesh's arrays')");
  command->add_option("--colormap", options.colorMap, "the colour map of a --color-by field")
    ->check(CLI::IsMember(colorMapNames()))
    ->needs(colorBy)
    ->capture_default_str();
  command
    ->add_option("--prefix", options.prefix,
      "prepended to every array name written (to keep clear of the input's own arrays): letters, digits and _")
    ->check(arrayNamePrefix());
}

/// How the normals are computed where the mesh has none, and whether they are turned outward.
void addNormalsOptions(CLI::App* command, ShadeOptions& options)
{
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
}

/// The scene's shadows, self-shadowing and ambient occlusion, overridden.
void addVisibilityOptions(CLI::App* command, SceneOverrides& overrides)
{
  command->add_flag("--shadows", overrides.shadows,
    "the mesh casts the shadows of every " + shadowCastingTypeNames() +
      " light (rays against its own "
      "triangles; a local light's <light>_visibility, 0 or 1, multiplies its diffuse and specular terms; an area "
      "light's or a map's is the visible fraction of its irradiance, from a ray per sample)");
  command
    ->add_option("--self-shadowing", overrides.selfShadowing,
      "smooth or facets, as the scene's \"self_shadowing\" (default smooth): with smooth, a vertex's own facets do "
      "not hide a light its normal faces (no speckles at the shadow terminator of a bumpy mesh); with facets, every "
      "facet hides what it blocks")
    ->check(CLI::IsMember(namesIn(selfShadowingNames)));
  command
    ->add_option("--ambient-occlusion", overrides.ambientOcclusion,
      "RAYS per vertex, or auto: the ambient term becomes ka La times the cosine-weighted fraction of the sky "
      "each vertex sees past the mesh (arrays ambient_occlusion and its _std_error; bent_normal and "
      "sky_view_factor on request, -a all); 64 is usual. auto (with --tolerance): each vertex draws rays in "
      "rounds until its standard error is within its share of the tolerance, at most the scene's max_rays "
      "(4096), and ambient_occlusion_rays says how many it drew")
    ->check(CLI::Range(2, maxSamplesPerVertex) | CLI::IsMember({ "auto" }));
  command
    ->add_option("--bounces", overrides.bounces,
      "K: add the light the mesh reflects onto itself, diffusely, over K bounces (the scene's \"interreflection\", "
      "its other settings kept: 64 gather rays per vertex by default); arrays indirect_irradiance with its "
      "_std_error, and indirect (kd times it), which diffuse and total include; indirect_bounce_<n> and "
      "ambient_minus_indirect on request (-a all). 0 turns it off. auto (with --tolerance): the fewest bounces "
      "whose rest fits the tolerance's share, and as many gather rays as the standard errors of a first run of 64 "
      "say the share needs (at most the scene's max_samples, 1024); the choice is printed with the methods")
    ->check(CLI::Range(0, Interreflection::maxBounces) | CLI::IsMember({ "auto" }));
}

/// --envmap and its settings: an environment light added to the scene. Their defaults shown are
/// the light's own.
void addEnvironmentMapOptions(CLI::App* command, EnvironmentMapOverride& environment)
{
  CLI::Option* envmapOption = command->add_option("--envmap", environment.file,
    "add an environment light named 'envmap' from this equirectangular map (.hdr, .exr: twice as wide "
    "as high, +y up, the image centre toward -z; docs/guide/lights-and-estimators.md)");
  command
    ->add_option("--envmap-estimator", environment.estimator,
      "its irradiance: sh (9 spherical-harmonic coefficients), monte_carlo (sampled, as --envmap-directions "
      "says), brute_force (every texel of the map downsampled to 128x64) or prt (precomputed radiance transfer: "
      "the array envmap_sh_transfer holds each vertex's transfer vector, with --shadows from --envmap-samples "
      "cosine-weighted shadow rays, and `shadelab relight` lights it with any other map)")
    ->check(CLI::IsMember(namesIn(environmentEstimatorNames)))
    ->default_str(nameIn(environmentEstimatorNames, EnvironmentLight{}.estimator))
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
    ->check(CLI::IsMember(namesIn(environmentDirectionNames)))
    ->needs(envmapOption);
  command
    ->add_option("--envmap-samples", environment.samples,
      "Monte Carlo samples per vertex (monte_carlo, the specular term of sh and prt, and with --shadows every "
      "estimator's shadow rays, from which prt estimates its transfer vectors), or auto with --tolerance: as many as "
      "each vertex needs for the map's share of the tolerance, at least 64 and at most 4096 (with --shadows, their "
      "shadow rays drawn with them; not for prt with --shadows, whose count is fixed)")
    ->check(CLI::Range(2, maxSamplesPerVertex) | CLI::IsMember({ "auto" }))
    ->default_str(std::to_string(Sampling{}.samples))
    ->needs(envmapOption);
  envmapOption->check(CLI::Validator(
    [](std::string& file) { return file.empty() ? std::string("needs the map's file name") : std::string(); }, "FILE"));
}

/// The scene the run shades: the scene file's (without one, the --envmap light alone under the
/// default material and viewer, or without a map either, the default light kit), with the
/// command line's overrides.
Scene sceneOf(const ShadeOptions& options)
{
  const bool environmentMap = !options.overrides.environment.file.empty();
  Scene read = !options.scene.empty() ? loadScene(options.scene) : environmentMap ? Scene{} : defaultLightKit();
  try
  {
    return withOverrides(std::move(read), options.overrides, options.scene);
  }
  catch (const SceneOverrideError& error)
  {
    throw UserError(error.what());
  }
}

/// Whether the run is lit by the mesh file's own lights (a glTF file's): the file has some, and
/// neither --scene nor --envmap gives others.
bool shadesWithFileLights(vtkPolyData* mesh, const ShadeOptions& options)
{
  return options.scene.empty() && options.overrides.environment.file.empty() && !fileLightsOf(mesh).empty();
}

/// The scene of the mesh file's lights (GltfScene.h), with the command line's overrides.
Scene sceneOfFileLights(vtkPolyData* mesh, const ShadeOptions& options)
{
  try
  {
    return withOverrides(parseScene(fileLightsOf(mesh), options.mesh + "'s lights"), options.overrides, "");
  }
  catch (const std::exception& error)
  {
    throw UserError(error.what());
  }
}

/// The items of a comma-separated list, empty ones left out.
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

/// The arrays --arrays names, checked against what the scene can produce.
std::vector<std::string> arraySelection(const Scene& scene, const std::string& arrays)
{
  const std::vector<std::string> selection = splitList(arrays);
  try
  {
    selectArrays(scene, selection);
  }
  catch (const std::invalid_argument& error)
  {
    throw UserError(std::string("--arrays: ") + error.what());
  }
  return selection;
}

/// Under mpiexec, the mesh file's own lights (a glTF file's) on every process's piece, so that
/// all shade one scene: a .pvtp's reader gives a process without a piece no field data.
void shareFileLights(vtkPolyData* mesh)
{
  if (runProcessCount() == 1)
  {
    return;
  }
  const std::string lights = firstText(runProcesses(), fileLightsOf(mesh));
  if (!lights.empty() && fileLightsOf(mesh).empty())
  {
    vtkNew<vtkStringArray> text;
    text->SetName(fileLightsArrayName);
    text->InsertNextValue(lights);
    mesh->GetFieldData()->AddArray(text);
  }
}

/// The mesh to shade, or under mpiexec this process's piece of it (what its file holds that the
/// reader skips, in ignored). A mesh without points is refused here: the filter would pass it
/// on empty.
vtkSmartPointer<vtkPolyData> readMeshToShade(const std::string& fileName, std::string& ignored, RunWarnings& warnings)
{
  vtkSmartPointer<vtkPolyData> mesh;
  onEveryProcess(
    [&]
    {
      mesh = readMesh(fileName, &ignored, { runProcessIndex(), runProcessCount() });
      warnings.collect(fileName);
    });
  if (!onAnyRunProcess(mesh->GetNumberOfPoints() > 0))
  {
    throw UserError(fileName + ": the mesh has no points");
  }
  shareFileLights(mesh);
  return mesh;
}

/// Where the run's scene came from, for the report.
std::string sceneOrigin(vtkPolyData* mesh, const ShadeOptions& options)
{
  return !options.scene.empty()                  ? options.scene
    : shadesWithFileLights(mesh, options)        ? "the file's own lights"
    : options.overrides.environment.file.empty() ? "the default light kit, placed on the mesh"
                                                 : "default material and viewer";
}

/// Where the run's processes write (one file, or under mpiexec a .pvtp of a piece each), and
/// what they can do.
void checkSplitRun(const ShadeOptions& options)
{
  const std::string& fileName = options.output;
  checkOutputFile(fileName, shadedMeshExtensions);
  const int processes = runProcessCount();
  if (processes > 1 && options.splitAngle)
  {
    throw UserError("--split-sharp-edges: splitting adds points, which a mesh split over processes cannot take: "
                    "split it in one process first (its output keeps the split normals, which shade then uses)");
  }
  if (processes > 1 && lowerExtension(fileName) != ".pvtp")
  {
    throw UserError(fileName + ": " + std::to_string(processes) +
      " processes write a piece of the mesh each: name a .pvtp, which ParaView opens as one mesh (its pieces "
      "go in a folder beside it)");
  }
  // Where a .pvtp cannot go is known before the work (and checked again when it is written).
  onEveryProcess(
    [&]
    {
      const std::string place =
        lowerExtension(fileName) == ".pvtp" && runProcessIndex() == 0 ? pvtpPlaceProblem(fileName) : "";
      if (!place.empty())
      {
        throw UserError(fileName + ": cannot be written: " + place);
      }
    });
}

/// Writes the shaded mesh, or under mpiexec each process's piece of it.
void writeShaded(vtkPolyData* output, const ShadeOptions& options)
{
  const VtpLayout layout = options.rawAppended ? VtpLayout::RawAppended : VtpLayout::Inline;
  if (lowerExtension(options.output) == ".pvtp")
  {
    writePieces(output, options.output, runProcesses(), compressionNamed(options.compression), layout);
  }
  else
  {
    writeMesh(output, options.output, compressionNamed(options.compression), layout);
  }
}

/// The mesh into the shading filter, through --split-sharp-edges' step where it is given; each
/// filter watched for errors, the shading's progress and plan shown as it runs.
void connectPipeline(ShadingPipeline& pipeline, vtkPolyData* mesh, const ShadeOptions& options)
{
  if (options.splitAngle)
  {
    // Splitting adds points, so it runs as a step of its own, before the shading filter: the
    // shading filter keeps point ids and count.
    vtkShadingNormalsFilter* splitter = pipeline.splitter;
    splitter->SetInputData(mesh);
    splitter->KeepInputNormalsOff();
    splitter->SplitSharpEdgesOn();
    splitter->SetSplitAngle(*options.splitAngle);
    splitter->SetOrientOutward(!options.keepNormals);
    splitter->SetNormalsName(options.prefix + "Normals");
    pipeline.errors->watch(splitter);
    pipeline.filter->SetInputConnection(splitter->GetOutputPort());
  }
  else
  {
    pipeline.filter->SetInputData(mesh);
  }
  pipeline.errors->watch(pipeline.filter);
  pipeline.progress->watch(pipeline.filter, "shading");
  pipeline.planBeforeRun->watch(pipeline.filter);
}

/// The shading filter's settings: the scene, the arrays and the options.
void configureShading(vtkLocalReflectanceFilter* filter, const Scene& scene, const std::vector<std::string>& selection,
  const ShadeOptions& options)
{
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
}

/// Why the run failed, as the user's error: a problem of the scene's values names where the
/// scene came from, as the scene file's own checks do; any other, the mesh.
void checkRun(const ShadingPipeline& pipeline, const ShadeOptions& options)
{
  if (!pipeline.errors->failed())
  {
    return;
  }
  const std::string sceneProblem = pipeline.filter->GetSceneProblem();
  auto problemText = [&] { return sceneProblem.substr(sceneProblem.find(": ") + 2); };
  // Occlusion, when --ambient-occlusion asked for it, is the option's problem.
  const std::string& ambientOcclusion = options.overrides.ambientOcclusion;
  if (!ambientOcclusion.empty() && sceneProblem.rfind("/ambient_occlusion", 0) == 0)
  {
    throw UserError("--ambient-occlusion " + ambientOcclusion + ": " + problemText());
  }
  // The material's arrays, when --color-by set them.
  if (!options.colorBy.empty() && sceneProblem.rfind("/material: ", 0) == 0)
  {
    throw UserError("--color-by " + options.colorBy + ": " + problemText());
  }
  // And interreflection's, when --bounces set it.
  const std::string& bounces = options.overrides.bounces;
  if (!bounces.empty() && sceneProblem.rfind("/interreflection", 0) == 0)
  {
    throw UserError("--bounces " + bounces + ": " + problemText());
  }
  if (!sceneProblem.empty())
  {
    const std::string& environmentMap = options.overrides.environment.file;
    const std::string source = !options.scene.empty() ? options.scene
      : environmentMap.empty()                        ? "the default light kit"
                                                      : "--envmap " + environmentMap;
    throw UserError(source + ": " + sceneProblem);
  }
  throw UserError(options.mesh + ": " + pipeline.errors->message());
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

}

CLI::App* addShadeCommand(CLI::App& cli, ShadeOptions& options)
{
  CLI::App* command = cli.add_subcommand("shade",
    "Shade a mesh under a scene and write the terms as point-data arrays.\n"
    "Reads .vtp, .pvtp, .vtk, .ply, .stl, .obj (with its MTL file's materials and textures), .gltf and .glb\n"
    "(with their materials, base colour textures and KHR_lights_punctual lights); writes .vtp (binary,\n"
    "compressed), .pvtp (a folder of pieces beside it) or legacy .vtk (binary).\n"
    "Under `mpiexec -np N` each process shades a piece of the mesh and writes it into one .pvtp, bit for bit\n"
    "what one process writes (docs/guide/mpi.md).");
  // In the order --help lists them.
  addFileOptions(command, options);
  addPrecisionOptions(command, options);
  addOutputOptions(command, options);
  addNormalsOptions(command, options);
  addVisibilityOptions(command, options.overrides);
  addEnvironmentMapOptions(command, options.overrides.environment);
  return command;
}

int runShade(const ShadeOptions& options)
{
  // Everything that can be checked before the slow work is checked first.
  Scene scene = sceneOf(options);
  if (const std::string problem = tolerancePlanProblem(scene); options.tolerance > 0 && !problem.empty())
  {
    throw UserError("--tolerance " + withDigits(options.tolerance, 6) + ": " + problem + ": use --precision");
  }
  // A glTF file may bring its own lights, whose arrays --arrays may name: checked once it is read.
  const bool lightsMayComeFromFile =
    isGltfFile(options.mesh) && options.scene.empty() && options.overrides.environment.file.empty();
  std::vector<std::string> selection =
    lightsMayComeFromFile ? std::vector<std::string>{} : arraySelection(scene, options.arrays);
  checkSplitRun(options);

  if (options.threads > 0)
  {
    vtkSMPTools::Initialize(options.threads);
  }
  // Under mpiexec each step that can fail on one process is agreed by all (onEveryProcess), so
  // that none waits for another that stopped.
  RunWarnings warnings;
  RunFacts facts;
  Clock::time_point start = Clock::now();
  vtkSmartPointer<vtkPolyData> mesh = readMeshToShade(options.mesh, facts.ignored, warnings);
  facts.seconds.read = secondsSince(start);
  onEveryProcess(
    [&]
    {
      if (shadesWithFileLights(mesh, options))
      {
        scene = sceneOfFileLights(mesh, options);
      }
      if (lightsMayComeFromFile)
      {
        selection = arraySelection(scene, options.arrays);
      }
    });
  facts.sceneOrigin = sceneOrigin(mesh, options);

  ShadingPipeline pipeline;
  connectPipeline(pipeline, mesh, options);
  configureShading(pipeline.filter, scene, selection, options);
  start = Clock::now();
  pipeline.filter->Update();
  facts.seconds.shade = secondsSince(start);
  vtkPolyData* output = pipeline.filter->GetOutput();
  onEveryProcess(
    [&]
    {
      warnings.collect(options.mesh);
      checkRun(pipeline, options);
      refuseNonFinite(output, scene, options.prefix);
    });

  start = Clock::now();
  writeShaded(output, options);
  warnings.collect(options.output);
  facts.seconds.write = secondsSince(start);

  warnings.gatherFromEveryProcess();
  warnings.show();
  printReport(pipeline, scene, facts, options);
  return 0;
}
}
