#include "ShadeReport.h"

#include "MeshFiles.h"
#include "NumberText.h"
#include "RunProcesses.h"

#include "ArrayCatalog.h"
#include "ShadeLabImportedParts.h"
#include "ShadeLabMeshPieces.h"
#include "ShadingFlags.h"

#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkFieldData.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>
#include <utility>

namespace shadelab::app
{
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

namespace
{
/// values reduced element by element over the run's processes by operation (vtkCommunicator's
/// SUM_OP, MIN_OP, MAX_OP), on every process; values as they are where the run has one.
std::vector<double> reducedOverProcesses(std::vector<double> values, int operation)
{
  vtkMultiProcessController* processes = runProcesses();
  if (!processes)
  {
    return values;
  }
  std::vector<double> reduced(values.size());
  processes->AllReduce(values.data(), reduced.data(), static_cast<vtkIdType>(values.size()), operation);
  return reduced;
}

/// What the visibility step's report covers where the run has several processes: the first
/// process's piece (its rays and times), which the first process prints.
std::string firstPieceOnly()
{
  return runProcessCount() > 1 ? " (the first process's piece)" : "";
}

/// The piece's points and polygons as the whole mesh counts them (a collective call): where
/// pieces share points (under several processes, or a .pvtp's pieces read in one), each point
/// once over them (its first copy by global id) and ghost cells not at all; otherwise every
/// point and polygon of the mesh, as it is.
class WholeMeshTally
{
public:
  WholeMeshTally(vtkPolyData* piece, bool piecesSharePoints)
  {
    vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
    if (piecesSharePoints && onAnyRunProcess(ids != nullptr))
    {
      counted_ = firstCopies(runProcesses(), idsOf(ids));
    }
    const double points = counted_.empty() ? double(piece->GetNumberOfPoints())
                                           : double(std::count(counted_.begin(), counted_.end(), true));
    const double polygons =
      piecesSharePoints ? double(ownPolygons(piece)) : double(piece->GetNumberOfPolys() + piece->GetNumberOfStrips());
    const std::vector<double> whole = reducedOverProcesses({ points, polygons }, vtkCommunicator::SUM_OP);
    points_ = static_cast<vtkIdType>(whole[0]);
    polygons_ = static_cast<vtkIdType>(whole[1]);
  }
  /// Whether the piece's point is counted here (not a copy of one another piece counts).
  bool counted(vtkIdType point) const { return counted_.empty() || counted_[static_cast<std::size_t>(point)]; }
  vtkIdType points() const { return points_; }
  vtkIdType polygons() const { return polygons_; }

private:
  /// The ids as a list; every process stops alike where one has no memory for it.
  static std::vector<vtkIdType> idsOf(vtkDataArray* ids)
  {
    std::vector<vtkIdType> list;
    bool allocated = true;
    try
    {
      list.resize(static_cast<std::size_t>(ids ? ids->GetNumberOfTuples() : 0));
    }
    catch (const std::bad_alloc&)
    {
      allocated = false;
    }
    if (!everyProcessHolds(runProcesses(), allocated))
    {
      throw std::runtime_error("not enough memory to count the mesh's points for the report");
    }
    for (std::size_t k = 0; k < list.size(); ++k)
    {
      list[k] = static_cast<vtkIdType>(ids->GetTuple1(static_cast<vtkIdType>(k)));
    }
    return list;
  }

