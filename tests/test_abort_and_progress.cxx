// A long run stops when its pipeline asks (vtkAlgorithm::SetAbortExecute, ParaView's Cancel),
// leaving an empty output and no error, and its progress moves through the normals, the rays
// and the shading, in order.
#include "MeshFiles.h"
#include "SceneFile.h"
#include "TestPaths.h"
#include "VtkErrorCapture.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <vector>

namespace
{
using namespace shadelab;
const std::string data = shadelab::testing::sourcePath("data/");

/// The studio lights with ambient occlusion of `rays` rays per vertex.
Scene studioWithOcclusion(int rays)
{
  Scene scene = readSceneFile(data + "scenes/studio.json");
  scene.ambientOcclusion = AmbientOcclusion{};
  scene.ambientOcclusion->sampling.samples = rays;
  return scene;
}

/// The bunny's filter under scene, its totals and occlusion asked for.
void setUp(vtkLocalReflectanceFilter* filter, vtkPolyData* bunny, const Scene& scene)
{
  filter->SetInputData(bunny);
  filter->SetScene(scene);
  filter->SetArraySelection({ "totals", "ambient_occlusion" });
}

double secondsToUpdate(vtkLocalReflectanceFilter* filter)
{
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A progress observer that asks its filter to abort at the first event past `threshold`.
struct AbortPast
{
  double threshold = 0;
  bool asked = false;

  static void onProgress(vtkObject* caller, unsigned long, void* self, void* done)
  {
    auto* abort = static_cast<AbortPast*>(self);
    if (!abort->asked && *static_cast<double*>(done) >= abort->threshold)
    {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      abort->asked = true;
    }
  }
};
}

TEST(AbortAndProgress, AnAbortStopsA2048RayOcclusionRunWithinAQuarterOfItsTime)
{
  vtkSmartPointer<vtkPolyData> bunny = app::readMesh(data + "meshes/bunny_zipper.ply");
  const Scene scene = studioWithOcclusion(2048);
  vtkNew<vtkLocalReflectanceFilter> whole;
  setUp(whole, bunny, scene);
  const double full = secondsToUpdate(whole);
  ASSERT_NE(whole->GetOutput()->GetPointData()->GetArray("ambient_occlusion"), nullptr);

  // At the first event (VTK's own, as the run starts) and at the first past the rays' start
  // (the normals done: 5% of the progress), as a user who cancels midway.
  for (const double threshold : { 0.0, 0.06 })
  {
    vtkNew<vtkLocalReflectanceFilter> stopped;
    setUp(stopped, bunny, scene);
    AbortPast abort{ threshold };
    vtkNew<vtkCallbackCommand> observer;
    observer->SetCallback(AbortPast::onProgress);
    observer->SetClientData(&abort);
    stopped->AddObserver(vtkCommand::ProgressEvent, observer);
    vtkNew<app::VtkErrorCapture> errors;
    errors->watch(stopped);
    const double seconds = secondsToUpdate(stopped);
    std::cout << "aborted at progress " << threshold << ": " << seconds << " s, against " << full
              << " s for the whole run\n";
    EXPECT_TRUE(abort.asked);
    EXPECT_LT(seconds, full / 4) << "aborted at progress " << threshold << " after " << seconds << " s; the whole run "
                                 << full << " s";
    EXPECT_FALSE(errors->failed()) << errors->message();
    EXPECT_EQ(stopped->GetOutput()->GetNumberOfPoints(), 0) << "an empty output";
    EXPECT_EQ(stopped->GetOutput()->GetPointData()->GetNumberOfArrays(), 0) << "no partial arrays";

    // Run again, it shades the whole mesh: what the aborted run left is not kept.
    stopped->RemoveObserver(observer);
    stopped->Update();
    ASSERT_EQ(stopped->GetOutput()->GetNumberOfPoints(), bunny->GetNumberOfPoints());
    vtkDataArray* occlusion = stopped->GetOutput()->GetPointData()->GetArray("ambient_occlusion");
    vtkDataArray* expected = whole->GetOutput()->GetPointData()->GetArray("ambient_occlusion");
    ASSERT_NE(occlusion, nullptr);
    for (vtkIdType i = 0; i < occlusion->GetNumberOfTuples(); i += 97)
    {
      ASSERT_EQ(occlusion->GetComponent(i, 0), expected->GetComponent(i, 0)) << i;
    }
  }
}

/// The progress a run of the filter reports, in order.
std::vector<double> progressOf(vtkLocalReflectanceFilter* filter)
{
  std::vector<double> seen;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetCallback([](vtkObject*, unsigned long, void* values, void* done)
    { static_cast<std::vector<double>*>(values)->push_back(*static_cast<double*>(done)); });
  observer->SetClientData(&seen);
  filter->AddObserver(vtkCommand::ProgressEvent, observer);
  filter->Update();
  filter->RemoveObserver(observer);
  return seen;
}

/// That a run's progress events are at least `events`, from 0 to 1, never falling.
void expectProgressInOrder(const std::vector<double>& seen, std::size_t events)
{
  ASSERT_GE(seen.size(), events);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  for (std::size_t k = 1; k < seen.size(); ++k)
  {
    ASSERT_GE(seen[k], seen[k - 1]) << "event " << k;
  }
}

// With interreflection on a two-sided surface, the hidden side's rays and shading and then the
// bounces follow the seen side's, in order.
TEST(AbortAndProgress, ProgressMovesThroughBothSidesAndTheBouncesInOrder)
{
  vtkSmartPointer<vtkPolyData> bunny = app::readMesh(data + "meshes/bunny_zipper.ply");
  vtkNew<vtkLocalReflectanceFilter> filter;
  Scene scene = studioWithOcclusion(16);
  for (NamedLight& light : scene.lights) // rays for each side
  {
    light.shadows = castsShadows(light.source);
  }
  scene.material.twoSided = true;
  scene.interreflection = Interreflection{ 2, { 16, true } };
  setUp(filter, bunny, scene);
  expectProgressInOrder(progressOf(filter), 6);
}

TEST(AbortAndProgress, ProgressMovesThroughTheNormalsTheRaysAndTheShadingInOrder)
{
  vtkSmartPointer<vtkPolyData> bunny = app::readMesh(data + "meshes/bunny_zipper.ply");
  vtkNew<vtkLocalReflectanceFilter> filter;
  setUp(filter, bunny, studioWithOcclusion(64));
  const std::vector<double> seen = progressOf(filter);
  expectProgressInOrder(seen, 4);
  // The normals end at 5%; the rays' tenths lie between it and 80%; the shading follows.
  auto countWithin = [&](double low, double high)
  { return std::count_if(seen.begin(), seen.end(), [&](double p) { return p > low && p < high; }); };
  EXPECT_GE(countWithin(0.05, 0.8), 5) << "the rays' blocks";
  EXPECT_NE(std::find(seen.begin(), seen.end(), 0.05), seen.end()) << "the normals' end";
  EXPECT_NE(std::find(seen.begin(), seen.end(), 0.8), seen.end()) << "the rays' end";
}
