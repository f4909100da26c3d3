// The VtkOpenGL2 model against VTK 9.1's shader formulas (vtkOpenGLPolyDataMapper::
// ReplaceShaderLight, vtkOpenGLRenderer::UpdateLightingUniforms) evaluated by hand here, in
// view coordinates as the shader does, for several light sets built from vtkLight,
// vtkProperty and vtkCamera. ShadeLab works in world coordinates; the two must agree.
#include "TestMeshes.h"
#include "VtkLightSets.h"

#include "ShadeLabVtkScene.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkProperty.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace
{
using glm::dvec3;

dvec3 toGlm(const double* v)
{
  return { v[0], v[1], v[2] };
}

/// The shader's inputs for one light, as UpdateLightingUniforms sends them (view coords).
struct ShaderLight
{
  dvec3 color;
  dvec3 directionVC; // normalized FocalPoint - Position
  dvec3 positionVC;
  dvec3 attenuation;
  bool positional;
  double exponent, coneAngle;
};

/// VTK 9.1's fragment shader for lighting complexity 1, 2 or 3, transcribed.
class ShaderReference
{
public:
  ShaderReference(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera, int complexity)
    : complexity_(complexity)
  {
    vtkMatrix4x4* view = camera->GetModelViewTransformMatrix();
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        view_[r][c] = view->GetElement(r, c);
      }
    }
    ambient_ = property->GetAmbient() * toGlm(property->GetAmbientColor());
    diffuse_ = property->GetDiffuse() * toGlm(property->GetDiffuseColor());
    specular_ = property->GetSpecular() * toGlm(property->GetSpecularColor());
    power_ = property->GetSpecularPower();
    vtkCollectionSimpleIterator it;
    vtkLight* light;
    for (lights->InitTraversal(it); (light = lights->GetNextLight(it));)
    {
      if (!light->GetSwitch())
      {
        continue;
      }
      // What vtkRenderer::UpdateLightsGeometryToFollowCamera does to the lights before a
      // render; then UpdateLightingUniforms takes the transformed position and focal point
      // into view coordinates.
      if (light->LightTypeIsHeadlight())
      {
        light->SetPosition(camera->GetPosition());
        light->SetFocalPoint(camera->GetFocalPoint());
      }
      else if (light->LightTypeIsCameraLight())
      {
        light->SetTransformMatrix(camera->GetCameraLightTransformMatrix());
      }
      const dvec3 position = point(toGlm(light->GetTransformedPosition()));
      const dvec3 focal = point(toGlm(light->GetTransformedFocalPoint()));
      lights_.push_back({ light->GetIntensity() * toGlm(light->GetDiffuseColor()), glm::normalize(focal - position),
        position, toGlm(light->GetAttenuationValues()), light->GetPositional() != 0, light->GetExponent(),
        light->GetConeAngle() });
    }
  }

  dvec3 total(const dvec3& worldPoint, const dvec3& worldNormal) const
  {
    const dvec3 vertexVC = point(worldPoint);
    dvec3 normal = glm::normalize(direction(worldNormal));
    // gl_FrontFacing, per vertex: the face is a back face when its normal points away from
    // the camera (the origin of view coordinates).
    if (glm::dot(normal, -vertexVC) < 0)
    {
      normal = -normal;
    }
    if (complexity_ == 1)
    {
      const double df = std::max(0.0, normal.z);
      const double sf = std::pow(df, power_);
      return ambient_ + df * diffuse_ * lights_[0].color + sf * specular_ * lights_[0].color;
    }
    dvec3 diffuse(0), specular(0);
    for (const ShaderLight& light : lights_)
    {
      double attenuation = 1.0;
      dvec3 vertLightDirectionVC = light.directionVC;
      if (complexity_ == 3 && light.positional)
      {
        vertLightDirectionVC = vertexVC - light.positionVC;
        const double distanceVC = glm::length(vertLightDirectionVC);
        vertLightDirectionVC = glm::normalize(vertLightDirectionVC);
        attenuation = 1.0 /
          (light.attenuation.x + light.attenuation.y * distanceVC + light.attenuation.z * distanceVC * distanceVC);
        if (light.coneAngle < 90.0)
        {
          const double coneDot = glm::dot(vertLightDirectionVC, light.directionVC);
          attenuation =
            coneDot >= std::cos(light.coneAngle * M_PI / 180.0) ? attenuation * std::pow(coneDot, light.exponent) : 0.0;
        }
      }
      const double df = std::max(0.0, attenuation * glm::dot(normal, -vertLightDirectionVC));
      diffuse += df * light.color;
      const double sign = df > 0 ? 1.0 : 0.0;
      const double sf = sign * attenuation *
        std::pow(
          std::max(0.0, glm::dot(glm::reflect(vertLightDirectionVC, normal), glm::normalize(-vertexVC))), power_);
      specular += sf * light.color;
    }
    return ambient_ + diffuse * diffuse_ + specular * specular_;
  }

