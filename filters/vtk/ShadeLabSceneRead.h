#ifndef ShadeLabSceneRead_h
#define ShadeLabSceneRead_h
// The scene a filter runs with, read from where its properties say (shadelab::SceneSource).
#include "SceneSource.h"

#include "vtkAlgorithm.h"

#include <optional>

namespace shadelab
{
/// The scene, or nothing once the reason it cannot be read (the command line's message) is
/// reported as the filter's error. A scene file that JSON text overrides is warned of.
inline std::optional<Scene> readSceneFor(vtkAlgorithm* filter, const SceneSource& source)
{
  if (source.hasJson() && !source.fileName().empty())
  {
    vtkWarningWithObjectMacro(filter, "both SceneJson and SceneFileName are set: the JSON text is used, not "
        << source.fileName() << " (set SceneJson to \"\" to use the file)");
  }
  try
  {
    return source.scene();
  }
  catch (const std::exception& error) // a scene file or JSON text that cannot be used
  {
    vtkErrorWithObjectMacro(filter, << error.what());
    return std::nullopt;
  }
}
}

#endif
