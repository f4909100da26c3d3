#pragma once
// One camera, one property and several light sets built from VTK's own objects, shared by
// the tests that compare the vtk model with VTK's shader formulas and with real renders.
#include "FilterRun.h"
#include "TestMeshes.h"

#include "ShadeLabVtkScene.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"

#include <glm/vec3.hpp>

#include <functional>

#include <gtest/gtest.h>

namespace shadelab::testing
{
/// The sphere the light sets are aimed at (off-centre, so that the camera sees it obliquely).
constexpr glm::dvec3 litSphereCentre{ 0.3, -0.2, 0.1 };
constexpr double litSphereRadius = 1.2;

class VtkLightSets : public ::testing::Test
{
protected:
  void SetUp() override
  {
    camera->SetPosition(0.5, 2.0, 6.0);
    camera->SetFocalPoint(0.2, 0.0, 0.0);
    camera->SetViewUp(0.0, 1.0, 0.2);
    camera->OrthogonalizeViewUp();
    property->SetAmbient(0.1);
    property->SetAmbientColor(1.0, 0.5, 0.25);
    property->SetDiffuse(0.7);
    property->SetDiffuseColor(0.2, 0.4, 0.9);
    property->SetSpecular(0.5);
    property->SetSpecularColor(1.0, 1.0, 0.5);
    property->SetSpecularPower(20.0);
  }

  vtkSmartPointer<vtkLight> addLight(int type, glm::dvec3 position, glm::dvec3 focalPoint)
  {
    auto light = vtkSmartPointer<vtkLight>::New();
    light->SetLightType(type);
    light->SetPosition(position.x, position.y, position.z);
    light->SetFocalPoint(focalPoint.x, focalPoint.y, focalPoint.z);
    lights->AddItem(light);
    return light;
  }

  /// VTK's "lighting complexity 1": one headlight and nothing else.
  void addLoneHeadlight()
  {
    auto head = addLight(VTK_LIGHT_TYPE_HEADLIGHT, { 0, 0, 1 }, { 0, 0, 0 });
    head->SetDiffuseColor(1.0, 0.9, 0.8);
    head->SetIntensity(0.8);
  }

  /// Complexity 2: directional lights of every type.
  void addLightKit()
  {
    addLight(VTK_LIGHT_TYPE_HEADLIGHT, { 0, 0, 1 }, { 0, 0, 0 })->SetIntensity(0.5);
    auto key = addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { 3, 4, 2 }, { 0, 0, 0 });
    key->SetDiffuseColor(1.0, 0.8, 0.6);
    addLight(VTK_LIGHT_TYPE_CAMERA_LIGHT, { 1, 0, 1 }, { 0, 0, 0 })->SetIntensity(0.3);
  }

  /// Complexity 2 by a quirk: VTK 9.1's UpdateLights checks the light type outside its
  /// "switched on" test, so a switched-off scene light after the headlight selects the
  /// general shader.
  void addHeadlightAndSwitchedOffSceneLight()
  {
    addLight(VTK_LIGHT_TYPE_HEADLIGHT, { 0, 0, 1 }, { 0, 0, 0 });
    addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { 3, 4, 2 }, { 0, 0, 0 })->SwitchOff();
  }

  /// Complexity 3: a spot, a point light, a directional light and a positional camera light
  /// (whose position is in units of the camera distance, so a wrong camera-light transform
  /// moves it and changes its attenuation and cone).
  void addPositionalLights()
  {
    auto spot = addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { 2.5, 3.0, 2.0 }, litSphereCentre);
    spot->PositionalOn();
    spot->SetConeAngle(25);
    spot->SetExponent(3);
    spot->SetAttenuationValues(1.0, 0.2, 0.05);
    spot->SetIntensity(2.0);
    auto bulb = addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { -2.0, 1.0, 3.0 }, { 0, 0, 0 });
    bulb->PositionalOn();
    bulb->SetConeAngle(90); // no cone
    bulb->SetAttenuationValues(0.5, 0.0, 0.3);
    bulb->SetDiffuseColor(0.6, 0.8, 1.0);
    addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { 0, 5, 0 }, { 0, 0, 0 })->SetIntensity(0.4);
    auto lamp = addLight(VTK_LIGHT_TYPE_CAMERA_LIGHT, { 0.2, 0.3, 0.8 }, { 0.0, 0.0, 0.0 });
    lamp->PositionalOn();
    lamp->SetConeAngle(20);
    lamp->SetAttenuationValues(1.0, 0.1, 0.02);
  }

  /// The lit sphere at this resolution, and ShadeLab's float64 total for it under the vtk
  /// model of these lights, property and camera. Checks that the scene takes the
  /// lone-headlight shader exactly when lone is true. colorBy (if given) adds arrays to the
  /// sphere and takes the scene's material from them, as a mapper's scalar colouring does.
  std::pair<vtkSmartPointer<vtkPolyData>, vtkSmartPointer<vtkDataArray>> shadeLitSphere(
    int resolution, bool lone, const std::function<void(vtkPolyData*, Scene&)>& colorBy = {})
  {
    Scene scene = sceneFromVtk(lights, property, camera);
    EXPECT_EQ(scene.vtkLoneHeadlight, lone);
    vtkSmartPointer<vtkPolyData> sphere = exactSphere(resolution, litSphereCentre, litSphereRadius);
    if (colorBy)
    {
      colorBy(sphere, scene);
    }
    vtkSmartPointer<vtkDataArray> total =
      shadeWithFilter(sphere, scene, { "total" })->GetPointData()->GetArray("total");
    EXPECT_NE(total, nullptr);
    return { sphere, total };
  }

  vtkNew<vtkLightCollection> lights;
  vtkNew<vtkProperty> property;
  vtkNew<vtkCamera> camera;
};
}
