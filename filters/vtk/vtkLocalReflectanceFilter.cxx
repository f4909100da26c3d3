#include "vtkLocalReflectanceFilter.h"

#include "ArrayCatalog.h"
#include "Colorimetry.h"
#include "MethodChoice.h"
#include "ShadeLabFieldNotes.h"
#include "ShadeLabThreadCount.h"
#include "ShadeLabWholeMesh.h"
#include "ShadeLabLargeArrays.h"
#include "ShadeLabMaterialArrays.h"
#include "SceneFrame.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabRunAborted.h"
#include "ShadingKernel.h"

#include "vtkArrayDispatch.h"
#include "vtkCommand.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArrayRange.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTypeUInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkLocalReflectanceFilter);

namespace
{
using shadelab::LightTerm;
using shadelab::TotalTerm;

/// Allocates the requested arrays of value type T on the output and points the kernel's
/// outputs at their memory.
template <typename T>
class OutputArrays
{
public:
  using ArrayType = vtkAOSDataArrayTemplate<T>;

  OutputArrays(const shadelab::Scene& scene, const shadelab::ArrayRequest& request,
    const std::string& prefix, vtkIdType count)
  {
    // In the order of shadelab::availableArrays: totals, flags, then each light's terms.
    for (int t = 0; t < shadelab::TotalTermCount; ++t)
    {
      outputs.totals[t] = request.totals[t]
        ? add(shadelab::totalArrayName(prefix, TotalTerm(t)), 3, count)
        : nullptr;
    }
    if (request.flags)
    {
      auto flags = vtkSmartPointer<vtkUnsignedCharArray>::New();
      flags->SetName(shadelab::flagsArrayName(prefix).c_str());
      allocate<unsigned char>(flags.GetPointer(), count);
      outputs.flags = flags->GetPointer(0);
      arrays.push_back(flags);
    }
    outputs.lights.resize(scene.lights.size());
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      outputs.lights[l].fill(nullptr);
      for (int t = 0; t < shadelab::LightTermCount; ++t)
      {
        if (request.lights[l][t])
        {
          outputs.lights[l][t] = add(shadelab::lightArrayName(prefix, scene.lights[l].name, LightTerm(t)),
            shadelab::lightTermComponents(scene.lights[l], LightTerm(t)), count);
        }
      }
    }
  }

  shadelab::ShadingOutputs<T> outputs;
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;

private:
  T* add(const std::string& name, int components, vtkIdType count)
  {
    auto array = vtkSmartPointer<ArrayType>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(components);
    allocate<T>(array.GetPointer(), count);
    arrays.push_back(array);
    return array->GetPointer(0);
  }

  /// Memory for `count` tuples, in huge pages when large (ShadeLabLargeArrays.h). Throws
  /// std::runtime_error, naming the array, when there is not enough.
  template <typename Value>
  static void allocate(vtkAOSDataArrayTemplate<Value>* array, vtkIdType count)
  {
    if (!shadelab::allocateTuples(array, count))
    {
      std::ostringstream message;
      message << "not enough memory for the array '" << array->GetName() << "' ("
              << static_cast<double>(count) * array->GetNumberOfComponents() * sizeof(Value) / 1e6
              << " MB): request fewer arrays, or float32";
      throw std::runtime_error(message.str());
    }
  }
};

/// Told the share of the points done after each block of the shading; may throw
/// shadelab::RunAborted to stop it.
using ProgressReport = std::function<void(double)>;

/// Runs the kernel over all points in a vtkSMPTools loop, for any real point and normal
/// array types (dispatched once, so the loop reads raw memory).
template <typename T>
struct ShadeAllPoints
{
  const shadelab::ShadingKernel<T>& kernel;
  const ProgressReport* progress;

  template <typename PointArray, typename NormalArray>
  void operator()(PointArray* points, NormalArray* normals) const
  {
    const auto pointRange = vtk::DataArrayTupleRange<3>(points);
    const auto normalRange = vtk::DataArrayTupleRange<3>(normals);
    const vtkIdType count = pointRange.size();
    // Blocks of the SMP loop, so progress can be reported between them: tenths of a large
    // mesh, hundredths where area lights or environment maps make every vertex slow.
    const vtkIdType block = kernel.hasDistributedLights() ? std::max<vtkIdType>(count / 100, 1024)
                                                          : std::max<vtkIdType>(count / 10, 100000);
    for (vtkIdType first = 0; first < count; first += block)
    {
      const vtkIdType last = std::min(count, first + block);
      vtkSMPTools::For(first, last,
        [&](vtkIdType begin, vtkIdType end)
        {
          shadelab::shadeRange(kernel, static_cast<std::size_t>(begin), static_cast<std::size_t>(end),
            [&](std::size_t i, shadelab::VertexBlock<T>& block, std::size_t k)
            {
              const auto p = pointRange[i];
              const auto n = normalRange[i];
              block.set(k, shadelab::Vec3<T>(T(p[0]), T(p[1]), T(p[2])),
                shadelab::Vec3<T>(T(n[0]), T(n[1]), T(n[2])));
            });
        });
      if (progress)
      {
        (*progress)(static_cast<double>(last) / count);
      }
    }
  }
};

/// Per scene light (empty for those not drawn to a target), 1 at each vertex that stopped at the
/// maximum short of its target.
using ShortOfTarget = std::vector<std::vector<std::uint8_t>>;

/// The requested arrays, shaded in precision T. progress (or nullptr) is told how far it is;
/// shortOfTarget (or nullptr) receives the vertices that stopped short of their targets, and
/// standardError and samplesDrawn (or nullptr), where they are sized for every point, each
/// one's sampled standard error and count of samples (shadelab::ShadingOutputs').
template <typename T>
std::vector<vtkSmartPointer<vtkDataArray>> shade(const shadelab::Scene& scene,
  const shadelab::ArrayRequest& request, const std::vector<shadelab::LightMethod>& methods,
  const std::string& prefix, vtkDataArray* points, vtkDataArray* normals, const shadelab::ShadingInputs& inputs,
  const ProgressReport* progress, ShortOfTarget* shortOfTarget = nullptr, std::vector<double>* standardError = nullptr,
  std::vector<std::uint32_t>* samplesDrawn = nullptr)
{
  const auto count = static_cast<std::size_t>(points->GetNumberOfTuples());
  OutputArrays<T> arrays(scene, request, prefix, points->GetNumberOfTuples());
  if (standardError && standardError->size() == count)
  {
    arrays.outputs.sampledStandardError = standardError->data();
  }
  if (samplesDrawn && samplesDrawn->size() == count)
  {
    arrays.outputs.samplesDrawn = samplesDrawn->data();
  }
  if (shortOfTarget)
  {
    shortOfTarget->assign(scene.lights.size(), {});
    arrays.outputs.shortOfTarget.assign(scene.lights.size(), nullptr);
    for (std::size_t l = 0; l < methods.size(); ++l)
    {
      if (methods[l].targets.any())
      {
        (*shortOfTarget)[l].resize(static_cast<std::size_t>(points->GetNumberOfTuples()));
        arrays.outputs.shortOfTarget[l] = (*shortOfTarget)[l].data();
      }
    }
  }
  const shadelab::ShadingKernel<T> kernel(scene, arrays.outputs, methods, inputs);
  ShadeAllPoints<T> worker{ kernel, progress };
  using Reals = vtkArrayDispatch::Reals;
  if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(points, normals, worker))
  {
    worker(points, normals); // other value types, through the generic vtkDataArray API
  }

  return arrays.arrays;
}

/// How many points of a mesh (or piece) are shaded in both precisions to measure what float32
/// rounds: evenly spaced, about this many.
constexpr vtkIdType roundingSampleSize = 16384;

/// The k for taking every k-th of `count` points by id so as to keep at most `most` of them
/// (and more than most / 2): 1 where count is at most `most`.
vtkIdType everyKth(vtkIdType count, vtkIdType most)
{
  return std::max<vtkIdType>(1, (count + most - 1) / most);
}

/// Where a rounding can put a local light on the other side of a vertex's horizon, and switch
/// its terms on or off (a whole highlight, at a grazing light that the viewer sees mirrored):
/// |n.s| below this. float32 rounds n.s by about 1e-7 for a light as far from the mesh as the
/// mesh is large; the band leaves a thousandfold margin and holds few vertices (every vertex
/// of a plane under a grazing light, which are then all measured).
constexpr double horizonBand = 1e-4;

/// Where a pow approximation errs on a light's lobe by at least this share of its largest error
/// over [0, 1]: the few vertices of a large mesh whose highlight meets the method's worst x,
/// which an evenly spaced sample may pass over.
constexpr double powErrorBand = 0.9;

