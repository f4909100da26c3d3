#pragma once
// Scenes that several test programs shade.
#include <string>

namespace shadelab::testing
{
/// data/scenes/interreflection.json's scene with fewer rays (32 gather rays a vertex, 16 of the
/// map's), under the map at mapPath: the same exchanges between processes, for a test's time.
inline std::string bouncesUnderAMapScene(const std::string& mapPath)
{
  return R"({ "material": { "kd": [0.8, 0.62, 0.45], "ks": [0.35, 0.35, 0.35], "shininess": 40 },
         "viewer": { "position": [0.0, 0.12, 0.45], "focal_point": [-0.017, 0.11, 0.0] },
         "interreflection": { "bounces": 3, "samples": 32 },
         "lights": [ { "name": "studio", "type": "environment", "file": ")" +
    mapPath + R"(", "estimator": "sh", "directions": "mis", "samples": 16, "intensity": 0.04, "shadows": true } ] })";
}
}
