#include "ShadeLabIndirectLight.h"

#include "ShadingFlags.h"
#include "vtkInterreflectionFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <stdexcept>

namespace shadelab
{
vtkDataArray* named(const std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const std::string& name)
{
  const auto found = std::find_if(arrays.begin(), arrays.end(),
    [&](const vtkSmartPointer<vtkDataArray>& array) { return array->GetName() && name == array->GetName(); });
  return found == arrays.end() ? nullptr : found->Get();
}

namespace
{
/// kd per vertex from the material's arrays, r, g, b after one another (none on an empty
/// piece); nullptr where the scene's kd is every vertex's.
vtkSmartPointer<vtkDoubleArray> albedoArray(const Scene& scene, const VertexMaterial* material, vtkIdType points)
{
  if (!material || !scene.material.arrays[MaterialCoefficient::Diffuse])
  {
    return nullptr;
  }
  auto albedo = vtkSmartPointer<vtkDoubleArray>::New();
  albedo->SetName("albedo");
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(points);
  const double* wide = material->of<double>(MaterialCoefficient::Diffuse);
  const float* narrow = material->of<float>(MaterialCoefficient::Diffuse);
  for (vtkIdType i = 0; i < 3 * points; ++i)
  {
    albedo->SetValue(i, wide ? wide[i] : double(narrow[i]));
  }
  return albedo;
}

/// The array of that name among `arrays` or, on an empty piece, which shaded none, an empty one
/// of that name and size (added to them), so that its process takes part in the bounces.
vtkDataArray* namedOrEmpty(std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const std::string& name, int components)
{
  if (vtkDataArray* array = named(arrays, name))
  {
    return array;
  }
  auto empty = vtkSmartPointer<vtkDoubleArray>::New();
  empty->SetName(name.c_str());
  empty->SetNumberOfComponents(components);
  arrays.push_back(empty);
  return empty;
}

/// Whether a vertex's hidden side is its normal's back (so the seen one is its front). A vertex
/// of non-finite input, whose flags say that alone, sends nothing from either side.
bool hiddenOnBack(const HiddenSide& hidden, vtkIdType i)
{
  return (static_cast<unsigned>(hidden.flags->GetComponent(i, 0)) & FlagNormalFlipped) != 0;
}

/// The values of each vertex's front (the side its normal points to) or back, from the seen
/// side's array and the hidden side's (its diffuse term, or a transfer vector).
vtkSmartPointer<vtkDataArray> valuesOfSide(
  vtkDataArray* seen, vtkDataArray* hiddenValues, const HiddenSide& hidden, bool back, const std::string& name)
{
  vtkSmartPointer<vtkDataArray> side = vtk::TakeSmartPointer(seen->NewInstance());
  side->SetName(name.c_str());
  side->SetNumberOfComponents(seen->GetNumberOfComponents());
  side->SetNumberOfTuples(seen->GetNumberOfTuples());
  for (vtkIdType i = 0; i < seen->GetNumberOfTuples(); ++i)
  {
    side->SetTuple(i, (hiddenOnBack(hidden, i) == back ? hiddenValues : seen)->GetTuple(i));
  }
  return side;
}

/// The step's front and back arrays of that name made one, of the side each vertex is seen
/// from, under the front's name.
void keepSeenSide(vtkPointData* gathered, const HiddenSide& hidden, const std::string& name)
{
  vtkDataArray* front = gathered->GetArray(name.c_str());
  vtkDataArray* back = gathered->GetArray((name + "_back").c_str());
  for (vtkIdType i = 0; i < front->GetNumberOfTuples(); ++i)
  {
    if (!hiddenOnBack(hidden, i))
    {
      front->SetTuple(i, back->GetTuple(i));
    }
  }
  gathered->RemoveArray((name + "_back").c_str());
}

/// into += scale x added, RGB tuple by tuple.
void addScaled(vtkDataArray* into, vtkDataArray* added, double scale)
{
  for (vtkIdType i = 0; i < into->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      into->SetComponent(i, c, into->GetComponent(i, c) + scale * added->GetComponent(i, c));
    }
  }
}
}