/// Why a point is to be measured besides the evenly spaced ones (pointsToMeasure).
enum PointToMeasure : unsigned char
{
  AtAHorizon = 1,
  AtAPowMethodsWorst = 2,
};

/// Which points the sample must hold besides the evenly spaced ones (bands of their own
/// geometry, so the same points whatever the pieces): those whose normal is within horizonBand
/// of a local light's horizon, and those where a pow approximation errs on a local light's lobe
/// by at least powErrorBand of its largest.
std::vector<unsigned char> pointsToMeasure(const shadelab::Scene& scene, vtkDataArray* points, vtkDataArray* normals)
{
  std::vector<shadelab::LocalEvaluation> lights;
  shadelab::EvaluationContext context;
  context.lineOfSight = scene.viewer.lineOfSight();
  for (const shadelab::NamedLight& light : scene.lights)
  {
    if (!shadelab::isDistributed(light.source)) // (a map's preparation would project it)
    {
      const shadelab::LightEvaluation evaluation = shadelab::prepareEvaluation(light.source, context);
      if (const auto* local = std::get_if<shadelab::LocalEvaluation>(&evaluation))
      {
        lights.push_back(*local);
      }
    }
  }
  const double eta = scene.material.shininess;
  // The lobe's cosine x: the lobe at eta 1.
  const shadelab::LobeModel cosineOfLobe{ shadelab::hasSpecularTerm(scene) ? shadelab::evaluatedSpecularModel(scene)
                                                                            : shadelab::SpecularModel::None,
    1.0 };
  const bool twoSided = shadelab::shadesBothSides(scene);
  const bool measuresPow = cosineOfLobe.wanted() && eta > 0;
  // Per method, its error on x^eta at x, its largest, and the least x where it reaches the
  // band (on a grid of 4096, less a step; 0 where the grid misses it): below that no point
  // needs the error worked out.
  auto powErrorAt = [eta](int m, double x)
  {
    double error = 0;
    shadelab::withPowMethod(shadelab::approximatePowMethods[m], eta, [&](auto power) { error = std::abs(power(x) - std::pow(x, eta)); });
    return error;
  };
  double largestPowError[2] = { 0, 0 }, leastX[2] = { 2, 2 };
  for (int m = 0; m < 2 && measuresPow; ++m)
  {
    largestPowError[m] = shadelab::largestPowError<double>(shadelab::approximatePowMethods[m], eta);
    constexpr int steps = 4096;
    for (int k = 0; k <= steps && leastX[m] > 1; ++k)
    {
      if (powErrorAt(m, k / double(steps)) >= powErrorBand * largestPowError[m])
      {
        leastX[m] = (k - 1) / double(steps);
      }
    }
    leastX[m] = leastX[m] > 1 ? 0.0 : leastX[m];
  }
  const vtkIdType count = points->GetNumberOfTuples();
  std::vector<unsigned char> measured(static_cast<std::size_t>(count), 0);
  // The coordinates and normals in their own memory (float or double), read without a call each.
  shadelab::visitPackedPoints(points, [&](auto pointAt) { shadelab::visitPackedPoints(normals, [&](auto normalAt) {
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const glm::dvec3 normal = normalAt(i);
        if (!shadelab::isFinite(normal) || normal == glm::dvec3(0.0))
        {
          continue; // shaded with ambient light only
        }
        const glm::dvec3 position = pointAt(i);
        const glm::dvec3 unit = shadelab::unitVector(normal);
        const glm::dvec3 toViewer = scene.viewer.directionFrom(position);
        for (const shadelab::LocalEvaluation& light : lights)
        {
          const glm::dvec3 s = shadelab::towardLight(light, position).toLight;
          const double cosine = glm::dot(unit, s);
          unsigned char measure = std::abs(cosine) < horizonBand ? AtAHorizon : 0;
          // The lobe's cosine x on the side the kernel shades.
          const glm::dvec3 shaded = twoSided && glm::dot(unit, toViewer) < 0 ? -unit : unit;
          if (measuresPow && glm::dot(shaded, s) > 0)
          {
            const double x = cosineOfLobe(shaded, s, toViewer);
            for (int m = 0; m < 2; ++m)
            {
              if (x >= leastX[m] && powErrorAt(m, x) >= powErrorBand * largestPowError[m])
              {
                measure |= AtAPowMethodsWorst;
              }
            }
          }
          measured[static_cast<std::size_t>(i)] |= measure;
        }
      }
    });
  }); });
  return measured;
}

/// Per scene light, the least distance from it to any of the points, for the lights with a
/// position (+infinity for the others, and where `points` is nullptr: a piece without any). On a split mesh
/// (processes), the least over every piece: a collective call.
std::vector<double> nearestPointDistances(
  const shadelab::Scene& scene, vtkDataArray* points, vtkMultiProcessController* processes)
{
  const std::size_t lightCount = scene.lights.size();
  // Each thread's least squared distances; a minimum is the same in any order, so on any
  // thread count.
  vtkSMPThreadLocal<std::vector<double>> nearestSquared;
  if (points)
  {
    shadelab::visitPackedPoints(points, [&](auto pointAt) {
    vtkSMPTools::For(0, points->GetNumberOfTuples(),
      [&](vtkIdType begin, vtkIdType end)
      {
        std::vector<double>& least = nearestSquared.Local();
        least.resize(lightCount, std::numeric_limits<double>::infinity());
        for (std::size_t l = 0; l < lightCount; ++l)
        {
          if (const glm::dvec3* light = shadelab::positionOf(scene.lights[l].source))
          {
            for (vtkIdType i = begin; i < end; ++i)
            {
              const glm::dvec3 offset = pointAt(i) - *light;
              least[l] = std::min(least[l], glm::dot(offset, offset));
            }
          }
        }
      });
    });
  }
  std::vector<double> nearest(lightCount, std::numeric_limits<double>::infinity());
  for (const std::vector<double>& least : nearestSquared)
  {
    for (std::size_t l = 0; l < least.size(); ++l)
    {
      nearest[l] = std::min(nearest[l], std::sqrt(least[l]));
    }
  }
  if (processes && lightCount > 0)
  {
    std::vector<double> everywhere(lightCount);
    processes->AllReduce(nearest.data(), everywhere.data(), static_cast<vtkIdType>(lightCount), vtkCommunicator::MIN_OP);
    nearest = everywhere;
  }
  return nearest;
}

/// The largest difference between two shadings of the same arrays (float32's and float64's),
/// over every component of the real-valued arrays (the flags are bits, not values).
double largestDifference(
  const std::vector<vtkSmartPointer<vtkDataArray>>& a, const std::vector<vtkSmartPointer<vtkDataArray>>& b)
{
  double largest = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (!a[k]->IsA("vtkUnsignedCharArray"))
    {
      const int components = a[k]->GetNumberOfComponents();
      for (vtkIdType v = 0; v < a[k]->GetNumberOfValues(); ++v)
      {
        largest = std::max(largest,
          std::abs(a[k]->GetComponent(v / components, int(v % components)) - b[k]->GetComponent(v / components, int(v % components))));
      }
    }
  }
  return largest;
}
}

vtkLocalReflectanceFilter::vtkLocalReflectanceFilter()
  : Controller(vtkMultiProcessController::GetGlobalController())
{
  // The steps run over this filter's processes only on a split mesh (ShadeMesh sets them).
  this->NormalsStep->SetController(nullptr);
  this->VisibilityStep->SetController(nullptr);
  this->AvailableArrays->AddObserver(vtkCommand::ModifiedEvent, this, &vtkLocalReflectanceFilter::AvailableArraysChanged);
  this->NormalsStep->AddObserver(vtkCommand::ProgressEvent, this, &vtkLocalReflectanceFilter::ForwardStepProgress);
  this->VisibilityStep->AddObserver(vtkCommand::ProgressEvent, this, &vtkLocalReflectanceFilter::ForwardStepProgress);
}

void vtkLocalReflectanceFilter::ForwardStepProgress(vtkObject* step, unsigned long, void* done)
{
  if (this->Progress.span > 0)
  {
    this->UpdateProgress(this->Progress.start + this->Progress.span * *static_cast<double*>(done));
  }
  if (this->Stoppable && this->GetAbortExecute())
  {
    static_cast<vtkAlgorithm*>(step)->SetAbortExecute(1);
  }
}

void vtkLocalReflectanceFilter::ReportProgress(double done)
{
  this->UpdateProgress(this->Progress.start + this->Progress.span * done);
  this->StopIfAborted();
}

void vtkLocalReflectanceFilter::StopIfAborted()
{
  if (this->Stoppable && this->GetAbortExecute())
  {
    throw shadelab::RunAborted();
  }
}

