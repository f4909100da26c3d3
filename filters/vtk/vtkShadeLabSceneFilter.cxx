#include "vtkShadeLabSceneFilter.h"

vtkShadeLabSceneFilter::vtkShadeLabSceneFilter() = default;
vtkShadeLabSceneFilter::~vtkShadeLabSceneFilter() = default;

void vtkShadeLabSceneFilter::SetScene(const shadelab::Scene& scene)
{
  this->Scene.setScene(scene);
  this->Modified();
}

void vtkShadeLabSceneFilter::SetSceneFileName(const std::string& fileName)
{
  if (this->Scene.setFileName(fileName))
  {
    this->Modified();
  }
}

void vtkShadeLabSceneFilter::SetSceneJson(const std::string& json)
{
  if (this->Scene.setJson(json))
  {
    this->Modified();
  }
}

std::optional<shadelab::Scene> vtkShadeLabSceneFilter::ReportedScene(const shadelab::SceneReading& reading)
{
  if (this->Scene.hasJson() && !this->Scene.fileName().empty())
  {
    vtkWarningMacro("both SceneJson and SceneFileName are set: the JSON text is used, not "
      << this->Scene.fileName() << " (set SceneJson to \"\" to use the file)");
  }
  if (!reading.scene)
  {
    vtkErrorMacro(<< reading.problem);
  }
  return reading.scene;
}

bool vtkShadeLabSceneFilter::SceneIsValid(const std::vector<shadelab::SceneProblem>& problems)
{
  if (problems.empty())
  {
    return true;
  }
  this->SceneProblem = problems.front().path + ": " + problems.front().message;
  vtkErrorMacro("scene " << this->SceneProblem);
  return false;
}

void vtkShadeLabSceneFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SceneFileName: " << this->Scene.fileName() << "\n";
  os << indent << "SceneJson: " << (this->Scene.hasJson() ? "(set)" : "(none)") << "\n";
}
