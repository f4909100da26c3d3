#include "ShadeLabVtkScene.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkProperty.h"

#include <stdexcept>

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

// A light is on when its Switch is positive (vtkOpenGLRenderer tests status > 0.0).
bool isOn(vtkLight* light)
{
  return light->GetSwitch() > 0;
}

// vtkOpenGLRenderer::UpdateLights (VTK 9.1) picks the shader's "lighting complexity" with this
// loop: 1 for a lone headlight, 2 for directional lights, 3 with a positional one. Note that it
// looks at every light, switched on or not, when it moves on to the general shaders.
int lightingComplexity(vtkLightCollection* lights)
{
  int complexity = 0;
  int switchedOn = 0;
  vtkCollectionSimpleIterator it;
  vtkLight* light;
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it));)
  {
    if (isOn(light))
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
  if (switchedOn == 0)
  {
    // The renderer appends a headlight and, on that render, takes the complexity from the
    // collection's first light: 1 if it is a headlight (or the new one), else 2.
    lights->InitTraversal(it);
    vtkLight* first = lights->GetNextLight(it);
    return first == nullptr || first->GetLightType() == VTK_LIGHT_TYPE_HEADLIGHT ? 1 : 2;
  }
  return complexity;
}

glm::dvec3 transformedPoint(vtkMatrix4x4* matrix, const double p[3])
{
  if (!matrix)
  {
    return toGlm(p);
  }
  double h[4] = { p[0], p[1], p[2], 1.0 };
  matrix->MultiplyPoint(h, h);
  return { h[0] / h[3], h[1] / h[3], h[2] / h[3] };
}

// World-space position and focal point of a light, as the renderer places it with
// LightFollowCamera on (the default): vtkRenderer::UpdateLightsGeometryToFollowCamera moves a
// headlight to the camera and gives a camera light the camera's light transform (camera at
// (0,0,1), focal point at the origin, units of the camera distance); then
// vtkLight::GetTransformedPosition applies the light's transform matrix.
void placeLight(vtkLight* light, vtkCamera* camera, glm::dvec3& position, glm::dvec3& focalPoint)
{
  double p[3], f[3];
  light->GetPosition(p);
  light->GetFocalPoint(f);
  vtkMatrix4x4* matrix = light->GetTransformMatrix();
  if (light->LightTypeIsHeadlight())
  {
    camera->GetPosition(p);
    camera->GetFocalPoint(f);
  }
  else if (light->LightTypeIsCameraLight())
  {
    matrix = camera->GetCameraLightTransformMatrix();
  }
  position = transformedPoint(matrix, p);
  focalPoint = transformedPoint(matrix, f);
}

/// shinesFromPosition: VTK's PBR shader at complexity 1 or 3, which takes every light's
/// direction from its position (docs/vtk-renderer.md section 11.4).
LightSource lightSource(vtkLight* light, vtkCamera* camera, bool shinesFromPosition)
{
  // vtkOpenGLRenderer::UpdateLightingUniforms: light colour = DiffuseColor * Intensity.
  const Rgb color = toGlm(light->GetDiffuseColor());
  const double intensity = light->GetIntensity();
  glm::dvec3 position, focalPoint;
  placeLight(light, camera, position, focalPoint);
  if (!light->GetPositional() && shinesFromPosition && !light->LightTypeIsHeadlight())
  {
    // A directional light shining from its position, unattenuated (a headlight's position is
    // the camera's: placeHeadlightsAtTheCamera, below).
    return PointLight{ position, color, intensity, Attenuation{ AttenuationModel::None } };
  }
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

/// vtkOpenGLPolyDataMapper::SetPropertyShaderParameters: each colour times its coefficient.
Material phongMaterial(vtkProperty* property)
{
  Material m;
  m.ka = scaledColor(property->GetAmbient(), property->GetAmbientColor());
  m.kd = scaledColor(property->GetDiffuse(), property->GetDiffuseColor());
  m.ks = scaledColor(property->GetSpecular(), property->GetSpecularColor());
  m.shininess = property->GetSpecularPower();
  return m;
}

/// The PBR shader's uniforms (docs/vtk-renderer.md section 11.1): the albedo is Diffuse x
/// DiffuseColor; a coat, anisotropy or textures, which it would add, are refused.
Material microfacetMaterial(vtkProperty* property)
{
  if (property->GetCoatStrength() > 0 || property->GetAnisotropy() > 0)
  {
    throw std::invalid_argument("the vtk_pbr model has no coat layer or anisotropy: set the property's "
                                "CoatStrength and Anisotropy to 0");
  }
  if (property->GetNumberOfTextures() > 0)
  {
    throw std::invalid_argument("the vtk_pbr model reads no textures (base colour, ORM, emissive, normal): remove "
                                "the property's textures");
  }
  Material m;
  m.ka = m.kd = m.ks = Rgb(0.0);
  m.microfacet.baseColor = scaledColor(property->GetDiffuse(), property->GetDiffuseColor());
  m.microfacet.metallic = property->GetMetallic();
  m.microfacet.roughness = property->GetRoughness();
  m.microfacet.baseIor = property->GetBaseIOR();
  m.microfacet.edgeTint = toGlm(property->GetEdgeTint());
  return m;
}
}

Scene sceneFromVtk(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera)
{
  Scene scene;
  const bool pbr = property->GetInterpolation() == VTK_PBR;
  scene.model = pbr ? ShadingModel::VtkPbr : ShadingModel::VtkOpenGL2;
  scene.viewer.position = toGlm(camera->GetPosition());
  scene.viewer.focalPoint = toGlm(camera->GetFocalPoint());
  scene.material = pbr ? microfacetMaterial(property) : phongMaterial(property);
  scene.materialGiven = true; // the property's, which a mesh's own materials do not replace

  const int complexity = lightingComplexity(lights);

  vtkCollectionSimpleIterator it;
  vtkLight* light;
  int index = 0;
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it)); ++index)
  {
    if (isOn(light))
    {
      scene.lights.push_back({ "light" + std::to_string(index), lightSource(light, camera, pbr && complexity != 2) });
    }
  }
  if (scene.lights.empty())
  {
    scene.lights.push_back({ "headlight", Headlight{} });
  }
  scene.vtkLoneHeadlight = complexity == 1;
  if (pbr)
  {
    placeHeadlightsAtTheCamera(scene, complexity != 2);
  }
  return scene;
}
}
