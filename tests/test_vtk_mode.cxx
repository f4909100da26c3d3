// The VtkOpenGL2 and VtkPbr models against VTK 9.1's shader formulas (vtkOpenGLPolyDataMapper::
// ReplaceShaderLight, vtkOpenGLRenderer::UpdateLightingUniforms) evaluated by hand here, in
// view coordinates as the shader does, for several light sets built from vtkLight,
// vtkProperty and vtkCamera. ShadeLab works in world coordinates; the two must agree.
#include "TestMeshes.h"
#include "VtkLightSets.h"

#include "ShadeLabMaterialArrays.h"
#include "ShadeLabVtkScene.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <optional>
#include <tuple>

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

/// The camera's view transform (a rotation plus a translation, so that its normal matrix is its
/// rotation).
class ViewTransform
{
public:
  explicit ViewTransform(vtkCamera* camera)
  {
    vtkMatrix4x4* view = camera->GetModelViewTransformMatrix();
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        view_[r][c] = view->GetElement(r, c);
      }
    }
  }
  dvec3 point(const dvec3& p) const { return transform(p, 1.0); }
  dvec3 direction(const dvec3& v) const { return transform(v, 0.0); }

private:
  dvec3 transform(const dvec3& v, double w) const
  {
    dvec3 out;
    for (int r = 0; r < 3; ++r)
    {
      out[r] = view_[r][0] * v.x + view_[r][1] * v.y + view_[r][2] * v.z + view_[r][3] * w;
    }
    return out;
  }
  double view_[4][4];
};

/// The lights that are on, as the shader receives them: what vtkRenderer::
/// UpdateLightsGeometryToFollowCamera does to them before a render, then UpdateLightingUniforms'
/// transformed position and focal point in view coordinates.
std::vector<ShaderLight> shaderLightsOf(vtkLightCollection* lights, vtkCamera* camera, const ViewTransform& view)
{
  std::vector<ShaderLight> result;
  vtkCollectionSimpleIterator it;
  vtkLight* light;
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it));)
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    if (light->LightTypeIsHeadlight())
    {
      light->SetPosition(camera->GetPosition());
      light->SetFocalPoint(camera->GetFocalPoint());
    }
    else if (light->LightTypeIsCameraLight())
    {
      light->SetTransformMatrix(camera->GetCameraLightTransformMatrix());
    }
    const dvec3 position = view.point(toGlm(light->GetTransformedPosition()));
    const dvec3 focal = view.point(toGlm(light->GetTransformedFocalPoint()));
    result.push_back({ light->GetIntensity() * toGlm(light->GetDiffuseColor()), glm::normalize(focal - position),
      position, toGlm(light->GetAttenuationValues()), light->GetPositional() != 0, light->GetExponent(),
      light->GetConeAngle() });
  }
  return result;
}

/// VTK 9.1's fragment shader for lighting complexity 1, 2 or 3, transcribed.
class ShaderReference
{
public:
  ShaderReference(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera, int complexity)
    : complexity_(complexity)
    , view_(camera)
    , lights_(shaderLightsOf(lights, camera, view_))
  {
    ambient_ = property->GetAmbient() * toGlm(property->GetAmbientColor());
    diffuse_ = property->GetDiffuse() * toGlm(property->GetDiffuseColor());
    specular_ = property->GetSpecular() * toGlm(property->GetSpecularColor());
    power_ = property->GetSpecularPower();
  }

