#pragma once
// The message a scene file's text is refused with, for tests of the scene file's rules.
#include "SceneFile.h"

#include <string>

namespace shadelab::testing
{
/// parseScene's error for text (as from a file named scene.json), or "no error".
inline std::string sceneFileErrorOf(const std::string& text)
{
  try
  {
    parseScene(text, "scene.json");
  }
  catch (const SceneFileError& error)
  {
    return error.what();
  }
  return "no error";
}
}
