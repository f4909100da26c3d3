// A scene file's text: parsed and checked, and when valid, shaded at a few vertices in both
// precisions, as the filter would.
#include "KernelHarness.h"
#include "SceneFile.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace
{
template<typename T>
void shadeAFewVertices(const shadelab::Scene& scene)
{
  using shadelab::Vec3;
  if (!shadelab::sceneProblems(scene, sizeof(T) == 4 ? shadelab::Precision::Float32 : shadelab::Precision::Float64)
         .empty())
  {
    return; // the filter refuses it
  }
  const std::vector<Vec3<T>> positions = { Vec3<T>(0), Vec3<T>(T(0.1), T(-0.2), T(0.3)), Vec3<T>(T(1e3), 0, 0),
    Vec3<T>(0, T(0.01), 0) };
  const std::vector<Vec3<T>> normals = { Vec3<T>(0, 0, 1), Vec3<T>(T(0.6), 0, T(-0.8)), Vec3<T>(0), Vec3<T>(0, 1, 0) };
  shadelab::testing::KernelHarness<T> run(scene, positions, normals);
}
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  shadelab::Scene scene;
  try
  {
    scene = shadelab::parseScene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  }
  catch (const shadelab::SceneFileError&)
  {
    return 0;
  }
  // Distributed lights are estimated per vertex with their sample counts: keep a run short.
  for (const shadelab::NamedLight& light : scene.lights)
  {
    if (std::holds_alternative<shadelab::AreaLight>(light.source) ||
      std::holds_alternative<shadelab::EnvironmentLight>(light.source))
    {
      return 0;
    }
  }
  shadeAFewVertices<float>(scene);
  shadeAFewVertices<double>(scene);
  return 0;
}
