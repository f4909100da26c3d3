#pragma once
// The baseline a user would otherwise reach for: vtkArrayCalculator evaluating the same
// lighting expression, written out from a scene.
#include "Scene.h"

#include <optional>
#include <string>

namespace shadelab::app
{
/// The vtkArrayCalculator expression for a scene's `diffuse` total (diffuseOnly) or `total`,
/// in terms of the vector variables `normals` (the name of the unit point normals array) and
/// "coords" (point coordinates). Covers what an expression can say plainly: distant and point lights with
/// 1/d^2 or no attenuation, ambient lights, Phong, Blinn-Phong or no specular, and a local
/// viewer or one at infinity. Empty for anything else.
std::optional<std::string> calculatorExpression(const Scene& scene, bool diffuseOnly, const std::string& normals);
}