void vtkLocalReflectanceFilter::StartStep(double start, double span)
{
  this->Progress = { start, span };
  this->StopIfAborted();
}

void vtkLocalReflectanceFilter::AvailableArraysChanged()
{
  if (!this->FillingAvailableArrays)
  {
    this->Modified();
  }
}

int vtkLocalReflectanceFilter::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  vtkDataArraySelection* list = this->AvailableArrays;
  // An empty list changed is no choice: ParaView sets the list it has before the first fill.
  const bool chosenInList = list->GetNumberOfArrays() > 0 && list->GetMTime() > this->AvailableArraysFilledAt;
  // Read once for the update: RequestData shades with it, or reports why it could not be read.
  this->SceneOfThisUpdate = this->ReadScene();
  if (!this->SceneOfThisUpdate.scene)
  {
    return 1; // RequestData reports it
  }
  const shadelab::Scene& scene = *this->SceneOfThisUpdate.scene;
  std::vector<std::string> available;
  for (const auto& array : shadelab::availableArrays(scene))
  {
    available.push_back(array.name);
  }
  auto isAvailable = [&](const std::string& name)
  { return std::find(available.begin(), available.end(), name) != available.end(); };
  if (chosenInList)
  {
    // The names enabled in the list become the selection.
    this->ArraySelection.clear();
    for (int i = 0; i < list->GetNumberOfArrays(); ++i)
    {
      if (list->GetArraySetting(i))
      {
        this->ArraySelection.push_back(list->GetArrayName(i));
      }
    }
    this->SelectionFromList = true;
  }
  if (this->SelectionFromList)
  {
    // Names from the list, of another scene's arrays, that this scene lacks.
    this->ArraySelection.erase(std::remove_if(this->ArraySelection.begin(), this->ArraySelection.end(),
      [&](const std::string& name) { return !isAvailable(name); }), this->ArraySelection.end());
  }
  std::vector<std::string> selected;
  try
  {
    selected = shadelab::selectedArrayNames(scene, this->ArraySelection);
  }
  catch (const std::invalid_argument&)
  {
    // RequestData reports it; the list shows nothing ticked.
  }
  this->FillingAvailableArrays = true;
  list->RemoveAllArrays();
  for (const std::string& name : available)
  {
    list->AddArray(name.c_str(), std::find(selected.begin(), selected.end(), name) != selected.end());
  }
  this->FillingAvailableArrays = false;
  this->AvailableArraysFilledAt = list->GetMTime();
  return 1;
}
vtkLocalReflectanceFilter::~vtkLocalReflectanceFilter() = default;

void vtkLocalReflectanceFilter::SetLightMethods(const std::vector<shadelab::LightMethod>& methods)
{
  this->LightMethods = methods;
  this->Modified();
}

void vtkLocalReflectanceFilter::SetArraySelection(const std::vector<std::string>& selection)
{
  this->ArraySelection = selection;
  this->SelectionSetHere();
}

void vtkLocalReflectanceFilter::ClearArraySelection()
{
  if (!this->ArraySelection.empty())
  {
    this->ArraySelection.clear();
    this->SelectionSetHere();
  }
}

void vtkLocalReflectanceFilter::AddToArraySelection(const std::string& entry)
{
  this->ArraySelection.push_back(entry);
  this->SelectionSetHere();
}

void vtkLocalReflectanceFilter::SelectionSetHere()
{
  // Set after any choice in AvailableArrays, so it is the one used.
  this->AvailableArraysFilledAt = this->AvailableArrays->GetMTime();
  this->SelectionFromList = false;
  this->Modified();
}

std::string vtkLocalReflectanceFilter::GetArraySelectionEntry(int i) const
{
  return i >= 0 && i < this->GetNumberOfArraySelectionEntries() ? this->ArraySelection[i] : std::string();
}

namespace
{
/// What makes the mesh's structure unusable (its coordinates are checked against the precision
/// apart), or "" when there is nothing.
std::string meshProblem(vtkPolyData* input)
{
  const vtkIdType pointCount = input->GetNumberOfPoints();
  std::ostringstream problem;
  if (input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    problem << "the mesh has no polygons (" << input->GetNumberOfCells()
            << " vertex or line cells): surface shading needs a surface";
    return problem.str();
  }
  const std::string cells = shadelab::cellProblem(input);
  if (!cells.empty())
  {
    return cells;
  }
  vtkDataArray* normals = input->GetPointData()->GetNormals();
  if (normals && (normals->GetNumberOfComponents() != 3 || normals->GetNumberOfTuples() != pointCount))
  {
    problem << "the point normals '" << (normals->GetName() ? normals->GetName() : "") << "' have "
            << normals->GetNumberOfTuples() << " tuples of " << normals->GetNumberOfComponents()
            << " components: there must be one 3-component normal per point (" << pointCount << ")";
    return problem.str();
  }
  return "";
}

/// The first of names that the input already has as a point array, or "".
std::string takenName(vtkPolyData* input, const std::vector<std::string>& names)
{
  for (const std::string& name : names)
  {
    if (input->GetPointData()->HasArray(name.c_str()))
    {
      return name;
    }
  }
  return "";
}

/// The spectral mode's arrays besides the kernel's linear sRGB (docs/formulas.md section 22):
/// each RGB total's XYZ twin ("<total>_xyz", by the inverse of the sRGB matrix), and
/// "total_rgb_difference", the spectral total less the RGB model's (rgbTotal).
void addSpectralArrays(std::vector<vtkSmartPointer<vtkDataArray>>& arrays, vtkDataArray* rgbTotal, const std::string& prefix)
{
  const glm::dmat3 toXyz = glm::inverse(shadelab::xyzToLinearSrgb());
  // An array of the total's type and length, 3 components, to fill.
  auto emptyLike = [](vtkDataArray* total, const std::string& name)
  {
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(total->NewInstance());
    array->SetName(name.c_str());
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(total->GetNumberOfTuples());
    return array;
  };
  std::vector<vtkSmartPointer<vtkDataArray>> added;
  for (const vtkSmartPointer<vtkDataArray>& array : arrays)
  {
    for (int t = 0; t < shadelab::TotalTermCount; ++t)
    {
      const std::string name = shadelab::totalArrayName(prefix, shadelab::TotalTerm(t));
      if (name != array->GetName())
      {
        continue;
      }
      const vtkSmartPointer<vtkDataArray> xyz = emptyLike(array, shadelab::totalXyzArrayName(prefix, shadelab::TotalTerm(t)));
      for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
      {
        double rgb[3];
        array->GetTuple(i, rgb);
        const glm::dvec3 value = toXyz * glm::dvec3(rgb[0], rgb[1], rgb[2]);
        xyz->SetTuple3(i, value.x, value.y, value.z);
      }
      added.push_back(xyz);
      if (t == int(shadelab::TotalTerm::Total))
      {
        const vtkSmartPointer<vtkDataArray> difference = emptyLike(array, shadelab::rgbDifferenceArrayName(prefix));
        for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            difference->SetComponent(i, c, array->GetComponent(i, c) - rgbTotal->GetComponent(i, c));
          }
        }
        added.push_back(difference);
      }
    }
  }
  arrays.insert(arrays.end(), added.begin(), added.end());
}

/// The material_clamped array: per vertex, bit c where coefficient c's value was clamped.
vtkSmartPointer<vtkDataArray> clampedMaterialArray(const std::vector<std::uint8_t>& clamped, const std::string& prefix)
{
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName(shadelab::materialClampedArrayName(prefix).c_str());
  array->SetNumberOfTuples(static_cast<vtkIdType>(clamped.size()));
  std::copy(clamped.begin(), clamped.end(), array->GetPointer(0));
  return array;
}

