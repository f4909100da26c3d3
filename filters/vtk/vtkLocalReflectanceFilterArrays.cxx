// vtkLocalReflectanceFilter's list of the scene's arrays (for ParaView's panel), its array
// selection, and the names it would write, checked free on the input.
#include "vtkLocalReflectanceFilterInternals.h"

#include "ArrayCatalog.h"
#include "ShadeLabMaterialArrays.h"
#include "ShadeLabShadedArrays.h"
#include "ShadeLabWholeMesh.h"

#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <stdexcept>

namespace
{
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
}

void vtkLocalReflectanceFilter::AvailableArraysChanged()
{
  if (!this->Internals->FillingAvailableArrays)
  {
    this->Modified();
  }
}

int vtkLocalReflectanceFilter::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  vtkDataArraySelection* list = this->AvailableArrays;
  // An empty list changed is no choice: ParaView sets the list it has before the first fill.
  const bool chosenInList =
    list->GetNumberOfArrays() > 0 && list->GetMTime() > this->Internals->AvailableArraysFilledAt;
  // Read once for the update: RequestData shades with it, or reports why it could not be read.
  this->Internals->SceneOfThisUpdate = this->ReadScene();
  if (!this->Internals->SceneOfThisUpdate.scene)
  {
    return 1; // RequestData reports it
  }
  const shadelab::Scene& scene = *this->Internals->SceneOfThisUpdate.scene;
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
    this->Internals->SelectionFromList = true;
  }
  if (this->Internals->SelectionFromList)
  {
    // Names from the list, of another scene's arrays, that this scene lacks.
    this->ArraySelection.erase(std::remove_if(this->ArraySelection.begin(), this->ArraySelection.end(),
                                 [&](const std::string& name) { return !isAvailable(name); }),
      this->ArraySelection.end());
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
  this->Internals->FillingAvailableArrays = true;
  list->RemoveAllArrays();
  for (const std::string& name : available)
  {
    list->AddArray(name.c_str(), std::find(selected.begin(), selected.end(), name) != selected.end());
  }
  this->Internals->FillingAvailableArrays = false;
  this->Internals->AvailableArraysFilledAt = list->GetMTime();
  return 1;
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
  this->Internals->AvailableArraysFilledAt = this->AvailableArrays->GetMTime();
  this->Internals->SelectionFromList = false;
  this->Modified();
}

std::string vtkLocalReflectanceFilter::GetArraySelectionEntry(int i) const
{
  return i >= 0 && i < this->GetNumberOfArraySelectionEntries() ? this->ArraySelection[i] : std::string();
}

std::vector<std::string> vtkLocalReflectanceFilter::WritableArrayNames(
  vtkPolyData* input, const shadelab::Scene& scene) const
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
  vtkPolyData* input, const shadelab::Scene& scene, const shadelab::MeshPieces& pieces)
{
  const std::string taken = takenName(input, this->WritableArrayNames(input, scene));
  const std::string problem = pieces.firstProblem(taken.empty() ? ""
                                                                : "the input already has a point array named '" +
        taken + "', which this filter would write: set an array prefix (shadelab shade --prefix) to keep both");
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  return true;
}