  dvec3 total(const dvec3& worldPoint, const dvec3& worldNormal) const
  {
    const dvec3 vertexVC = view_.point(worldPoint);
    dvec3 normal = glm::normalize(view_.direction(worldNormal));
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
  int complexity_;
  ViewTransform view_;
  std::vector<ShaderLight> lights_;
  dvec3 ambient_, diffuse_, specular_;
  double power_;
};

/// One light's terms at a vertex in VTK 9.1's PBR shader (docs/vtk-renderer.md section 11).
struct PbrLightTerms
{
  double d = 0, v = 0;
  dvec3 f{ 0 }, diffuse{ 0 }, specular{ 0 };
};

/// VTK 9.1's PBR fragment shader without image-based lighting (vtkOpenGLPolyDataMapper::
/// ReplaceShaderLight and glsl/vtkPBRFunctions.glsl at v9.1.0), transcribed in view coordinates
/// with VTK's own arrangement of every formula.
class PbrShaderReference
{
public:
  PbrShaderReference(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera, int complexity)
    : complexity_(complexity)
    , view_(camera)
    , lights_(shaderLightsOf(lights, camera, view_))
  {
    diffuse_ = property->GetDiffuse();
    albedo_ = diffuse_ * toGlm(property->GetDiffuseColor());
    metallic_ = property->GetMetallic();
    roughness_ = property->GetRoughness();
    const double ior = property->GetBaseIOR();
    baseF0_ = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    edgeTint_ = toGlm(property->GetEdgeTint());
  }

  /// Each light's terms at the vertex, in the order of the lights that are on. Where the vertex
  /// has a scalar colour (bytes over 255), the shader's diffuseColor, and so its albedo, is
  /// Diffuse x the colour; where it has its own metallic factor or roughness, they are the ones
  /// the shader of a part whose property has them (a glTF file's parts) computes with.
  std::vector<PbrLightTerms> termsOfVertex(const dvec3& worldPoint, const dvec3& worldNormal,
    const unsigned char* colour = nullptr, std::optional<double> metallic = std::nullopt,
    std::optional<double> roughness = std::nullopt) const
  {
    return terms(worldPoint, worldNormal, colour ? diffuse_ * dvec3(colour[0], colour[1], colour[2]) / 255.0 : albedo_,
      metallic.value_or(metallic_), roughness.value_or(roughness_));
  }

private:
  std::vector<PbrLightTerms> terms(
    const dvec3& worldPoint, const dvec3& worldNormal, const dvec3& albedo, double metallic, double roughness) const
  {
    const dvec3 f0 = (1 - metallic) * dvec3(baseF0_) + metallic * albedo;
    const double f90 = std::clamp(glm::dot(f0, dvec3(50.0 * 0.33)), 0.0, 1.0);
    const dvec3 grazing = (1 - metallic) * dvec3(f90) + metallic * edgeTint_;
    const dvec3 vertexVC = view_.point(worldPoint);
    dvec3 n = glm::normalize(view_.direction(worldNormal));
    n = glm::dot(n, -vertexVC) < 0 ? -n : n; // gl_FrontFacing, per vertex
    const dvec3 v = glm::normalize(-vertexVC);
    const double nDotV = std::clamp(glm::dot(n, v), 1e-5, 1.0);
    std::vector<PbrLightTerms> result;
    for (const ShaderLight& light : lights_)
    {
      double attenuation = 1.0;
      dvec3 l = -light.directionVC;
      if (complexity_ == 1)
      {
        l = v; // "L = V = H for headlights"
      }
      else if (complexity_ == 3)
      {
        const dvec3 toLight = light.positionVC - vertexVC;
        const double distanceVC = glm::length(toLight);
        l = glm::normalize(toLight);
        if (light.positional)
        {
          attenuation = 1.0 /
            (light.attenuation.x + light.attenuation.y * distanceVC + light.attenuation.z * distanceVC * distanceVC);
          if (light.coneAngle < 90.0)
          {
            const double coneDot = glm::dot(-l, light.directionVC);
            attenuation =
              coneDot >= std::cos(light.coneAngle * M_PI / 180.0) ? attenuation * std::pow(coneDot, light.exponent) : 0;
          }
        }
      }
      const dvec3 h = glm::normalize(v + l);
      const double hDotL = std::clamp(glm::dot(h, l), 1e-5, 1.0);
      const double nDotL = std::clamp(glm::dot(n, l), 1e-5, 1.0);
      const double nDotH = std::clamp(glm::dot(n, h), 1e-5, 1.0);
      const double pi = 3.14159265359;
      const double a = roughness * roughness, a2 = a * a;
      const double d = (nDotH * a2 - nDotH) * nDotH + 1.0;
      PbrLightTerms t;
      t.d = a2 / (pi * d * d);
      const double r2 = roughness * roughness;
      t.v = 0.5 /
        (nDotL * std::sqrt(r2 + nDotV * (nDotV - r2 * nDotV)) + nDotV * std::sqrt(r2 + nDotL * (nDotL - r2 * nDotL)));
      t.f = f0 + (grazing - f0) * std::pow(1.0 - hDotL, 5.0);
      const dvec3 radiance = light.color * attenuation;
      t.diffuse = radiance * ((1.0 - metallic) * (1.0 - t.f) * albedo * 0.31830988618) * nDotL;
      t.specular = radiance * (t.d * t.v * t.f) * nDotL;
      result.push_back(t);
    }
    return result;
  }