/// Points the kernel's inputs at the rays' arrays in `seen`: each shadowed light's visibility,
/// the ambient occlusion and the flags. Returns the occlusion arrays the request asks for, to
/// be output as they are (float32 whatever the precision: estimates, not exact terms).
std::vector<vtkSmartPointer<vtkDataArray>> useVisibility(vtkPolyData* seen, const shadelab::Scene& scene,
  const shadelab::ArrayRequest& request, const std::string& prefix, shadelab::ShadingInputs& inputs)
{
  vtkPointData* data = seen->GetPointData();
  auto floats = [&](const std::string& name) { return vtkFloatArray::SafeDownCast(data->GetArray(name.c_str())); };
  auto hiddenSamplesOf = [&](const std::string& light) -> const std::uint64_t*
  {
    static_assert(sizeof(vtkTypeUInt64) == sizeof(std::uint64_t), "the hidden samples' words are 64 bits");
    auto* words = vtkTypeUInt64Array::SafeDownCast(data->GetArray(shadelab::hiddenSamplesArrayName(prefix, light).c_str()));
    return words ? reinterpret_cast<const std::uint64_t*>(words->GetPointer(0)) : nullptr;
  };
  auto shadowedTermsOf = [&](const std::string& light) -> const double*
  {
    auto* terms = vtkDoubleArray::SafeDownCast(data->GetArray(shadelab::shadowedTermsArrayName(prefix, light).c_str()));
    return terms ? terms->GetPointer(0) : nullptr;
  };
  for (const shadelab::NamedLight& light : scene.lights)
  {
    // A local light's visibility multiplies its terms; an area light's or a map's samples are
    // weighted by the bits of those the mesh hides, or, drawn to a target, the visibility step
    // estimated it.
    const bool distributed = light.shadows && shadelab::isDistributed(light.source);
    const bool local = light.shadows && !distributed;
    inputs.lightVisibility.push_back(
      local ? floats(shadelab::lightArrayName(prefix, light.name, shadelab::LightTerm::Visibility))->GetPointer(0) : nullptr);
    inputs.lightHiddenSamples.push_back(distributed ? hiddenSamplesOf(light.name) : nullptr);
    inputs.lightShadowedTerms.push_back(distributed ? shadowedTermsOf(light.name) : nullptr);
  }
  std::vector<vtkSmartPointer<vtkDataArray>> requested;
  if (scene.ambientOcclusion)
  {
    inputs.ambientOcclusion = floats(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::AmbientOcclusion))->GetPointer(0);
    inputs.ambientOcclusionStdError =
      floats(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::AmbientOcclusionStdError))->GetPointer(0);
  }
  for (int t = 0; t < shadelab::OcclusionTermCount; ++t)
  {
    if (request.occlusion[t])
    {
      requested.push_back(data->GetArray(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm(t)).c_str()));
    }
  }
  inputs.flags =
    vtkUnsignedCharArray::SafeDownCast(data->GetArray(shadelab::visibilityFlagsArrayName(prefix).c_str()))->GetPointer(0);
  return requested;
}

}

int vtkLocalReflectanceFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return shadelab::runWithThreads(this->NumberOfThreads, [&] { return this->Shade(inputVector, outputVector); });
}

int vtkLocalReflectanceFilter::Shade(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ForgetSceneProblem();
  this->NormalsReport.clear();
  this->VisibilityReport.clear();
  // A split mesh's processes must all take part in its exchanges: only a whole mesh stops.
  this->Stoppable = !shadelab::isPieceOfSplitMesh(this->Controller, input);
  if (this->Stoppable)
  {
    try
    {
      return this->ShadeMesh(input, output, nullptr);
    }
    catch (const shadelab::RunAborted&) // an empty output, and no error
    {
      output->Initialize();
      this->SamplingReport.clear();
      // Not generated, so that the next update runs again, and the steps with it.
      outputVector->GetInformationObject(0)->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
      this->NormalsStep->Modified();
      this->VisibilityStep->Modified();
      return 1;
    }
  }
  const shadelab::PieceLayout layout = shadelab::pieceLayout(this->Controller, input);
  if (!layout.problem.empty())
  {
    vtkErrorMacro(<< layout.problem); // on every process alike
    return 0;
  }
  // Pieces not put together: one process holds the whole mesh, and shades it alone.
  const bool shaded = this->ShadeMesh(input, output, layout.putTogether ? &layout : nullptr) == 1;
  return shadelab::agreedOutcome(this->Controller, this, output, shaded);
}

namespace
{
/// The share of a run's progress that preparing the normals takes.
constexpr double normalsShare = 0.05;

/// The share the rays take: most of the run where each vertex casts many (ambient occlusion, an
/// area light's or a map's shadows), a quarter where it casts one per light, none without rays.
double raysShareOf(const shadelab::Scene& scene)
{
  if (!scene.needsVisibility())
  {
    return 0;
  }
  const bool manyRays = scene.ambientOcclusion ||
    std::any_of(scene.lights.begin(), scene.lights.end(),
      [](const shadelab::NamedLight& light) { return light.shadows && shadelab::isDistributed(light.source); });
  return manyRays ? 0.75 : 0.25;
}

/// A cost forecast's pilot: enough vertices for their mean cost to a few percent, a small share
/// of a large mesh's; a mesh under pilotMeshLeast is shaded without one (the run is short).
constexpr vtkIdType pilotLeast = 256, pilotMost = 2048, pilotMeshLeast = 4 * pilotLeast;

/// How many of the pilot's vertices stopped at a maximum short of a target: a light's, or the
/// ambient occlusion's (its array in `seen`, where there is one).
std::size_t shortOfTargetCount(const ShortOfTarget& lights, vtkPolyData* seen, const std::string& prefix, std::size_t count)
{
  vtkDataArray* occlusion = seen ? seen->GetPointData()->GetArray(
    shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::ShortOfTarget).c_str()) : nullptr;
  std::size_t stopped = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    bool marked = occlusion && occlusion->GetComponent(static_cast<vtkIdType>(i), 0) != 0;
    for (const std::vector<std::uint8_t>& marks : lights)
    {
      marked = marked || (!marks.empty() && marks[i]);
    }
    stopped += marked ? 1 : 0;
  }
  return stopped;
}

/// The ambient occlusion's rays from the pilot's points: its rays array where drawn to a
/// target, else its fixed count each.
double occlusionRayCount(const shadelab::Scene& scene, vtkPolyData* seen, const std::string& prefix, std::size_t count)
{
  if (!scene.ambientOcclusion)
  {
    return 0;
  }
  vtkDataArray* rays = seen->GetPointData()->GetArray(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::Rays).c_str());
  double sum = rays ? 0 : double(scene.ambientOcclusion->sampling.samples) * double(count);
  for (vtkIdType i = 0; rays && i < rays->GetNumberOfTuples(); ++i)
  {
    sum += rays->GetComponent(i, 0);
  }
  return sum;
}
}

/// What the checks before shading settle, for the steps that write.
struct vtkLocalReflectanceFilter::ShadingPlan
{
  shadelab::MeshExtent extent; // the whole mesh's, on a split mesh
  shadelab::Scene scene;       // placed on the mesh
  shadelab::ArrayRequest request;
  std::vector<shadelab::LightMethod> methods;
  shadelab::Precision precision = shadelab::Precision::Float32;
  bool float32Fits = true; // the mesh's coordinates and the scene's values fit float32
  shadelab::MeshMeasurements measured; // under a tolerance, for its plan's bounds
};

