#include "DefaultLightKit.h"

#include "SceneFile.h"

namespace shadelab
{
// vtkLightKit's defaults (VTK 9.1, vtkLightKit.cxx), as distant lights:
// - key at elevation 50, azimuth 10, intensity 0.75, warmth 0.6; fill at elevation -75,
//   azimuth -10, key / 3; back lights at elevation 0, azimuth +110 and -110, key / 3.5 =
//   0.214286. The kit's headlight (key / 3) is left out; a small ambient light lifts the
//   faces that the key and fill miss instead.
// - Directions: vtkLight::SetDirectionAngle puts a light at elevation e, azimuth a in the
//   direction (cos e sin a, sin e, cos e cos a) from the focal point, in coordinates of a
//   camera that looks down -z with +y up (+x to its right); the light travels toward the
//   focal point, so direction = -(cos e sin a, sin e, cos e cos a), rounded to 6 decimals.
//   Azimuth +110 is on the viewer's right (x > 0): back_right.
// - Colours: vtkLightKit's warmth table (64 entries over [0, 1]) interpolated at the key's
//   0.6 (slightly warm) and the fill's 0.4 (slightly cool); the back lights' 0.5 is white.
// - The viewer sits on +z, so the camera's axes are the mesh frame's, at distance
//   d = 1/sin(15 degrees) from the centre: the bounding sphere (radius 1) just fits a
//   30-degree view angle, vtkCamera's default.
const std::string& defaultLightKitText()
{
  static const std::string text = R"({
  "frame": "mesh",
  "viewer": { "position": [0, 0, 3.8637033051562737], "focal_point": [0, 0, 0] },
  "material": { "kd": 0.8, "ks": 0.25, "shininess": 32, "specular": "blinn-phong" },
  "lights": [
    { "name": "key", "type": "distant", "direction": [-0.111619, -0.766044, -0.633022],
      "color": [1.0, 0.9723, 0.9022], "intensity": 0.75 },
    { "name": "fill", "type": "distant", "direction": [0.044943, 0.965926, -0.254887],
      "color": [0.9082, 0.9331, 1.0], "intensity": 0.25 },
    { "name": "back_left", "type": "distant", "direction": [0.939693, 0, 0.34202],
      "intensity": 0.214286 },
    { "name": "back_right", "type": "distant", "direction": [-0.939693, 0, 0.34202],
      "intensity": 0.214286 },
    { "name": "ambient", "type": "ambient", "intensity": 0.1 }
  ]
}
)";
  return text;
}

Scene defaultLightKit()
{
  Scene kit = parseScene(defaultLightKitText(), "the default light kit");
  kit.materialGiven = false; // the kit's material is a default: a mesh's own materials win over it
  return kit;
}
}
