#pragma once
// The scene for when the user gives none: the lights of VTK's vtkLightKit, built from
// ShadeLab's own lights, in the mesh frame so that it suits a mesh of any size anywhere.
#include "Scene.h"

#include <string>

namespace shadelab
{
/// The kit as scene-file text: the one description of it, which docs/guide/scene-files.md shows verbatim.
const std::string& defaultLightKitText();

/// defaultLightKitText() parsed. Its frame is Mesh: place it with placedOnMesh (SceneFrame.h).
Scene defaultLightKit();
}