int vtkLocalReflectanceFilter::ShadeMesh(vtkPolyData* input, vtkPolyData* output, const shadelab::PieceLayout* split)
{
  // A piece without points still takes part in its steps' exchanges, and shades nothing.
  const bool empty = input->GetNumberOfPoints() == 0;
  if (empty && !split)
  {
    output->ShallowCopy(input); // nothing in, nothing out, and no error: VTK's convention
    return 1;
  }
  vtkMultiProcessController* processes = split ? this->Controller.Get() : nullptr;
  this->NormalsStep->SetController(processes);
  this->VisibilityStep->SetController(processes);
  std::optional<ShadingPlan> plan = this->PlanShading(input, processes, split != nullptr);
  if (!plan || !this->ReadMaterialArrays(input, processes, split, *plan))
  {
    return 0;
  }

  output->ShallowCopy(input);
  // Progress: the normals, then the rays where there are any, then the shading.
  const double raysShare = raysShareOf(plan->scene);
  this->StartStep(0, normalsShare);
  vtkDataArray* shadingNormals = this->PrepareNormals(input, output, split != nullptr);
  // The step failed (on a split mesh, on every process, having said why). An empty piece has
  // none where the others kept their own.
  const bool prepared = shadingNormals || empty;
  if (split ? !shadelab::everyProcessHolds(processes, prepared) : !prepared)
  {
    output->Initialize();
    vtkErrorMacro("preparing the normals failed (see the error above)");
    return 0;
  }
  // Under a tolerance, what float32 rounds and what the pow approximations err are measured on
  // a sample of the points, with the normals they are shaded with, and the methods chosen
  // again with them (the same outcome on every process, which all measure the same).
  if (this->Tolerance > 0)
  {
    this->MeasureOnSample(
      this->SamplePoints(input, shadingNormals, *plan, processes, split ? &split->pieceIds : nullptr), *plan, processes);
  }
  if (this->Tolerance > 0 && !this->ChooseMethods(*plan, false))
  {
    output->Initialize();
    return 0;
  }

  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  SamplingOutcome sampling;
  // Where the plan samples (the same on every process), each vertex's standard error is kept
  // for the estimate after sampling.
  const bool estimatesSampling = this->Tolerance > 0 && this->MethodPlan->samplingError > 0;
  std::string failure;
  try
  {
    sampling.standardError.resize(estimatesSampling ? static_cast<std::size_t>(input->GetNumberOfPoints()) : 0);
    if (this->Tolerance > 0)
    {
      this->StartStep(normalsShare, 0); // a forecast's pilot moves no progress bar
      this->MethodPlan->forecast =
        estimatesSampling ? this->ForecastCost(input, shadingNormals, *plan, split != nullptr) : std::nullopt;
      sampling.samplesDrawn.resize(this->MethodPlan->forecast ? static_cast<std::size_t>(input->GetNumberOfPoints()) : 0);
      this->InvokeEvent(MethodsChosenEvent);
    }
    this->StartStep(normalsShare, raysShare);
    vtkPolyData* seen = this->PrepareVisibility(input, shadingNormals, *plan, split != nullptr);
    this->StartStep(normalsShare + raysShare, 1 - normalsShare - raysShare);
    if (!empty)
    {
      arrays = this->ShadedArrays(input, shadingNormals, seen, *plan, split, sampling);
    }
    if (this->Tolerance > 0 && this->MethodPlan->forecast) // what the run drew, against it
    {
      this->MethodPlan->forecast->drawn = shadelab::SampleCounts{
        std::accumulate(sampling.samplesDrawn.begin(), sampling.samplesDrawn.end(), 0.0),
        occlusionRayCount(plan->scene, seen, this->ArrayPrefix, sampling.samplesDrawn.size()) };
    }
    // The rays' arrays have been used (those asked for are in `arrays`): not kept until the next run.
    this->VisibilityStep->GetOutput()->Initialize();
  }
  catch (const shadelab::RunAborted&)
  {
    throw; // for Shade to leave an empty output
  }
  catch (const std::exception& error) // an array, or anything else, that could not be allocated
  {
    failure = error.what();
  }
  // Counted over every piece (a collective call, which an empty or failed piece joins too).
  this->SamplingReport = this->ShortOfTargetReport(*plan, sampling.shortOfTarget, split);
  if (estimatesSampling)
  {
    try // collective too: a failed piece takes part with no values
    {
      this->MethodPlan->estimatedSamplingError =
        this->EstimatedSamplingError(failure.empty() ? std::move(sampling.standardError) : std::vector<double>(), split);
    }
    catch (const std::exception& error) // no memory to gather the values
    {
      failure = failure.empty() ? error.what() : failure;
    }
  }
  if (!failure.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< failure);
    return 0;
  }
  if (empty)
  {
    return 1;
  }
  for (const auto& array : arrays)
  {
    output->GetPointData()->AddArray(array);
  }
  this->AddFieldNotes(output);
  return 1;
}

std::optional<vtkLocalReflectanceFilter::ShadingPlan> vtkLocalReflectanceFilter::PlanShading(
  vtkPolyData* input, vtkMultiProcessController* processes, bool split)
{
  // Everything is checked before anything is written. Until the steps run, what differs
  // between pieces is agreed, so that every process stops alike; the rest (the settings, the
  // scene, the extent) is the same on every process.
  if (!this->CheckTolerance())
  {
    return std::nullopt;
  }
  ShadingPlan plan;
  // Under a tolerance the precision is chosen with the methods, and float64 is checked first
  // as the precision that accepts the most scenes and meshes.
  plan.precision = this->OutputPrecision == DOUBLE_PRECISION || this->Tolerance > 0 ? shadelab::Precision::Float64
                                                                                   : shadelab::Precision::Float32;
  if (!this->CheckMesh(input, processes, split, plan) || !this->PlaceScene(input, processes, split, plan) ||
    !this->CheckLightMethods(plan.scene) || !this->ChooseArraysAndMethods(plan) ||
    !this->CheckArrayNamesFree(input, plan.scene, processes, split))
  {
    return std::nullopt;
  }
  return plan;
}

bool vtkLocalReflectanceFilter::MaterialSource::operator==(const MaterialSource& other) const
{
  return sources.coefficients == other.sources.coefficients && model == other.model && storage == other.storage &&
    points == other.points && arrays == other.arrays;
}

bool vtkLocalReflectanceFilter::ReadMaterialArrays(
  vtkPolyData* input, vtkMultiProcessController* processes, const shadelab::PieceLayout* split, ShadingPlan& plan)
{
  if (!plan.scene.material.arrays.any())
  {
    return true;
  }
  // Stored in float32 where the run is float32 for sure (no tolerance to choose float64), which
  // halves the memory; in float64 otherwise.
  const shadelab::Precision storage = this->Tolerance == 0 && this->OutputPrecision == SINGLE_PRECISION
    ? shadelab::Precision::Float32
    : shadelab::Precision::Float64;
  MaterialSource source{ plan.scene.material.arrays, plan.scene.model, storage, input->GetNumberOfPoints(), {} };
  for (const auto& coefficient : source.sources.coefficients)
  {
    vtkDataArray* array = coefficient ? input->GetPointData()->GetArray(coefficient->array.c_str()) : nullptr;
    source.arrays.emplace_back(array, array ? array->GetMTime() : 0);
  }
  const bool unchanged = this->VertexMaterialSource && *this->VertexMaterialSource == source;
  if (!(split ? shadelab::everyProcessHolds(processes, unchanged) : unchanged) &&
    !this->DecodeMaterialArrays(input, processes, split, plan, source))
  {
    return false;
  }
  if (plan.scene.material.arrays[shadelab::MaterialCoefficient::Shininess])
  {
    const double mine = this->VertexMaterial.largest(shadelab::MaterialCoefficient::Shininess);
    double everywhere = mine;
    if (split)
    {
      processes->AllReduce(&mine, &everywhere, 1, vtkCommunicator::MAX_OP);
    }
    plan.measured.largestShininess = everywhere;
  }
  return true;
}

bool vtkLocalReflectanceFilter::DecodeMaterialArrays(vtkPolyData* input, vtkMultiProcessController* processes,
  const shadelab::PieceLayout* split, const ShadingPlan& plan, const MaterialSource& source)
{
  this->VertexMaterialSource.reset();
  shadelab::MaterialReading reading =
    shadelab::readVertexMaterial(input, plan.scene, source.storage, processes, split ? &split->pieceIds : nullptr);
  this->VertexMaterial = std::move(reading.material);
  const std::string problem = split ? shadelab::firstText(processes, reading.problem) : reading.problem;
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  this->VertexMaterialSource = source;
  return true;
}

bool vtkLocalReflectanceFilter::CheckTolerance()
{
  if (!(this->Tolerance >= 0 && std::isfinite(this->Tolerance)))
  {
    vtkErrorMacro("the tolerance is " << this->Tolerance
                                      << ": it must be a finite number >= 0 (0: exact methods)");
    return false;
  }
  return true;
}