private:
  dvec3 point(const dvec3& p) const { return transform(p, 1.0); }
  // The view matrix is a rotation plus a translation, so its normal matrix is its rotation.
  dvec3 direction(const dvec3& v) const { return transform(v, 0.0); }
  dvec3 transform(const dvec3& v, double w) const
  {
    dvec3 out;
    for (int r = 0; r < 3; ++r)
    {
      out[r] = view_[r][0] * v.x + view_[r][1] * v.y + view_[r][2] * v.z + view_[r][3] * w;
    }
    return out;
  }

  int complexity_;
  double view_[4][4];
  dvec3 ambient_, diffuse_, specular_;
  double power_;
  std::vector<ShaderLight> lights_;
};

class VtkRendererMode : public shadelab::testing::VtkLightSets
{
protected:
  /// Shades an off-centre sphere (so that some vertices face away from the camera and are
  /// flipped) and compares the total at every vertex with the shader reference.
  void expectShaderResult(int complexity)
  {
    const auto [sphere, total] = shadeLitSphere(60, complexity == 1);
    ASSERT_NE(total, nullptr);
    const ShaderReference shader(lights, property, camera, complexity);
    vtkDataArray* normals = sphere->GetPointData()->GetNormals();
    double largest = 0;
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
    {
      const dvec3 want = shader.total(toGlm(sphere->GetPoint(i)), toGlm(normals->GetTuple3(i)));
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(total->GetComponent(i, c), want[c], 1e-12) << "vertex " << i;
        largest = std::max(largest, want[c]);
      }
    }
    EXPECT_GT(largest, 0.3); // the light set really lights the sphere
  }
};

TEST_F(VtkRendererMode, LoneHeadlight)
{
  addLoneHeadlight();
  expectShaderResult(1);
}

TEST_F(VtkRendererMode, NoLightSwitchedOnMeansVtksAutomaticHeadlight)
{
  // vtkOpenGLRenderer::UpdateLights appends a headlight, then takes the shader from the
  // collection's first light: the lone-headlight shader only if that one is a headlight.
  auto expectAutomaticHeadlight = [&](bool lone)
  {
    const shadelab::Scene scene = shadelab::sceneFromVtk(lights, property, camera);
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<shadelab::Headlight>(scene.lights[0].source));
    EXPECT_EQ(scene.vtkLoneHeadlight, lone);
  };
  expectAutomaticHeadlight(true); // empty collection
  addLight(VTK_LIGHT_TYPE_HEADLIGHT, { 0, 0, 1 }, { 0, 0, 0 })->SwitchOff();
  expectAutomaticHeadlight(true);
  lights->RemoveAllItems();
  addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { 1, 1, 1 }, { 0, 0, 0 })->SwitchOff();
  expectAutomaticHeadlight(false);
}

TEST_F(VtkRendererMode, LightKitOfDirectionalLights)
{
  addLightKit();
  expectShaderResult(2);
}

TEST_F(VtkRendererMode, SwitchedOffSceneLightStillEndsTheLoneHeadlightShader)
{
  addHeadlightAndSwitchedOffSceneLight();
  expectShaderResult(2);
}

TEST_F(VtkRendererMode, PositionalSpotAndPointLights)
{
  addPositionalLights();
  expectShaderResult(3);
}
}