ArrayRequest withInterreflectionSources(const Scene& scene, const ArrayRequest& asked)
{
  ArrayRequest request = asked;
  if (needsInterreflection(scene, asked))
  {
    request.totals[int(TotalTerm::Diffuse)] = true;
    request.totals[int(TotalTerm::Ambient)] |= asked.interreflection[int(InterreflectionTerm::AmbientMinusIndirect)];
    for (std::size_t l = 0; l < asked.indirectTransfer.size(); ++l)
    {
      request.lights[l][int(LightTerm::ShTransfer)] =
        request.lights[l][int(LightTerm::ShTransfer)] || asked.indirectTransfer[l];
    }
  }
  return request;
}

namespace
{
/// The gather's error in the diffuse term at 95% of the vertices (estimatedErrorQuantile): each
/// vertex's kd times its standard error, in its largest channel, over every piece's vertices
/// (each once) on a split mesh.
double gatherError(vtkPointData* gathered, vtkDoubleArray* albedo, const Scene& scene, const MeshPieces& pieces)
{
  vtkDataArray* standardError = gathered->GetArray("indirect_irradiance_std_error");
  std::vector<double> errors(static_cast<std::size_t>(standardError->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < standardError->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double kd = albedo ? albedo->GetComponent(i, c) : scene.material.kd[c];
      errors[std::size_t(i)] = std::max(errors[std::size_t(i)], kd * standardError->GetComponent(i, c));
    }
  }
  if (pieces.split())
  {
    errors = valuesByDistinctId(pieces.processes, *pieces.pointIds(), errors);
  }
  return estimatedErrorQuantile(std::move(errors), targetConfidence);
}

/// The step run, and under a tolerance run once more with more rays where the first run's
/// standard errors say its share needs them. With a hidden side, each vertex keeps the arrays
/// of the side it is seen from.
vtkPointData* runStep(vtkInterreflectionFilter* step, vtkDoubleArray* albedo, const Scene& scene,
  const MeshPieces& pieces, InterreflectionChoice* choice, const HiddenSide* hidden)
{
  auto run = [&]
  {
    step->Update();
    vtkPointData* gathered = step->GetOutput()->GetPointData();
    if (!gathered->GetArray("indirect_irradiance"))
    {
      throw std::runtime_error("interreflection failed (see the error above)");
    }
    std::vector<std::string> sided; // every array the step wrote for the fronts and the backs
    vtkPointData* given = vtkPolyData::SafeDownCast(step->GetInputDataObject(0, 0))->GetPointData();
    for (int a = 0; hidden && a < gathered->GetNumberOfArrays(); ++a)
    {
      const char* name = gathered->GetArrayName(a); // null for a mesh's unnamed normals
      if (name && !given->HasArray(name) && gathered->GetArray((std::string(name) + "_back").c_str()))
      {
        sided.push_back(name);
      }
    }
    for (const std::string& name : sided)
    {
      keepSeenSide(gathered, *hidden, name);
    }
    return gathered;
  };
  vtkPointData* gathered = run();
  if (choice)
  {
    const Sampling& sampling = scene.interreflection->sampling;
    choice->firstSamples = step->GetSamples();
    choice->samples = gatherRaysWithin(
      gatherError(gathered, albedo, scene, pieces), choice->firstSamples, choice->samplingShare(), sampling.maximum);
    if (choice->samples > choice->firstSamples)
    {
      step->SetSamples(choice->samples);
      gathered = run();
    }
    choice->estimatedSamplingError = gatherError(gathered, albedo, scene, pieces);
    choice->bounces = step->GetBounceCount();
    choice->bouncesLeftOut = step->GetRestBound();
  }
  return gathered;
}

/// The transfer arrays (among `arrays`) of the lights whose indirect transfer is asked for.
std::vector<vtkDataArray*> transfersToCarry(const Scene& scene, const ArrayRequest& asked, const std::string& prefix,
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays)
{
  std::vector<vtkDataArray*> transfers;
  for (std::size_t l = 0; l < asked.indirectTransfer.size(); ++l)
  {
    if (asked.indirectTransfer[l])
    {
      transfers.push_back(namedOrEmpty(arrays, lightArrayName(prefix, scene.lights[l].name, LightTerm::ShTransfer),
        lightTermComponents(scene.lights[l], LightTerm::ShTransfer)));
    }
  }
  return transfers;
}

/// The piece's global ids and ghost cells, which say where it lies in the whole mesh, onto the
/// surface the step is given.
void markAsPiece(vtkPolyData* piece, vtkPolyData* surface)
{
  surface->GetPointData()->SetGlobalIds(piece->GetPointData()->GetGlobalIds());
  surface->GetCellData()->SetGlobalIds(piece->GetCellData()->GetGlobalIds());
  if (vtkDataArray* ghosts = piece->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()))
  {
    surface->GetPointData()->AddArray(ghosts);
  }
  if (vtkDataArray* ghosts = piece->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()))
  {
    surface->GetCellData()->AddArray(ghosts);
  }
}