bool vtkLocalReflectanceFilter::CheckMesh(
  vtkPolyData* input, vtkMultiProcessController* processes, bool split, ShadingPlan& plan)
{
  // A piece may lack polygons where others have them (a piece of lines, or of nothing).
  const bool polygons = input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0;
  std::string problem = !split || polygons ? meshProblem(input) : "";
  if (split)
  {
    problem = shadelab::firstText(processes, problem);
    if (problem.empty() && shadelab::everyProcessHolds(processes, !polygons))
    {
      problem = meshProblem(input); // no piece has a polygon
    }
  }
  if (problem.empty())
  {
    plan.extent = split ? shadelab::wholeMeshExtent(processes, input) : shadelab::meshExtentOf(input);
    problem = shadelab::meshCoordinateProblem(plan.extent.reach, plan.precision);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  return true;
}

std::optional<shadelab::Scene> vtkLocalReflectanceFilter::SceneReadEverywhere(
  vtkMultiProcessController* processes, bool split)
{
  const std::optional<shadelab::Scene> given = this->ReportedScene(this->SceneOfThisUpdate);
  // Each process reads the scene itself: one that could not (its file missing there, say)
  // stops them all.
  if (split && !shadelab::everyProcessHolds(processes, given.has_value()))
  {
    if (given)
    {
      vtkErrorMacro("another process could not read the scene (see its error), so this one stops too");
    }
    return std::nullopt;
  }
  return given;
}

bool vtkLocalReflectanceFilter::PlaceScene(
  vtkPolyData* input, vtkMultiProcessController* processes, bool split, ShadingPlan& plan)
{
  const std::optional<shadelab::Scene> given = this->SceneReadEverywhere(processes, split);
  if (!given)
  {
    return false;
  }
  // A scene written relative to the mesh is placed on it here, and checked where it lands.
  plan.scene = shadelab::placedOnMesh(*given, plan.extent);
  if (this->ColorByArray)
  {
    if (!shadelab::isColorMapName(this->MaterialColorMap))
    {
      vtkErrorMacro("MaterialColorMap \"" << this->MaterialColorMap << "\" is not one of "
                                          << shadelab::colorMapNameList());
      return false;
    }
    shadelab::colorMaterialBy(plan.scene, this->MaterialColorArray, this->MaterialColorMap);
  }
  if (!this->SceneIsValid(shadelab::sceneProblems(plan.scene, plan.precision)))
  {
    return false;
  }
  if (this->Tolerance > 0) // one pass over the points, for bounds that are not the sphere's
  {
    plan.measured.nearestVertexDistance = nearestPointDistances(
      plan.scene, input->GetPoints() ? input->GetPoints()->GetData() : nullptr, split ? processes : nullptr);
  }
  return true;
}

bool vtkLocalReflectanceFilter::CheckLightMethods(const shadelab::Scene& scene)
{
  this->MethodPlan.reset();
  if (!this->LightMethods.empty() && this->LightMethods.size() != scene.lights.size())
  {
    vtkErrorMacro("SetLightMethods was given " << this->LightMethods.size() << " methods for " << scene.lights.size()
                                               << " lights: give one per light, or none");
    return false;
  }
  return true;
}

bool vtkLocalReflectanceFilter::ChooseArraysAndMethods(ShadingPlan& plan)
{
  plan.methods = this->LightMethods;
  try
  {
    plan.request = shadelab::selectArrays(plan.scene, this->ArraySelection);
  }
  catch (const std::invalid_argument& error)
  {
    vtkErrorMacro(<< error.what());
    return false;
  }
  plan.float32Fits = shadelab::meshCoordinateProblem(plan.extent.reach, shadelab::Precision::Float32).empty() &&
    shadelab::sceneProblems(plan.scene, shadelab::Precision::Float32).empty();
  if (this->Tolerance > 0 && !this->ChooseMethods(plan, true))
  {
    return false;
  }
  // Under a tolerance, its plan gives every "auto" its target (in the second pass at the latest).
  return this->Tolerance > 0 || this->SceneIsValid(shadelab::untargetedSamplingProblems(plan.scene, false));
}

bool vtkLocalReflectanceFilter::ChooseMethods(ShadingPlan& plan, bool roundingMeasuredLater)
{
  try
  {
    this->MethodPlan = shadelab::chooseMethods(
      plan.scene, plan.request, plan.extent, this->Tolerance, plan.float32Fits, plan.measured);
  }
  catch (const shadelab::RoundingAboveTolerance& error)
  {
    if (!roundingMeasuredLater)
    {
      vtkErrorMacro(<< error.what());
    }
    return roundingMeasuredLater;
  }
  catch (const shadelab::UnboundedSceneField& error) // the scene's problem, at its field
  {
    return this->SceneIsValid({ { error.field, error.what() } });
  }
  catch (const std::invalid_argument& error)
  {
    vtkErrorMacro(<< error.what());
    return false;
  }
  plan.precision = this->MethodPlan->precision;
  plan.methods = this->MethodPlan->methods();
  if (this->MethodPlan->occlusion)
  {
    plan.scene.ambientOcclusion->target = this->MethodPlan->occlusion->target;
  }
  return true;
}

vtkLocalReflectanceFilter::PointSample vtkLocalReflectanceFilter::SamplePoints(vtkPolyData* input,
  vtkDataArray* shadingNormals, const ShadingPlan& plan, vtkMultiProcessController* processes,
  const std::vector<vtkIdType>* pieceIds)
{
  // Points evenly spaced by their id in the whole mesh, and those where a light grazes the
  // surface: on a split mesh, the pieces' samples make up the whole mesh's, whatever the pieces.
  const vtkIdType count = input->GetNumberOfPoints();
  auto idOf = [&](vtkIdType i) { return pieceIds ? (*pieceIds)[static_cast<std::size_t>(i)] : i; };
  // Global ids number the whole mesh's points 0 to n-1.
  const vtkIdType wholeCount = processes ? shadelab::wholePointCount(processes, *pieceIds) : count;
  const vtkIdType stride = everyKth(wholeCount, roundingSampleSize);
  const std::vector<unsigned char> banded =
    count > 0 ? pointsToMeasure(plan.scene, input->GetPoints()->GetData(), shadingNormals) : std::vector<unsigned char>();
  // Every point at a horizon; of those at a pow method's worst, all of a small band (a small
  // highlight, which the evenly spaced points may miss) and about roundingSampleSize of a
  // large one, evenly spaced by id (the error is smooth along it): counted over the whole mesh,
  // so the same points whatever the pieces.
  std::vector<vtkIdType> worstIds;
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (banded[static_cast<std::size_t>(i)] & AtAPowMethodsWorst)
    {
      worstIds.push_back(idOf(i));
    }
  }
  const std::size_t worstCount = processes ? shadelab::distinctIdCount(processes, worstIds) : worstIds.size();
  const vtkIdType worstStride = everyKth(static_cast<vtkIdType>(worstCount), roundingSampleSize);
  std::vector<vtkIdType> sample;
  PointSample taken;
  for (vtkIdType i = 0; i < count; ++i)
  {
    const unsigned char why = banded.empty() ? 0 : banded[static_cast<std::size_t>(i)];
    if (idOf(i) % stride == 0 || (why & AtAHorizon) || ((why & AtAPowMethodsWorst) && idOf(i) % worstStride == 0))
    {
      sample.push_back(i);
      taken.ids.push_back(idOf(i));
    }
  }
  if (!sample.empty())
  {
    taken.points = shadelab::tuplesAt(input->GetPoints()->GetData(), sample);
    taken.normals = shadelab::tuplesAt(shadingNormals, sample);
  }
  return taken;
}

void vtkLocalReflectanceFilter::MeasureOnSample(
  const PointSample& sample, ShadingPlan& plan, vtkMultiProcessController* processes)
{
  // Every light visible and the open sky: every term that the scene can make nonzero is, and
  // rounds as it would in the shading. Each point's samples (an area light's or a map's) are
  // seeded by its id in the whole mesh, as in the shading, whatever the pieces.
  shadelab::ShadingInputs open;
  open.sampleIds = sample.ids.data();
  const shadelab::Scene& scene = plan.scene;
  auto shadeSample = [&](auto precision, const shadelab::ArrayRequest& request,
                       const std::vector<shadelab::LightMethod>& methods)
  {
    using T = decltype(precision);
    return shade<T>(scene, request, methods, "", sample.points, sample.normals, open, nullptr);
  };
  const std::vector<shadelab::LightMethod> exact(scene.lights.size());
  // What float32 rounds, all lights exact, against float64; and what each pow approximation
  // adds to each light's specular term, in float32 where it fits (its rounding included).
  std::vector<double> largest(1 + 2 * scene.lights.size(), 0.0);
  if (sample.points)
  {
    if (plan.float32Fits)
    {
      largest[0] = largestDifference(shadeSample(float(), plan.request, exact), shadeSample(double(), plan.request, exact));
    }
    // The specular arrays of the lights a pow method applies to (point, spot, distant), which
    // the shading writes in the lights' order.
    shadelab::ArrayRequest speculars;
    speculars.lights.resize(scene.lights.size());
    std::vector<std::size_t> specularLights;
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      const shadelab::LightSource& source = scene.lights[l].source;
      if (shadelab::hasSpecularTerm(scene) && !shadelab::isAmbient(source) &&
        !shadelab::isDistributed(source))
      {
        speculars.lights[l][int(shadelab::LightTerm::Specular)] = true;
        specularLights.push_back(l);
      }
    }
    const auto reference = specularLights.empty() ? decltype(shadeSample(double(), speculars, exact))()
                                                  : shadeSample(double(), speculars, exact);
    for (std::size_t m = 0; m < 2 && !specularLights.empty(); ++m)
    {
      std::vector<shadelab::LightMethod> methods(scene.lights.size());
      for (const std::size_t l : specularLights)
      {
        methods[l].pow = shadelab::approximatePowMethods[m];
      }
      const auto approximated =
        plan.float32Fits ? shadeSample(float(), speculars, methods) : shadeSample(double(), speculars, methods);
      for (std::size_t k = 0; k < specularLights.size(); ++k)
      {
        largest[1 + 2 * specularLights[k] + m] = largestDifference({ reference[k] }, { approximated[k] });
      }
    }
  }
  if (processes) // the largest over every piece, the same on every process
  {
    std::vector<double> everywhere(largest.size());
    processes->AllReduce(largest.data(), everywhere.data(), static_cast<vtkIdType>(largest.size()), vtkCommunicator::MAX_OP);
    largest = everywhere;
  }
  if (plan.float32Fits)
  {
    plan.measured.sampledFloat32Difference = largest[0];
  }
  plan.measured.sampledPowDifference.resize(scene.lights.size());
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    for (std::size_t m = 0; m < 2; ++m)
    {
      plan.measured.sampledPowDifference[l].of(shadelab::approximatePowMethods[m]) = largest[1 + 2 * l + m];
    }
  }
}