  int complexity_;
  ViewTransform view_;
  std::vector<ShaderLight> lights_;
  dvec3 albedo_, edgeTint_;
  double diffuse_, metallic_, roughness_, baseF0_;
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

class VtkPbrMode : public shadelab::testing::VtkLightSets
{
protected:
  /// A PBR property (a metal-dielectric mix with an edge tint and a base IOR of 1.8) on the
  /// off-centre sphere: every light's D, V, F, diffuse and specular arrays and the total against
  /// the shader's formulas, evaluated by hand in view coordinates.
  /// With colours: each vertex's scalar colour (8-bit RGB, VTK's scalar colouring) is its base
  /// colour, times the property's Diffuse (0.9 here), as `shadelab shade --color-by` takes it.
  /// Bright colours vary each channel on its own; dark ones on a nearly clear dielectric (base
  /// IOR 1.05, metallic 0.3) put F0's sum below 1/16.5 at most vertices, so that F90 too is each
  /// vertex's own.
  /// With OwnMetallicAndRoughness, bright colours, and each vertex's metallic factor (0 to 1)
  /// and roughness (0.1 to 1) from float arrays too, as a glTF file's parts give them; with
  /// OwnMetallic or OwnRoughness, the property's colour and that one array alone.
  enum class Colours
  {
    None,
    Bright,
    Dark,
    OwnMetallicAndRoughness,
    OwnMetallic,
    OwnRoughness
  };
  void expectShaderTerms(int complexity, Colours withColours = Colours::None)
  {
    property->SetInterpolationToPBR();
    property->SetMetallic(withColours == Colours::Dark ? 0.3 : 0.4);
    property->SetRoughness(0.35);
    property->SetBaseIOR(withColours == Colours::Dark ? 1.05 : 1.8);
    property->SetEdgeTint(0.9, 0.6, 0.3);
    shadelab::Scene scene = shadelab::sceneFromVtk(lights, property, camera);
    ASSERT_EQ(scene.model, shadelab::ShadingModel::VtkPbr);
    vtkSmartPointer<vtkPolyData> sphere =
      shadelab::testing::exactSphere(60, shadelab::testing::litSphereCentre, shadelab::testing::litSphereRadius);
    const bool ownMetallic = withColours == Colours::OwnMetallicAndRoughness || withColours == Colours::OwnMetallic;
    const bool ownRoughness = withColours == Colours::OwnMetallicAndRoughness || withColours == Colours::OwnRoughness;
    const bool scalarColours =
      withColours != Colours::None && withColours != Colours::OwnMetallic && withColours != Colours::OwnRoughness;
    if (scalarColours)
    {
      // Under scalar colouring the shader ignores DiffuseColor; the scene's base colour, a grey
      // here, stands for Diffuse (colorMaterialBy takes its largest component).
      property->SetDiffuse(0.9);
      property->SetDiffuseColor(1.0, 1.0, 1.0);
      scene = shadelab::sceneFromVtk(lights, property, camera);
      vtkNew<vtkUnsignedCharArray> colours;
      colours->SetName("colours");
      colours->SetNumberOfComponents(3);
      for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
      {
        withColours != Colours::Dark
          ? colours->InsertNextTuple3(double((37 * i) % 256), double((91 * i + 40) % 256), double((13 * i) % 17))
          : colours->InsertNextTuple3(double(i % 21), double((3 * i) % 21), double((7 * i) % 21));
      }
      sphere->GetPointData()->AddArray(colours);
      shadelab::colorMaterialBy(scene, "colours", "");
    }
    for (const auto& [name, coefficient, low, wanted] :
      { std::tuple{ "metal", shadelab::MaterialCoefficient::Metallic, 0.0, ownMetallic },
        std::tuple{ "rough", shadelab::MaterialCoefficient::Roughness, 0.1, ownRoughness } })
    {
      if (wanted)
      {
        vtkNew<vtkDoubleArray> values;
        values->SetName(name);
        for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
        {
          values->InsertNextValue(low + (1 - low) * double((29 * i + (low > 0 ? 11 : 0)) % 97) / 96.0);
        }
        sphere->GetPointData()->AddArray(values);
        shadelab::ArrayCoefficient source;
        source.array = name;
        scene.material.arrays[coefficient] = source;
        // The array's scale, 1.
        (coefficient == shadelab::MaterialCoefficient::Metallic ? scene.material.microfacet.metallic
                                                                : scene.material.microfacet.roughness) = 1.0;
      }
    }
    vtkSmartPointer<vtkPolyData> shaded = shadelab::testing::shadeWithFilter(sphere, scene, { "all" });
    const PbrShaderReference shader(lights, property, camera, complexity);
    vtkPointData* arrays = shaded->GetPointData();
    vtkDataArray* normals = arrays->GetNormals();
    auto expectClose = [](double got, double want, const std::string& what)
    { EXPECT_NEAR(got, want, 1e-12 * std::max(1.0, std::abs(want))) << what; };
    double largest = 0;
    for (vtkIdType i = 0; i < shaded->GetNumberOfPoints(); ++i)
    {
      const dvec3 point = toGlm(shaded->GetPoint(i)), normal = toGlm(normals->GetTuple3(i));
      auto* colours = vtkUnsignedCharArray::SafeDownCast(arrays->GetArray("colours")); // passed through
      const std::vector<PbrLightTerms> want =
        shader.termsOfVertex(point, normal, scalarColours ? colours->GetPointer(3 * i) : nullptr,
          ownMetallic ? std::optional(arrays->GetArray("metal")->GetComponent(i, 0)) : std::nullopt,
          ownRoughness ? std::optional(arrays->GetArray("rough")->GetComponent(i, 0)) : std::nullopt);
      ASSERT_EQ(want.size(), scene.lights.size());
      dvec3 total(0);
      for (std::size_t l = 0; l < want.size(); ++l)
      {
        const std::string light = scene.lights[l].name;
        const std::string at = " at vertex " + std::to_string(i);
        expectClose(arrays->GetArray((light + "_ggx_d").c_str())->GetComponent(i, 0), want[l].d, light + " D" + at);
        expectClose(arrays->GetArray((light + "_smith_v").c_str())->GetComponent(i, 0), want[l].v, light + " V" + at);
        for (int c = 0; c < 3; ++c)
        {
          const std::string channel = " channel " + std::to_string(c) + at;
          expectClose(
            arrays->GetArray((light + "_schlick_f").c_str())->GetComponent(i, c), want[l].f[c], light + " F" + channel);
          expectClose(arrays->GetArray((light + "_diffuse").c_str())->GetComponent(i, c), want[l].diffuse[c],
            light + " diffuse" + channel);
          expectClose(arrays->GetArray((light + "_specular").c_str())->GetComponent(i, c), want[l].specular[c],
            light + " specular" + channel);
        }
        total += want[l].diffuse + want[l].specular;
      }
      for (int c = 0; c < 3; ++c)
      {
        expectClose(arrays->GetArray("total")->GetComponent(i, c), total[c], "total at vertex " + std::to_string(i));
        EXPECT_EQ(arrays->GetArray("ambient")->GetComponent(i, c), 0.0);
        largest = std::max(largest, total[c]);
      }
    }
    EXPECT_GT(largest, withColours == Colours::Dark ? 0.05 : 0.3); // the light set really lights the sphere
  }
};

TEST_F(VtkPbrMode, LoneHeadlightAtTheEye)
{
  addLoneHeadlight();
  expectShaderTerms(1);
}

TEST_F(VtkPbrMode, LightKitOfDirectionalLights)
{
  addLightKit();
  expectShaderTerms(2);
}

TEST_F(VtkPbrMode, PositionalLightsWithTheDirectionalOneShiningFromItsPosition)
{
  addPositionalLights();
  expectShaderTerms(3);
}

TEST_F(VtkPbrMode, AHeadlightBesideAPointLightShinesFromTheCamera)
{
  addLight(VTK_LIGHT_TYPE_HEADLIGHT, { 0, 0, 1 }, { 0, 0, 0 })->SetIntensity(0.7);
  auto bulb = addLight(VTK_LIGHT_TYPE_SCENE_LIGHT, { -2.0, 1.0, 3.0 }, { 0, 0, 0 });
  bulb->PositionalOn();
  bulb->SetConeAngle(90);
  expectShaderTerms(3);
}

// VTK's scalar colouring under PBR: each vertex's colour is its albedo (times Diffuse), and so
// moves its F0, F90 and diffuse part, under every kind of light at once.
TEST_F(VtkPbrMode, ScalarColoursAreEachVertexsBaseColour)
{
  addPositionalLights();
  expectShaderTerms(3, Colours::Bright);
}

// Dark colours on a nearly clear dielectric: F0's channels sum below 1/16.5, where VTK's F90
// falls below 1 ("specular occlusion"), vertex by vertex.
TEST_F(VtkPbrMode, DarkScalarColoursDarkenEachVertexsGrazingReflectance)
{
  addLightKit();
  expectShaderTerms(2, Colours::Dark);
}

// A glTF file's parts: each vertex's metallic factor and roughness are its own, as well as its
// colour, and move D, V, F and the diffuse part's 1 - m, under every kind of light at once.
TEST_F(VtkPbrMode, MetallicAndRoughnessFromArraysAreEachVertexsOwn)
{
  addPositionalLights();
  expectShaderTerms(3, Colours::OwnMetallicAndRoughness);
}

// Each alone, with the property's colour: F0 from the property's base colour and the vertex's
// metallic factor; D and V from the vertex's roughness.
TEST_F(VtkPbrMode, AMetallicFactorFromAnArrayAlone)
{
  addLightKit();
  expectShaderTerms(2, Colours::OwnMetallic);
}

TEST_F(VtkPbrMode, ARoughnessFromAnArrayAlone)
{
  addLoneHeadlight();
  expectShaderTerms(1, Colours::OwnRoughness);
}

TEST_F(VtkPbrMode, NoLightSwitchedOnMeansVtksHeadlightAtTheCamera)
{
  // The headlight vtkRenderer creates, alone (complexity 1): VTK's PBR shader puts it at the eye.
  property->SetInterpolationToPBR();
  const shadelab::Scene scene = shadelab::sceneFromVtk(lights, property, camera);
  ASSERT_EQ(scene.lights.size(), 1u);
  const auto* head = std::get_if<shadelab::PointLight>(&scene.lights[0].source);
  ASSERT_NE(head, nullptr);
  EXPECT_EQ(head->position, toGlm(camera->GetPosition()));
  EXPECT_EQ(head->attenuation.model, shadelab::AttenuationModel::None);
  EXPECT_EQ(head->color, shadelab::Rgb(1.0));
  EXPECT_EQ(head->intensity, 1.0);
  EXPECT_TRUE(scene.vtkLoneHeadlight);
}
}