/// The step run on the input's surface (its points and cells, the shading normals, the direct
/// radiosity, the albedo and the transfer vectors to carry, and nothing else, so that no name
/// can clash); returns its output's arrays. Under a tolerance, the bounces are the fewest whose
/// rest fits the choice's share. Throws std::runtime_error where it failed.
vtkPointData* gatherBounces(vtkInterreflectionFilter* step, vtkPolyData* input, vtkDataArray* shadingNormals,
  vtkDataArray* diffuse, vtkDoubleArray* albedo, const std::vector<vtkDataArray*>& transfers, const Scene& scene,
  const ArrayRequest& asked, const MeshPieces& pieces, InterreflectionChoice* choice, const HiddenSide* hidden)
{
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(input->GetPoints());
  surface->SetPolys(input->GetPolys());
  surface->SetStrips(input->GetStrips());
  surface->GetPointData()->SetNormals(shadingNormals);
  step->SetController(pieces.processes);
  if (pieces.split())
  {
    markAsPiece(input, surface);
  }
  // With a hidden side (an empty piece has none), the fronts' and the backs' radiosity.
  const bool sides = hidden && hidden->diffuse;
  vtkSmartPointer<vtkDataArray> radiosity;
  if (sides)
  {
    radiosity = valuesOfSide(diffuse, hidden->diffuse, *hidden, false, "front_diffuse");
  }
  else
  {
    radiosity = vtk::TakeSmartPointer(diffuse->NewInstance());
    radiosity->ShallowCopy(diffuse);
    radiosity->SetName(hidden ? "front_diffuse" : "diffuse"); // an empty piece's, with a hidden side
  }
  surface->GetPointData()->AddArray(radiosity);
  if (sides)
  {
    surface->GetPointData()->AddArray(valuesOfSide(diffuse, hidden->diffuse, *hidden, true, "back_diffuse"));
  }
  step->SetBackRadiosityArrayName(hidden ? "back_diffuse" : "");
  if (albedo)
  {
    surface->GetPointData()->AddArray(albedo);
  }
  step->RemoveAllTransferArrayNames();
  for (vtkDataArray* transfer : transfers) // with a hidden side, the fronts' and the backs' (<name>_back)
  {
    const std::string name = transfer->GetName();
    vtkDataArray* hiddenTransfer = sides ? hidden->transfers.at(name).Get() : nullptr;
    surface->GetPointData()->AddArray(
      hiddenTransfer ? valuesOfSide(transfer, hiddenTransfer, *hidden, false, name).Get() : transfer);
    if (hiddenTransfer)
    {
      surface->GetPointData()->AddArray(valuesOfSide(transfer, hiddenTransfer, *hidden, true, name + "_back"));
    }
    step->AddTransferArrayName(name);
  }
  const Interreflection& settings = *scene.interreflection;
  step->SetInputData(surface);
  step->SetRadiosityArrayName(radiosity->GetName());
  step->SetAlbedoArrayName(albedo ? "albedo" : "");
  step->SetAlbedo(scene.material.kd.r, scene.material.kd.g, scene.material.kd.b);
  step->SetBounces(choice ? Interreflection::maxBounces : settings.bounces);
  step->SetBounceTolerance(choice ? choice->truncationShare() : 0);
  // "max_samples" bounds the first run too.
  step->SetSamples(choice ? std::min(settings.sampling.samples, settings.sampling.maximum) : settings.sampling.samples);
  step->SetStratified(settings.sampling.stratified);
  step->SetKeepBounces(std::any_of(asked.bounces.begin(), asked.bounces.end(), [](bool b) { return b; }));
  step->SetArrayPrefix("");
  return runStep(step, albedo, scene, pieces, choice, hidden);
}