std::vector<std::string> vtkLocalReflectanceFilter::WritableArrayNames(vtkPolyData* input, const shadelab::Scene& scene) const
{
  std::vector<std::string> names;
  for (const auto& array : shadelab::availableArrays(scene, this->ArrayPrefix))
  {
    names.push_back(array.name);
  }
  if (!input->GetPointData()->GetNormals())
  {
    names.push_back(this->ComputedNormalsName());
  }
  if (scene.material.arrays.clamps())
  {
    names.push_back(shadelab::materialClampedArrayName(this->ArrayPrefix));
  }
  const std::vector<std::string> spectral = shadelab::spectralArrayNames(scene, this->ArrayPrefix);
  names.insert(names.end(), spectral.begin(), spectral.end());
  return names;
}

bool vtkLocalReflectanceFilter::CheckArrayNamesFree(
  vtkPolyData* input, const shadelab::Scene& scene, vtkMultiProcessController* processes, bool split)
{
  const std::string taken = takenName(input, this->WritableArrayNames(input, scene));
  std::string problem = taken.empty() ? "" : "the input already has a point array named '" + taken +
      "', which this filter would write: set an array prefix (shadelab shade --prefix) to keep both";
  if (split)
  {
    problem = shadelab::firstText(processes, problem);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  return true;
}

std::vector<vtkSmartPointer<vtkDataArray>> vtkLocalReflectanceFilter::ShadedArrays(vtkPolyData* input,
  vtkDataArray* shadingNormals, vtkPolyData* seen, const ShadingPlan& plan, const shadelab::PieceLayout* split,
  SamplingOutcome& sampling)
{
  shadelab::ShadingInputs inputs;
  if (split) // each point's samples are seeded by its index in the whole mesh
  {
    static_assert(sizeof(vtkIdType) == sizeof(long long), "ids seed samples as 64-bit integers");
    inputs.sampleIds = reinterpret_cast<const long long*>(split->pieceIds.data());
  }
  if (plan.scene.material.arrays.any())
  {
    if (plan.precision == shadelab::Precision::Float32)
    {
      this->VertexMaterial.withFloat32(); // under a tolerance that chose float32: from float64
    }
    inputs.material = &this->VertexMaterial;
  }
  // Besides the kernel's: the occlusion arrays asked for, and which material values were clamped.
  std::vector<vtkSmartPointer<vtkDataArray>> besideShading =
    seen ? useVisibility(seen, plan.scene, plan.request, this->ArrayPrefix, inputs)
         : std::vector<vtkSmartPointer<vtkDataArray>>();
  if (plan.scene.material.arrays.clamps())
  {
    besideShading.push_back(clampedMaterialArray(this->VertexMaterial.clamped, this->ArrayPrefix));
  }
  vtkDataArray* points = input->GetPoints()->GetData();
  // The spectral mode always has its total, in XYZ too, and its difference from the RGB model.
  shadelab::ArrayRequest request = plan.request;
  std::optional<shadelab::LightColors> spectralColors;
  if (plan.scene.spectral)
  {
    spectralColors = shadelab::spectralLightColors(plan.scene);
    inputs.lightColors = &*spectralColors;
    request.totals[int(shadelab::TotalTerm::Total)] = true;
  }
  const ProgressReport progress = [this](double done) { this->ReportProgress(done); };
  auto shadeWith = [&](const shadelab::ArrayRequest& asked, SamplingOutcome* outcome)
  {
    return plan.precision == shadelab::Precision::Float64
      ? shade<double>(plan.scene, asked, plan.methods, this->ArrayPrefix, points, shadingNormals, inputs, &progress,
          outcome ? &outcome->shortOfTarget : nullptr, outcome ? &outcome->standardError : nullptr,
          outcome ? &outcome->samplesDrawn : nullptr)
      : shade<float>(plan.scene, asked, plan.methods, this->ArrayPrefix, points, shadingNormals, inputs, &progress,
          outcome ? &outcome->shortOfTarget : nullptr, outcome ? &outcome->standardError : nullptr,
          outcome ? &outcome->samplesDrawn : nullptr);
  };
  std::vector<vtkSmartPointer<vtkDataArray>> arrays = shadeWith(request, &sampling);
  if (spectralColors)
  {
    inputs.lightColors = nullptr; // the kernel's own products of RGB values: the RGB model
    shadelab::ArrayRequest totalAlone = shadelab::selectArrays(plan.scene, { "total" });
    totalAlone.flags = false;
    const std::vector<vtkSmartPointer<vtkDataArray>> rgbModel = shadeWith(totalAlone, nullptr);
    addSpectralArrays(arrays, rgbModel.front(), this->ArrayPrefix);
  }
  arrays.insert(arrays.end(), besideShading.begin(), besideShading.end());
  return arrays;
}

std::vector<std::string> vtkLocalReflectanceFilter::ShortOfTargetReport(
  const ShadingPlan& plan, const std::vector<std::vector<std::uint8_t>>& shortOfTarget,
  const shadelab::PieceLayout* split) const
{
  std::vector<std::string> report;
  for (std::size_t l = 0; l < plan.methods.size(); ++l)
  {
    if (!plan.methods[l].targets.any())
    {
      continue;
    }
    // On a split mesh, each vertex once, by its id in the whole mesh, whichever pieces hold it.
    std::vector<vtkIdType> ids;
    const std::vector<std::uint8_t> none;
    const std::vector<std::uint8_t>& marks = l < shortOfTarget.size() ? shortOfTarget[l] : none;
    for (std::size_t i = 0; i < marks.size(); ++i)
    {
      if (marks[i])
      {
        ids.push_back(split ? split->pieceIds[i] : static_cast<vtkIdType>(i));
      }
    }
    const std::size_t vertices = split ? shadelab::distinctIdCount(this->Controller, ids) : ids.size();
    if (vertices > 0)
    {
      report.push_back(plan.scene.lights[l].name + ": " + std::to_string(vertices) +
        " vertices stopped at \"max_samples\" short of their target (their _std_error arrays are above it): raise it");
    }
  }
  return report;
}

double vtkLocalReflectanceFilter::EstimatedSamplingError(
  std::vector<double> standardErrors, const shadelab::PieceLayout* split) const
{
  // A quantile of a few tens of thousands of values is that of the whole mesh to within a
  // fraction of a percent of its share (the rank of the 95th percentile among n has a
  // standard error of sqrt(0.05 0.95 / n), 0.12% of n at 32,768), so a large mesh gives every
  // k-th vertex by its id, 32,768 to 65,536 of them, the same on any number of processes.
  constexpr vtkIdType enough = 65536;
  std::vector<vtkIdType> ids;
  const vtkIdType count = static_cast<vtkIdType>(split ? split->pieceIds.size() : standardErrors.size());
  const vtkIdType wholeMesh = split ? shadelab::wholePointCount(this->Controller, split->pieceIds) : count;
  const vtkIdType stride = everyKth(wholeMesh, enough);
  std::vector<double> taken;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(standardErrors.size()) && i < count; ++i)
  {
    const vtkIdType id = split ? split->pieceIds[i] : i;
    if (id % stride == 0)
    {
      ids.push_back(id);
      taken.push_back(standardErrors[i]);
    }
  }
  return shadelab::estimatedErrorQuantile(
    split ? shadelab::valuesByDistinctId(this->Controller, ids, taken) : std::move(taken), shadelab::targetConfidence);
}

void vtkLocalReflectanceFilter::AddFieldNotes(vtkPolyData* output) const
{
  shadelab::addFieldNote(output, shadelab::normalsNoteName, { this->NormalsReport });
  if (!this->VisibilityReport.empty())
  {
    shadelab::addFieldNote(output, shadelab::visibilityNoteName, { this->VisibilityReport });
  }
  if (this->Tolerance > 0)
  {
    std::vector<std::string> lines = this->MethodPlan->describe();
    lines.insert(lines.end(), this->SamplingReport.begin(), this->SamplingReport.end());
    shadelab::addFieldNote(output, shadelab::methodsNoteName, lines);
  }
}

