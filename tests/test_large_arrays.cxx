// Output arrays of 4 MB and more come from ShadeLabLargeArrays.h: aligned to 2 MB, backed by
// huge pages where the kernel offers them, and filled completely by the filter.
#include "FilterRun.h"
#include "TestMeshes.h"

#include "ShadeLabLargeArrays.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace
{
using namespace shadelab;

constexpr std::uintptr_t hugePage = std::uintptr_t(2) << 20;

using Block = std::unique_ptr<void, decltype(&std::free)>;

/// The AnonHugePages line (kB) of the mapping in /proc/self/smaps that holds `address`.
long anonHugePagesKilobytes(const void* address)
{
  std::ifstream smaps("/proc/self/smaps");
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);)
  {
    std::uintptr_t low = 0, high = 0;
    char dash = 0;
    std::istringstream fields(line);
    if (fields >> std::hex >> low >> dash >> high && dash == '-')
    {
      inside = low <= at && at < high;
    }
    else if (inside && line.rfind("AnonHugePages:", 0) == 0)
    {
      return std::stol(line.substr(std::strlen("AnonHugePages:")));
    }
  }
  return -1;
}

TEST(LargeArrays, BlocksOfManyMegabytesAreAlignedToHugePages)
{
  const Block large(allocateLarge(8 << 20), &std::free);
  ASSERT_NE(large.get(), nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.get()) % hugePage, 0u);
  const Block small(allocateLarge(1000), &std::free);
  EXPECT_NE(small.get(), nullptr);
  // More than any machine has: no memory, and no exception.
  EXPECT_EQ(allocateLarge(SIZE_MAX / 2), nullptr);
}

TEST(LargeArrays, WrittenMemoryIsInHugePages)
{
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(setting, modes);
  if (modes.empty() || modes.find("[never]") != std::string::npos)
  {
    GTEST_SKIP() << "this kernel gives no transparent huge pages ('" << modes << "')";
  }
  const std::size_t bytes = 16 << 20;
  const Block block(allocateLarge(bytes), &std::free);
  ASSERT_NE(block.get(), nullptr);
  std::memset(block.get(), 1, bytes);
  EXPECT_GT(anonHugePagesKilobytes(block.get()), 0) << "transparent huge pages: " << modes;
}

TEST(LargeArrays, FilterFillsLargeArraysCompletely)
{
  // 359,402 vertices: the float64 RGB total is 8.6 MB, so it takes the large path. An ambient
  // light makes every vertex's value non-zero, so that a vertex left unwritten (a fresh page
  // reads 0) would show.
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(600);
  Scene scene;
  scene.material.ka = Rgb(0.1, 0.2, 0.3);
  scene.material.kd = Rgb(0.5, 0.25, 1.0);
  scene.material.specular = SpecularModel::None;
  scene.lights = { { "sun", DistantLight{ { 0, 0, -1 }, Rgb(1.0), 2.0, false } },
    { "sky", AmbientLight{ Rgb(1.0), 1.0 } } };
  vtkSmartPointer<vtkPolyData> output = shadelab::testing::shadeWithFilter(sphere, scene, { "total" });
  vtkDataArray* total = output->GetPointData()->GetArray("total");
  ASSERT_NE(total, nullptr);
  ASSERT_EQ(total->GetNumberOfTuples(), sphere->GetNumberOfPoints());
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(total->GetVoidPointer(0)) % hugePage, 0u);
  // ka + kd 2 max(0, z) at every vertex of the unit sphere, the light shining along -z.
  const double ka[] = { 0.1, 0.2, 0.3 };
  const double kd[] = { 0.5, 0.25, 1.0 };
  double worst = 0;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    const double z = sphere->GetPoint(i)[2];
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, std::abs(total->GetComponent(i, c) - (ka[c] + kd[c] * 2.0 * std::max(z, 0.0))));
    }
  }
  EXPECT_LT(worst, 1e-12);
}
}
