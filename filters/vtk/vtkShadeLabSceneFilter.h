/**
 * @class vtkShadeLabSceneFilter
 * @brief What ShadeLab's filters that run with a scene (vtkLocalReflectanceFilter,
 * vtkMeshVisibilityFilter) share: the properties that say where the scene comes from, and
 * its reading.
 *
 * The scene is read from SceneJson if it is set, else from SceneFileName, else it is the scene
 * given to SetScene, else the default light kit, as `shadelab shade` without --scene
 * (shadelab::SceneSource). A scene that cannot be read is the filter's error when it runs,
 * with the command line's message. The properties are strings so that VTK's Python wrapping
 * and ParaView's server-manager XML can set them.
 */
#ifndef vtkShadeLabSceneFilter_h
#define vtkShadeLabSceneFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include "SceneSource.h"

#include <optional>
#include <string>

class SHADELABFILTERS_EXPORT vtkShadeLabSceneFilter : public vtkPolyDataAlgorithm
{
public:
  vtkAbstractTypeMacro(vtkShadeLabSceneFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// A scene made in C++; forgets a scene file's name or JSON text given before.
  void SetScene(const shadelab::Scene& scene);
  /// A scene file (docs/guide/scene-files.md); "" for none.
  void SetSceneFileName(const std::string& fileName);
  std::string GetSceneFileName() const { return this->Scene.fileName(); }
  /// A scene as the JSON text of a scene file; "" for none.
  void SetSceneJson(const std::string& json);
  std::string GetSceneJson() const { return this->Scene.json(); }

  /// Why the last run failed because of the scene's values, as "<JSON pointer>: <problem>"
  /// ("/lights/0/radius: must be a number > 0"), for a caller to prefix with where its scene
  /// came from; "" when the scene was not the reason. The filter's error says the same after
  /// "scene ".
  std::string GetSceneProblem() const { return this->SceneProblem; }

protected:
  vtkShadeLabSceneFilter();
  ~vtkShadeLabSceneFilter() override;

  /// The scene as the properties give it now (a scene file is read again), or why it cannot be read.
  shadelab::SceneReading ReadScene() const { return this->Scene.read(); }
  /// The scene of `reading`, or nothing once why it could not be read is reported as the
  /// filter's error. A scene file that JSON text overrides is warned of.
  std::optional<shadelab::Scene> ReportedScene(const shadelab::SceneReading& reading);
  /// False, with the first problem reported as the filter's error and kept for
  /// GetSceneProblem, when the scene has problems.
  bool SceneIsValid(const std::vector<shadelab::SceneProblem>& problems);
  /// At the start of a run: its failure, if any, is not the scene's until SceneIsValid says so.
  void ForgetSceneProblem() { this->SceneProblem.clear(); }

private:
  vtkShadeLabSceneFilter(const vtkShadeLabSceneFilter&) = delete;
  void operator=(const vtkShadeLabSceneFilter&) = delete;

  shadelab::SceneSource Scene;
  std::string SceneProblem;
};

#endif