/// kd E_ind, in the precision of `like` (the shaded diffuse term).
vtkSmartPointer<vtkDataArray> indirectDiffuseTerm(
  vtkDataArray* irradiance, vtkDoubleArray* albedo, const Scene& scene, vtkDataArray* like, const std::string& name)
{
  vtkSmartPointer<vtkDataArray> indirect = vtk::TakeSmartPointer(like->NewInstance());
  indirect->SetName(name.c_str());
  indirect->SetNumberOfComponents(3);
  indirect->SetNumberOfTuples(irradiance->GetNumberOfTuples());
  for (vtkIdType i = 0; i < irradiance->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double kd = albedo ? albedo->GetComponent(i, c) : scene.material.kd[c];
      indirect->SetComponent(i, c, kd * irradiance->GetComponent(i, c));
    }
  }
  return indirect;
}

/// The totals and transfer vectors shaded only as the bounces' sources, out of `arrays`.
void dropSourcesNotAsked(const Scene& scene, const ArrayRequest& asked, const std::string& prefix,
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays)
{
  std::vector<std::string> sources;
  for (const TotalTerm term : { TotalTerm::Diffuse, TotalTerm::Ambient })
  {
    if (!asked.totals[int(term)])
    {
      sources.push_back(totalArrayName(prefix, term));
    }
  }
  for (std::size_t l = 0; l < asked.indirectTransfer.size(); ++l)
  {
    if (!asked.lights[l][int(LightTerm::ShTransfer)])
    {
      sources.push_back(lightArrayName(prefix, scene.lights[l].name, LightTerm::ShTransfer));
    }
  }
  arrays.erase(std::remove_if(arrays.begin(), arrays.end(),
                 [&](const vtkSmartPointer<vtkDataArray>& array)
                 { return array->GetName() && std::count(sources.begin(), sources.end(), array->GetName()) > 0; }),
    arrays.end());
}

/// The bounce arrays asked for by name past the count that "bounces": "auto" chose, which are not
/// written (-a all asks for every one a plan may choose, and is not told).
std::string bouncesNotMade(const ArrayRequest& asked, const std::string& prefix, int made)
{
  std::string note;
  const auto& bounces = asked.bounces;
  if (std::all_of(bounces.begin(), bounces.end(), [](bool b) { return b; }))
  {
    return note;
  }
  for (std::size_t n = std::size_t(made) + 1; n <= bounces.size(); ++n)
  {
    if (bounces[n - 1])
    {
      note += "; " + indirectBounceArrayName(prefix, int(n)) + " was asked for, past the " + std::to_string(made) +
        " bounces the plan made: not written";
    }
  }
  return note;
}
}

