#include "ShadeLabVtkScene.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkProperty.h"

namespace shadelab
{
namespace
{
glm::dvec3 toGlm(const double* v)
{
  return { v[0], v[1], v[2] };
}

Rgb scaledColor(double coefficient, const double* color)
{
  return coefficient * toGlm(color);
}

// vtkOpenGLRenderer::UpdateLights (VTK 9.1) picks the single-headlight shader ("lighting
// complexity 1") with this loop. Note that it looks at every light, switched on or not,
// when it moves on to the general shaders.
bool usesLoneHeadlightShader(vtkLightCollection* lights)
{
  int complexity = 0;
  int switchedOn = 0;
  vtkCollectionSimpleIterator it;
  vtkLight* light;
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it));)
  {
    if (light->GetSwitch())
    {
      ++switchedOn;
      complexity = complexity == 0 ? 1 : complexity;
    }
    if (complexity == 1 && (switchedOn > 1 || light->GetLightType() != VTK_LIGHT_TYPE_HEADLIGHT))
    {
      complexity = 2;
    }
    if (complexity < 3 && light->GetPositional())
    {
      complexity = 3;
    }
  }
  return switchedOn == 0 || complexity == 1; // none on: VTK adds a lone headlight
}

// World-space position and focal point of a light, as the renderer places it: a headlight
// sits at the camera, a camera light is given in camera coordinates, a scene light in world
// coordinates (with its own TransformMatrix, if any).
void placeLight(vtkLight* light, vtkCamera* camera, glm::dvec3& position, glm::dvec3& focalPoint)
{
  if (light->LightTypeIsHeadlight())
  {
    position = toGlm(camera->GetPosition());
    focalPoint = toGlm(camera->GetFocalPoint());
    return;
  }
  if (light->LightTypeIsCameraLight())
  {
    vtkNew<vtkMatrix4x4> cameraToWorld;
    vtkMatrix4x4::Invert(camera->GetModelViewTransformMatrix(), cameraToWorld);
    double p[4] = { 0, 0, 0, 1 };
    light->GetPosition(p);
    cameraToWorld->MultiplyPoint(p, p);
    double f[4] = { 0, 0, 0, 1 };
    light->GetFocalPoint(f);
    cameraToWorld->MultiplyPoint(f, f);
    position = { p[0] / p[3], p[1] / p[3], p[2] / p[3] };
    focalPoint = { f[0] / f[3], f[1] / f[3], f[2] / f[3] };
    return;
  }
  position = toGlm(light->GetTransformedPosition());
  focalPoint = toGlm(light->GetTransformedFocalPoint());
}

LightSource lightSource(vtkLight* light, vtkCamera* camera)
{
  // vtkOpenGLRenderer::UpdateLightingUniforms: light colour = DiffuseColor * Intensity.
  const Rgb color = toGlm(light->GetDiffuseColor());
  const double intensity = light->GetIntensity();
  glm::dvec3 position, focalPoint;
  placeLight(light, camera, position, focalPoint);
  if (!light->GetPositional())
  {
    if (light->LightTypeIsHeadlight())
    {
      return Headlight{ color, intensity };
    }
    return DistantLight{ focalPoint - position, color, intensity, false };
  }
  Attenuation attenuation;
  attenuation.model = AttenuationModel::ConstantLinearQuadratic;
  const double* k = light->GetAttenuationValues();
  attenuation.constant = k[0];
  attenuation.linear = k[1];
  attenuation.quadratic = k[2];
  if (k[0] > 0)
  {
    attenuation.minDistance = 0.0;
  }
  if (light->GetConeAngle() >= 90.0)
  {
    return PointLight{ position, color, intensity, attenuation };
  }
  SpotCone cone;
  cone.model = ConeModel::Vtk;
  cone.halfAngleDegrees = light->GetConeAngle();
  cone.exponent = light->GetExponent();
  return SpotLight{ position, focalPoint - position, color, intensity, attenuation, cone };
}
}

Scene sceneFromVtk(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera)
{
  Scene scene;
  scene.model = ShadingModel::VtkOpenGL2;
  scene.viewer.position = toGlm(camera->GetPosition());
  scene.viewer.focalPoint = toGlm(camera->GetFocalPoint());

  // vtkOpenGLPolyDataMapper::SetPropertyShaderParameters: each colour times its coefficient.
  scene.material.ka = scaledColor(property->GetAmbient(), property->GetAmbientColor());
  scene.material.kd = scaledColor(property->GetDiffuse(), property->GetDiffuseColor());
  scene.material.ks = scaledColor(property->GetSpecular(), property->GetSpecularColor());
  scene.material.shininess = property->GetSpecularPower();

  vtkCollectionSimpleIterator it;
  vtkLight* light;
  int index = 0;
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it)); ++index)
  {
    if (light->GetSwitch())
    {
      scene.lights.push_back({ "light" + std::to_string(index), lightSource(light, camera) });
    }
  }
  if (scene.lights.empty())
  {
    scene.lights.push_back({ "headlight", Headlight{} });
  }
  scene.vtkLoneHeadlight = usesLoneHeadlightShader(lights);
  return scene;
}
}
