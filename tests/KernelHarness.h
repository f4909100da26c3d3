#pragma once
// Test helper: runs the core ShadingKernel over a handful of vertices with every array the
// scene has, so a test can read any term of any vertex.
#include "ArrayCatalog.h"
#include "ShadingKernel.h"

#include <map>
#include <string>
#include <vector>

namespace shadelab::testing
{
template<typename T>
class KernelHarness
{
public:
  KernelHarness(const Scene& scene, const std::vector<Vec3<T>>& positions, const std::vector<Vec3<T>>& normals,
    const std::vector<std::string>& selection = { "all" })
    : flags(positions.size(), 0xff)
  {
    const ArrayRequest request = selectArrays(scene, selection);
    ShadingOutputs<T> outputs;
    outputs.lights.resize(scene.lights.size());
    const std::size_t count = positions.size();
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      outputs.lights[l].fill(nullptr);
      for (int t = 0; t < LightTermCount; ++t)
      {
        if (request.lights[l][t])
        {
          outputs.lights[l][t] = allocate(lightArrayName("", scene.lights[l].name, LightTerm(t)),
            lightTermComponents(scene.lights[l], LightTerm(t)) * count);
        }
      }
    }
    for (int t = 0; t < TotalTermCount; ++t)
    {
      outputs.totals[t] = request.totals[t] ? allocate(totalArrayName("", TotalTerm(t)), 3 * count) : nullptr;
    }
    outputs.flags = request.flags ? flags.data() : nullptr;
    const ShadingKernel<T> kernel(scene, outputs);
    shadeRange(kernel, 0, count,
      [&](std::size_t i, VertexBlock<T>& block, std::size_t k) { block.set(k, positions[i], normals[i]); });
  }

  /// Component c of array name at vertex i.
  T value(const std::string& name, std::size_t i, int c = 0) const
  {
    const std::vector<T>& array = arrays.at(name);
    const std::size_t components = array.size() / flags.size();
    return array.at(i * components + c);
  }

  Vec3<T> vec(const std::string& name, std::size_t i) const
  {
    return { value(name, i, 0), value(name, i, 1), value(name, i, 2) };
  }

  std::map<std::string, std::vector<T>> arrays;
  std::vector<ShadingFlags> flags;

private:
  T* allocate(const std::string& name, std::size_t size)
  {
    // NaN-filled, so a value the kernel forgot to write cannot pass for a result.
    std::vector<T>& array = arrays[name];
    array.assign(size, std::numeric_limits<T>::quiet_NaN());
    return array.data();
  }
};
}