vtkDataArray* vtkLocalReflectanceFilter::PrepareNormals(vtkPolyData* input, vtkPolyData* output, bool split)
{
  vtkShadingNormalsFilter* step = this->NormalsStep;
  step->SetInputData(input);
  step->SetNormalsName(this->ComputedNormalsName());
  step->SetOrientOutward(this->OrientNormalsOutward);
  step->SetWeldCoincidentPoints(this->WeldCoincidentPoints);
  step->SetFeatureAngle(this->FeatureAngle);
  step->SetWeldTolerance(this->WeldTolerance);
  step->CheckCellsOff(); // meshProblem checked them
  // Outputs share the prepared normals: one edited in place since the step ran (and marked
  // modified) is not trusted.
  vtkDataArray* previous = step->GetOutput()->GetPointData()->GetNormals();
  // On a split mesh the step exchanges data, so every process runs it, whatever it has kept.
  if (split || (previous && previous->GetMTime() > step->GetOutput()->GetUpdateTime()))
  {
    step->Modified();
  }
  step->Update();
  // The input's own normals, or computed ones added to the output; either may be used
  // flipped, in which case the input's own array still passes through unchanged.
  vtkDataArray* inputNormals = input->GetPointData()->GetNormals();
  vtkDataArray* shading = step->GetOutput()->GetPointData()->GetNormals();
  this->NormalsReport = step->GetReport();
  if (!inputNormals)
  {
    output->GetPointData()->SetNormals(shading);
  }
  else if (shading != inputNormals)
  {
    this->NormalsReport += " Shaded with the flipped copy; the input's array passes through unchanged.";
  }
  return shading;
}

vtkPolyData* vtkLocalReflectanceFilter::PrepareVisibility(vtkPolyData* input, vtkDataArray* shadingNormals,
  const ShadingPlan& plan, bool split, const std::vector<vtkIdType>& rayPoints)
{
  const shadelab::Scene& scene = plan.scene;
  const shadelab::ArrayRequest& request = plan.request;
  if (!scene.needsVisibility())
  {
    return nullptr;
  }
  // The mesh's surface and the normals to shade with, and nothing else (no name can clash).
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(input->GetPoints());
  surface->SetPolys(input->GetPolys());
  surface->SetStrips(input->GetStrips());
  surface->GetPointData()->SetNormals(shadingNormals);
  if (split) // what puts the pieces together, for the surface's cells (after the vertices and lines)
  {
    surface->GetPointData()->SetGlobalIds(input->GetPointData()->GetGlobalIds());
    const vtkIdType firstPolygon = input->GetNumberOfVerts() + input->GetNumberOfLines();
    std::vector<vtkIdType> surfaceCells(static_cast<std::size_t>(input->GetNumberOfCells() - firstPolygon));
    std::iota(surfaceCells.begin(), surfaceCells.end(), firstPolygon);
    vtkCellData* cells = input->GetCellData();
    if (vtkDataArray* ids = cells->GetGlobalIds())
    {
      surface->GetCellData()->SetGlobalIds(shadelab::tuplesAt(ids, surfaceCells));
    }
    if (vtkDataArray* ghosts = cells->GetArray(vtkDataSetAttributes::GhostArrayName()))
    {
      surface->GetCellData()->AddArray(shadelab::tuplesAt(ghosts, surfaceCells));
    }
  }
  vtkMeshVisibilityFilter* step = this->VisibilityStep;
  step->CheckCellsOff(); // meshProblem checked them
  step->SetInputData(surface);
  step->SetScene(scene);
  step->SetArrayPrefix(this->ArrayPrefix);
  step->SetComputeBentNormal(request.occlusion[int(shadelab::OcclusionTerm::BentNormal)]);
  step->SetComputeSkyViewFactor(request.occlusion[int(shadelab::OcclusionTerm::SkyViewFactor)]);
  // A shadowed light drawn to a target is estimated where its rays are, as the kernel would
  // estimate it: the same targets, and the lobe where its specular term is computed.
  std::vector<vtkMeshVisibilityFilter::DrawnLight> drawn(scene.lights.size());
  for (std::size_t l = 0; l < plan.methods.size(); ++l)
  {
    drawn[l].targets = plan.methods[l].targets;
    drawn[l].lobe = { shadelab::specularComputed(scene, request, l) ? shadelab::evaluatedSpecularModel(scene)
                                                                    : shadelab::SpecularModel::None,
      scene.material.shininess };
  }
  step->SetDrawnLights(drawn);
  step->SetRayPointIds(rayPoints);
  step->Update();
  this->StopIfAborted(); // the step stopped (ForwardStepProgress asked it to)
  vtkPolyData* seen = step->GetOutput();
  if (input->GetNumberOfPoints() > 0 && !seen->GetPointData()->GetArray(shadelab::visibilityFlagsArrayName(this->ArrayPrefix).c_str()))
  {
    throw std::runtime_error("casting the rays for shadows and ambient occlusion failed (see the error above)");
  }
  this->VisibilityReport = step->GetReport();
  return seen;
}

std::optional<shadelab::CostForecast> vtkLocalReflectanceFilter::ForecastCost(
  vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan, bool split)
{
  const vtkIdType count = input->GetNumberOfPoints();
  if (split || count < pilotMeshLeast)
  {
    return std::nullopt;
  }
  const vtkIdType stride = everyKth(count, std::clamp<vtkIdType>(count / 64, pilotLeast, pilotMost));
  std::vector<vtkIdType> pilot;
  for (vtkIdType id = 0; id < count; id += stride)
  {
    pilot.push_back(id);
  }
  const auto start = std::chrono::steady_clock::now();
  // Its rays from the pilot's points only (the BVH built here is kept for the run), seeded by
  // their ids, as in the run.
  vtkPolyData* seen = this->PrepareVisibility(input, shadingNormals, plan, false, pilot);
  const double buildSeconds = seen ? std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
      this->VisibilityStep->GetRaySeconds()
                                   : 0.0;
  shadelab::ShadingInputs inputs; // the scene's own material: per-vertex values are read for the whole mesh
  const std::vector<long long> ids(pilot.begin(), pilot.end());
  inputs.sampleIds = ids.data();
  if (seen)
  {
    useVisibility(seen, plan.scene, plan.request, this->ArrayPrefix, inputs);
  }
  const vtkSmartPointer<vtkDataArray> points = shadelab::tuplesAt(input->GetPoints()->GetData(), pilot);
  const vtkSmartPointer<vtkDataArray> normals = shadelab::tuplesAt(shadingNormals, pilot);
  std::vector<std::uint32_t> samples(pilot.size(), 0);
  ShortOfTarget shortOfTarget;
  if (plan.precision == shadelab::Precision::Float64)
  {
    shade<double>(plan.scene, plan.request, plan.methods, this->ArrayPrefix, points, normals, inputs, nullptr,
      &shortOfTarget, nullptr, &samples);
  }
  else
  {
    shade<float>(plan.scene, plan.request, plan.methods, this->ArrayPrefix, points, normals, inputs, nullptr,
      &shortOfTarget, nullptr, &samples);
  }
  const double pilotSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - buildSeconds;

  shadelab::CostForecast forecast;
  const double scale = double(count) / double(pilot.size());
  forecast.pilotVertices = pilot.size();
  forecast.meshVertices = static_cast<std::size_t>(count);
  forecast.counts.samples = scale * std::accumulate(samples.begin(), samples.end(), 0.0);
  forecast.counts.occlusionRays = scale * occlusionRayCount(plan.scene, seen, this->ArrayPrefix, pilot.size());
  forecast.shareShortOfTarget =
    double(shortOfTargetCount(shortOfTarget, seen, this->ArrayPrefix, pilot.size())) / double(pilot.size());
  forecast.seconds = scale * pilotSeconds;
  forecast.threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  return forecast;
}

void vtkLocalReflectanceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArraySelection:";
  for (const std::string& entry : this->ArraySelection)
  {
    os << " " << entry;
  }
  os << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ArrayPrefix: " << this->ArrayPrefix << "\n";
  os << indent << "ColorByArray: " << this->ColorByArray << "\n";
  os << indent << "MaterialColorArray: " << this->MaterialColorArray << "\n";
  os << indent << "MaterialColorMap: " << this->MaterialColorMap << "\n";
  os << indent << "OutputPrecision: " << this->OutputPrecision << "\n";
  os << indent << "OrientNormalsOutward: " << this->OrientNormalsOutward << "\n";
  os << indent << "WeldCoincidentPoints: " << this->WeldCoincidentPoints << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "WeldTolerance: " << this->WeldTolerance << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
}
