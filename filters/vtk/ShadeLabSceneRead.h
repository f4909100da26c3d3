#ifndef ShadeLabSceneRead_h
#define ShadeLabSceneRead_h
// The scene a filter runs with, read from where its properties say (shadelab::SceneSource).
#include "SceneSource.h"

#include "vtkAlgorithm.h"

#include <optional>

namespace shadelab
{
/// The scene read, or nothing once the reason it could not be is reported as the filter's
/// error. A scene file that JSON text overrides is warned of.
inline std::optional<Scene> reportedScene(vtkAlgorithm* filter, const SceneSource& source, const SceneReading& reading)
{
  if (source.hasJson() && !source.fileName().empty())
  {
    vtkWarningWithObjectMacro(filter, "both SceneJson and SceneFileName are set: the JSON text is used, not "
        << source.fileName() << " (set SceneJson to \"\" to use the file)");
  }
  if (!reading.scene)
  {
    vtkErrorWithObjectMacro(filter, << reading.problem);
  }
  return reading.scene;
}

/// The scene, read now, or nothing once why it cannot be is reported (reportedScene).
inline std::optional<Scene> readSceneFor(vtkAlgorithm* filter, const SceneSource& source)
{
  return reportedScene(filter, source, source.read());
}
}

#endif