  /// The piece's polygons and strips, ghost cells left out.
  static vtkIdType ownPolygons(vtkPolyData* piece)
  {
    const vtkIdType first = piece->GetNumberOfVerts() + piece->GetNumberOfLines();
    const vtkIdType count = piece->GetNumberOfPolys() + piece->GetNumberOfStrips();
    auto* ghosts =
      vtkUnsignedCharArray::SafeDownCast(piece->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
    vtkIdType own = count;
    for (vtkIdType c = first; ghosts && c < first + count && c < ghosts->GetNumberOfValues(); ++c)
    {
      own -= (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL) != 0 ? 1 : 0;
    }
    return own;
  }

  std::vector<bool> counted_;
  vtkIdType points_ = 0;
  vtkIdType polygons_ = 0;
};

/// Where the mesh has materials of its own (an OBJ's MTL): whether they shade it, and if not,
/// why; "" for a mesh without.
std::string ownMaterialsText(vtkPolyData* mesh, const Scene& scene, const ShadeOptions& options)
{
  if (!hasOwnMaterials(mesh))
  {
    return "";
  }
  auto* names = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(partNamesArrayName));
  const vtkIdType parts = names ? names->GetNumberOfValues() : 0;
  std::string list;
  for (vtkIdType p = 0; p < std::min<vtkIdType>(parts, 8); ++p)
  {
    list += (p ? ", " : "") + names->GetValue(p);
  }
  list += parts > 8 ? ", ..." : "";
  const std::string partsText = countOf(std::size_t(parts), "part") + (list.empty() ? "" : ": " + list);
  if (shadesWithOwnMaterials(scene, mesh, !options.colorBy.empty()))
  {
    return "the mesh's own, part by part (" + partsText + ")" +
      (scene.model == ShadingModel::Lecture && everyPartTwoSided(mesh) ? ", two-sided (every part is)" : "");
  }
  const std::string instead = scene.materialGiven ? "the scene's"
    : !options.colorBy.empty()                    ? "--color-by's"
    : scene.model == ShadingModel::VtkOpenGL2
    ? "the vtk model's (it reproduces VTK's renderer, not the file's materials)"
    : "the vtk_pbr model's defaults (the file's materials are not metallic-roughness ones: an MTL file's are the "
      "lecture model's)";
  return instead + ", in place of the mesh's own (" + partsText + ")";
}

/// The report's opening: the files, the mesh, the scene and the normals.
void printRunHeading(const ShadingPipeline& pipeline, const Scene& scene, const WholeMeshTally& tally,
  const RunFacts& facts, const ShadeOptions& options)
{
  vtkPolyData* output = pipeline.filter->GetOutput();
  const std::string& environmentMap = options.overrides.environment.file;
  const std::string ownMaterials = ownMaterialsText(output, scene, options);
  const int processes = runProcessCount();
  std::cout << "shadelab shade: " << options.mesh << " -> " << options.output
            << (processes > 1 ? " (" + std::to_string(processes) + " processes, a piece each)" : "") << "\n"
            << "  mesh: " << tally.points() << " vertices, " << tally.polygons() << " polygons and strips\n"
            << (facts.ignored.empty() ? "" : "  ignored: " + facts.ignored + "\n") << "  scene: " << facts.sceneOrigin
            << (environmentMap.empty() ? "" : " + --envmap " + environmentMap) << " (" << modelName(scene.model)
            << " model, " << countOf(scene.lights.size(), "light") << ")\n"
            << (ownMaterials.empty() ? "" : "  material: " + ownMaterials + "\n")
            << "  normals: " << (options.splitAngle ? pipeline.splitter->GetReport() + " " : "")
            << pipeline.filter->GetNormalsReport() << "\n";
}

/// The visibility step's report, and under a tolerance the methods chosen (those printed
/// before the run not again) and what sampling left.
void printVisibilityAndMethods(const ShadingPipeline& pipeline)
{
  vtkLocalReflectanceFilter* filter = pipeline.filter;
  if (!filter->GetVisibilityReport().empty())
  {
    std::cout << "  visibility" << firstPieceOnly() << ": " << filter->GetVisibilityReport() << "\n";
  }
  if (filter->GetMethodPlan())
  {
    const std::vector<std::string> lines = filter->GetMethodPlan()->describe();
    const std::size_t shown = pipeline.planBeforeRun->shownLines();
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
}

/// Each array written with its range over all components, names in a column 28 wide or as wide
/// as the longest and a space.
void printArrayRanges(vtkPointData* pointData, const Scene& scene, const std::string& prefix)
{
  std::cout << "  arrays written (min and max over all components):\n";
  std::vector<std::pair<std::string, vtkDataArray*>> written;
  for (const std::string& name : arrayNamesOf(scene, prefix))
  {
    vtkDataArray* array = pointData->GetArray(name.c_str());
    if (onAnyRunProcess(array != nullptr) && name != flagsArrayName(prefix))
    {
      written.emplace_back(name, array);
    }
  }
  std::size_t width = 28;
  for (const auto& [name, array] : written)
  {
    width = std::max(width, name.size() + 1);
  }
  for (const auto& [name, array] : written)
  {
    // An empty piece's range is VTK's empty one, which the others' replace.
    double low = VTK_DOUBLE_MAX, high = VTK_DOUBLE_MIN;
    const int components = static_cast<int>(
      reducedOverProcesses({ array ? double(array->GetNumberOfComponents()) : 0 }, vtkCommunicator::MAX_OP)[0]);
    for (int c = 0; array && c < array->GetNumberOfComponents(); ++c)
    {
      double range[2];
      array->GetRange(range, c);
      low = std::min(low, range[0]);
      high = std::max(high, range[1]);
    }
    low = reducedOverProcesses({ low }, vtkCommunicator::MIN_OP)[0];
    high = reducedOverProcesses({ high }, vtkCommunicator::MAX_OP)[0];
    std::cout << "    " << std::left << std::setw(static_cast<int>(width)) << name << std::right << std::setw(2)
              << components << "  " << std::setw(12) << std::setprecision(6) << low << " " << std::setw(12) << high
              << "\n";
  }
}

/// How many vertices have each of the shading flags.
void printFlagCounts(
  vtkPointData* pointData, const Scene& scene, const WholeMeshTally& tally, const std::string& prefix)
{
  auto* flags = vtkUnsignedCharArray::SafeDownCast(pointData->GetArray(flagsArrayName(prefix).c_str()));
  if (!onAnyRunProcess(flags != nullptr))
  {
    return;
  }
  std::cout << "  " << flagsArrayName(prefix) << ":";
  const std::size_t directed = std::count_if(scene.lights.begin(), scene.lights.end(),
    [](const NamedLight& light) { return !std::holds_alternative<AmbientLight>(light.source); });
  for (const FlagMeaning& flag : flagMeanings)
  {
    double held = 0;
    for (vtkIdType i = 0; flags && i < flags->GetNumberOfValues(); ++i)
    {
      held += tally.counted(i) && (flags->GetValue(i) & flag.flag) != 0 ? 1 : 0;
    }
    const vtkIdType count = static_cast<vtkIdType>(reducedOverProcesses({ held }, vtkCommunicator::SUM_OP)[0]);
    std::cout << (flag.flag == FlagDegenerateNormal ? " " : ", ") << count << " with " << flag.meaning;
    if (flag.flag == FlagLightBelowHorizon && directed > 1)
    {
      std::cout << " (any one of the " << directed << " lights: most vertices of a closed mesh face away from one)";
    }
  }
  std::cout << "\n";
}

/// The interreflection step's report, and the ambient term it stands against: the mean of the
/// indirect diffuse term over the vertices, the constant ambient term nearest it (least
/// squares), beside the scene's mean ambient term.
void printInterreflection(
  const ShadingPipeline& pipeline, vtkPointData* pointData, const WholeMeshTally& tally, const std::string& prefix)
{
  const std::string& report = pipeline.filter->GetInterreflectionReport();
  if (!onAnyRunProcess(!report.empty()))
  {
    return;
  }
  std::cout << "  interreflection: " << report << "\n";
  auto meanOf = [&](const std::string& name) -> std::optional<Rgb>
  {
    vtkDataArray* array = pointData->GetArray(name.c_str());
    // The sums of each point's values, counted once, and how many points there were.
    std::vector<double> sums(4, 0.0);
    for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
    {
      if (tally.counted(i))
      {
        sums = { sums[0] + array->GetComponent(i, 0), sums[1] + array->GetComponent(i, 1),
          sums[2] + array->GetComponent(i, 2), sums[3] + 1 };
      }
    }
    sums = reducedOverProcesses(sums, vtkCommunicator::SUM_OP);
    if (sums[3] == 0)
    {
      return std::nullopt;
    }
    return Rgb(sums[0], sums[1], sums[2]) / sums[3];
  };
  auto rgbText = [](const Rgb& c)
  { return "(" + withDigits(c.r, 3) + ", " + withDigits(c.g, 3) + ", " + withDigits(c.b, 3) + ")"; };
  const std::optional<Rgb> indirect = meanOf(interreflectionArrayName(prefix, InterreflectionTerm::Indirect));
  const std::optional<Rgb> ambient = meanOf(totalArrayName(prefix, TotalTerm::Ambient));
  if (indirect)
  {
    std::cout << "    the constant ambient term nearest the indirect light (least squares over the vertices): "
              << rgbText(*indirect) << (ambient ? "; the scene's ambient term, on average: " + rgbText(*ambient) : "")
              << "\n";
  }
}

}

void printReport(
  const ShadingPipeline& pipeline, const Scene& scene, const RunFacts& facts, const ShadeOptions& options)
{
  vtkPolyData* output = pipeline.filter->GetOutput();
  const WholeMeshTally tally(output, runProcessCount() > 1 || lowerExtension(options.mesh) == ".pvtp");
  printRunHeading(pipeline, scene, tally, facts, options);
  printVisibilityAndMethods(pipeline);
  vtkPointData* pointData = output->GetPointData();
  printInterreflection(pipeline, pointData, tally, options.prefix);
  printArrayRanges(pointData, scene, options.prefix);
  printFlagCounts(pointData, scene, tally, options.prefix);
  const StageSeconds& seconds = facts.seconds;
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::cout << std::setprecision(3) << "  time: read " << seconds.read << " s, shade " << seconds.shade << " s ("
            << threads << (threads == 1 ? " thread, " : " threads, ")
            << (options.tolerance > 0 ? "methods above" : options.precision) << "), write " << seconds.write << " s\n";
}
}