std::string addIndirectLight(vtkInterreflectionFilter* step, vtkPolyData* input, vtkDataArray* shadingNormals,
  const Scene& scene, const ArrayRequest& asked, const VertexMaterial* material, const std::string& prefix,
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const MeshPieces& pieces, InterreflectionChoice* choice,
  const HiddenSide* hidden)
{
  vtkDataArray* diffuse = namedOrEmpty(arrays, totalArrayName(prefix, TotalTerm::Diffuse), 3);
  const vtkSmartPointer<vtkDoubleArray> albedo = albedoArray(scene, material, input->GetNumberOfPoints());
  const std::vector<vtkDataArray*> transfers = transfersToCarry(scene, asked, prefix, arrays);
  vtkPointData* gathered =
    gatherBounces(step, input, shadingNormals, diffuse, albedo, transfers, scene, asked, pieces, choice, hidden);
  vtkDataArray* irradiance = gathered->GetArray("indirect_irradiance");
  const vtkSmartPointer<vtkDataArray> indirect = indirectDiffuseTerm(
    irradiance, albedo, scene, diffuse, interreflectionArrayName(prefix, InterreflectionTerm::Indirect));
  std::vector<vtkSmartPointer<vtkDataArray>> added;
  auto keep = [&](bool wanted, vtkDataArray* array, const std::string& name)
  {
    if (wanted)
    {
      array->SetName(name.c_str());
      added.push_back(array);
    }
  };
  const auto& wanted = asked.interreflection;
  if (wanted[int(InterreflectionTerm::AmbientMinusIndirect)])
  {
    vtkSmartPointer<vtkDataArray> difference = vtk::TakeSmartPointer(indirect->NewInstance());
    difference->DeepCopy(named(arrays, totalArrayName(prefix, TotalTerm::Ambient)));
    addScaled(difference, indirect, -1);
    keep(true, difference, interreflectionArrayName(prefix, InterreflectionTerm::AmbientMinusIndirect));
  }
  for (const TotalTerm term : { TotalTerm::Diffuse, TotalTerm::Total })
  {
    if (vtkDataArray* total = named(arrays, totalArrayName(prefix, term)))
    {
      addScaled(total, indirect, 1);
    }
  }
  keep(wanted[int(InterreflectionTerm::IndirectIrradiance)], irradiance,
    interreflectionArrayName(prefix, InterreflectionTerm::IndirectIrradiance));
  keep(wanted[int(InterreflectionTerm::IndirectIrradianceStdError)],
    gathered->GetArray("indirect_irradiance_std_error"),
    interreflectionArrayName(prefix, InterreflectionTerm::IndirectIrradianceStdError));
  keep(wanted[int(InterreflectionTerm::Indirect)], indirect,
    interreflectionArrayName(prefix, InterreflectionTerm::Indirect));
  // Under "bounces": "auto" the request reaches past the bounces the plan made.
  for (std::size_t n = 1; n <= asked.bounces.size() && n <= std::size_t(step->GetBounceCount()); ++n)
  {
    keep(asked.bounces[n - 1], gathered->GetArray(("indirect_bounce_" + std::to_string(n)).c_str()),
      indirectBounceArrayName(prefix, int(n)));
  }
  for (vtkDataArray* transfer : transfers) // the step named it <transfer>_indirect
  {
    added.push_back(gathered->GetArray((std::string(transfer->GetName()) + "_indirect").c_str()));
  }
  dropSourcesNotAsked(scene, asked, prefix, arrays);
  arrays.insert(arrays.end(), added.begin(), added.end());
  // What the step holds is not kept until the next run (the arrays asked for are in `arrays`).
  step->GetOutput()->Initialize();
  step->SetInputData(nullptr);
  const std::string sides =
    hidden ? "both sides shaded (front_diffuse: the diffuse term on the side the normals point to): " : "";
  return sides + step->GetReport() + bouncesNotMade(asked, prefix, step->GetBounceCount());
}
}
