// The vtk_pbr model's microfacet terms (Microfacet.h) against closed forms computed another way,
// at the angles and roughnesses where they break, and the model's scene rules.
#include "Microfacet.h"
#include "SceneFileErrors.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include <tuple>

namespace
{
using namespace shadelab;
using shadelab::testing::sceneFileErrorOf;

constexpr double pi = 3.14159265358979323846;

/// GGX's D written from the angle theta between n and h: alpha^2 / (pi (alpha^2 cos^2 + sin^2)^2).
double ggxFromAngle(double theta, double roughness)
{
  const double alpha2 = std::pow(roughness, 4.0);
  const double c = std::cos(theta), s = std::sin(theta);
  return alpha2 / (pi * std::pow(alpha2 * c * c + s * s, 2.0));
}

TEST(Microfacet, GgxDistributionIsTheAngleFormAndIntegratesToOneOverTheProjectedHemisphere)
{
  for (const double roughness : { 0.2, 0.5, 0.8, 1.0 })
  {
    for (const double theta : { 0.0, 0.1, 0.7, 1.2, 1.5 })
    {
      // vtkPi is the shader's 3.14159265359, 2e-12 from pi.
      EXPECT_NEAR(ggxDistribution(std::cos(theta), roughness) / ggxFromAngle(theta, roughness), 1.0, 1e-11)
        << "roughness " << roughness << " theta " << theta;
    }
    // A distribution of normals: the integral of D (n.h) over the hemisphere of h is 1. The
    // midpoint rule in cos^2, where D is a smooth function (1 / (a + b x)^2).
    const int steps = 200000;
    double integral = 0;
    for (int i = 0; i < steps; ++i)
    {
      const double cos2 = (i + 0.5) / steps;
      // d omega = 2 pi sin d theta; (n.h) sin d theta = d(cos^2) / 2.
      integral += ggxDistribution(std::sqrt(cos2), roughness) * pi / steps;
    }
    EXPECT_NEAR(integral, 1.0, 1e-6) << "roughness " << roughness;
  }
  // Roughness 1: a uniform distribution, 1/pi (to the shader's pi) at every angle.
  EXPECT_NEAR(ggxDistribution(0.3, 1.0), 1 / pi, 1e-12);
  EXPECT_NEAR(ggxDistribution(1e-5, 1.0), 1 / pi, 1e-12);
}

TEST(Microfacet, GgxDistributionNarrowsToItsPeakAsTheRoughnessFalls)
{
  // At n.h = 1 the peak is 1 / (pi r^4); one degree off, a small roughness has almost nothing.
  for (const double roughness : { 0.03, 0.1, 0.3 })
  {
    EXPECT_NEAR(ggxDistribution(1.0, roughness) * pi * std::pow(roughness, 4.0), 1.0, 1e-10);
  }
  const double oneDegree = pi / 180;
  EXPECT_LT(ggxDistribution(std::cos(oneDegree), 0.03), 1e-3 * ggxDistribution(1.0, 0.03));
  // Where it breaks in float32. VTK's arrangement, (n.h alpha^2 - n.h) n.h + 1, cancels digits
  // near n.h = 1; ShadeLab's, (1 - n.h)(1 + n.h) + (n.h)^2 alpha^2, does not: at one float32 n.h
  // a tenth of a degree off the peak at roughness 0.03, it gives that cosine's D to float32's
  // rounding, and VTK's form does not.
  const float c = float(std::cos(0.1 * oneDegree));
  const double ofThatCosine = ggxDistribution(double(c), 0.03);
  const float alpha2 = std::pow(0.03f, 4.0f);
  const float vtkBase = (c * alpha2 - c) * c + 1.0f;
  const float vtkForm = alpha2 / (vtkPi<float> * vtkBase * vtkBase);
  EXPECT_NEAR(ggxDistribution(c, 0.03f) / ofThatCosine, 1.0, 1e-5);
  EXPECT_GT(std::abs(vtkForm / ofThatCosine - 1.0), 1e-3);
  // What no arrangement saves: n.h itself rounded to float32. Near the peak D then errs by up
  // to float32DistributionError, the bound the scene's check uses (a percent at roughness 0.07).
  for (const double roughness : { 0.07, 0.1, 0.2 })
  {
    double worst = 0;
    for (int i = 0; i <= 20000; ++i)
    {
      const double cosine = std::cos(i * 1e-4 * oneDegree);
      const double rounded = double(float(cosine));
      worst = std::max(worst, std::abs(ggxDistribution(rounded, roughness) / ggxDistribution(cosine, roughness) - 1));
    }
    EXPECT_LE(worst, float32DistributionError(roughness)) << "roughness " << roughness;
    EXPECT_GE(worst, float32DistributionError(roughness) / 4) << "roughness " << roughness;
  }
  EXPECT_NEAR(float32DistributionError(0.07), 0.01, 1e-3);
}

/// Heitz 2014, eq. 99 with eq. 72: the height-correlated G2 = 1 / (1 + Lambda(v) + Lambda(l)),
/// Lambda(mu) = (-1 + sqrt(1 + alpha^2 tan^2)) / 2, for GGX of width alpha.
double heitzCorrelatedG2(double nDotV, double nDotL, double alpha)
{
  auto lambda = [alpha](double mu) { return (-1 + std::sqrt(1 + alpha * alpha * (1 - mu * mu) / (mu * mu))) / 2; };
  return 1 / (1 + lambda(nDotV) + lambda(nDotL));
}

TEST(Microfacet, SmithVisibilityIsHeitzsCorrelatedMaskingWithAlphaEqualToTheRoughness)
{
  for (const double roughness : { 0.05, 0.35, 0.7, 1.0 })
  {
    for (const double nDotV : { 1e-5, 0.05, 0.4, 0.9, 1.0 })
    {
      for (const double nDotL : { 1e-5, 0.2, 0.75, 1.0 })
      {
        // VTK's V = G2 / (4 (n.s)(n.v)) with alpha = roughness (not roughness^2, as its D).
        const double heitz = heitzCorrelatedG2(nDotV, nDotL, roughness) / (4 * nDotV * nDotL);
        EXPECT_NEAR(smithCorrelatedVisibility(nDotV, nDotL, roughness) / heitz, 1.0, 1e-9)
          << "r " << roughness << " n.v " << nDotV << " n.s " << nDotL;
        EXPECT_EQ(smithCorrelatedVisibility(nDotV, nDotL, roughness),
          smithCorrelatedVisibility(nDotL, nDotV, roughness)); // reciprocity
      }
    }
  }
  // Roughness 1: 0.5 / (n.s + n.v); roughness 0: no masking, G2 = 1.
  EXPECT_DOUBLE_EQ(smithCorrelatedVisibility(0.3, 0.6, 1.0), 0.5 / 0.9);
  EXPECT_DOUBLE_EQ(smithCorrelatedVisibility(0.3, 0.6, 0.0), 0.25 / (0.3 * 0.6));
  // At grazing view the shader's clamp keeps V finite: with n.v at 1e-5 and n.s = 1, V n.s is
  // 0.5 / (sqrt(r^2 + 1e-10 (1 - r^2)) + 1e-5) at roughness r.
  const double r = 0.35;
  const double grazing = vtkClampedCosine(0.0);
  EXPECT_EQ(grazing, 1e-5);
  EXPECT_NEAR(smithCorrelatedVisibility(grazing, 1.0, r), 0.5 / (std::sqrt(r * r + 1e-10 * (1 - r * r)) + 1e-5), 1e-12);
}

TEST(Microfacet, TheSpecularBoundBoundsDVTimesTheCosineOverEveryClampedAngle)
{
  // The scene's overflow check bounds each light's peak by microfacetSpecularBound: D V (n.s)
  // (F <= 1) over a grid of the clamped cosines, at roughnesses from smooth to rough.
  for (const double roughness : { 0.07, 0.3, 1.0 })
  {
    double largest = 0;
    for (const double nDotH : { 1e-5, 0.5, 0.9, 0.999, 1.0 })
    {
      for (const double nDotV : { 1e-5, 1e-3, 0.1, 0.5, 1.0 })
      {
        for (const double nDotL : { 1e-5, 1e-3, 0.1, 0.5, 1.0 })
        {
          largest = std::max(
            largest, ggxDistribution(nDotH, roughness) * smithCorrelatedVisibility(nDotV, nDotL, roughness) * nDotL);
        }
      }
    }
    EXPECT_LE(largest, microfacetSpecularBound(roughness)) << "roughness " << roughness;
    // Safe, and loose by less than 1e5: it pairs D's peak with V (n.s) at the grazing view's
    // 0.25 / 1e-5, where the grid's largest has V (n.s) = 0.5 / r at n.v = 1e-5, n.s = 1.
    EXPECT_GT(largest, 1e-5 * microfacetSpecularBound(roughness)) << "roughness " << roughness;
  }
}

TEST(Microfacet, SchlickFresnelRunsFromF0AtNormalIncidenceToF90AtGrazing)
{
  MicrofacetMaterial dielectric;
  const Rgb f0 = reflectanceAtNormalIncidence(dielectric);
  EXPECT_NEAR(f0.x, 0.04, 1e-15); // ((1.5 - 1) / (1.5 + 1))^2
  EXPECT_EQ(reflectanceAtGrazingIncidence(dielectric, f0), Rgb(1.0));
  EXPECT_EQ(schlickFresnel(0.04, 1.0, 1.0), 0.04);
  EXPECT_NEAR(schlickFresnel(0.04, 1.0, vtkClampedCosine(0.0)), 1.0 - 0.96 * 5e-5, 1e-9);
  EXPECT_NEAR(schlickFresnel(0.04, 1.0, 0.5), 0.04 + 0.96 / 32, 1e-15);

  // A metal: F0 is its base colour, F90 its edge tint.
  MicrofacetMaterial metal;
  metal.metallic = 1.0;
  metal.baseColor = { 0.9, 0.6, 0.2 };
  metal.edgeTint = { 1.0, 0.8, 0.5 };
  EXPECT_EQ(reflectanceAtNormalIncidence(metal), metal.baseColor);
  EXPECT_EQ(reflectanceAtGrazingIncidence(metal, metal.baseColor), metal.edgeTint);

  // VTK's "specular occlusion": an F0 whose channels sum below 1/16.5 has F90 = 16.5 x that sum.
  MicrofacetMaterial lowIndex;
  lowIndex.baseIor = 1.2;
  const Rgb low = reflectanceAtNormalIncidence(lowIndex);
  EXPECT_NEAR(low.x, std::pow(0.2 / 2.2, 2.0), 1e-15);
  EXPECT_NEAR(reflectanceAtGrazingIncidence(lowIndex, low).x, 16.5 * 3 * low.x, 1e-12);
}

const std::string pbrViewer = R"("model": "vtk_pbr", "viewer": { "position": [0, 0, 3], "focal_point": [0, 0, 0] })";

TEST(Microfacet, SceneFileGivesVtksPbrMaterialAndRefusesWhatItsShaderLacks)
{
  const Scene scene = parseScene("{ " + pbrViewer +
      R"(, "material": { "base_color": [0.5, 0.4, 0.3], "metallic": 0.25, "roughness": 0.6, "base_ior": 1.6,
        "edge_tint": [1, 0.9, 0.8] }, "lights": [] })",
    "scene.json");
  EXPECT_EQ(scene.model, ShadingModel::VtkPbr);
  EXPECT_EQ(scene.material.microfacet.baseColor, Rgb(0.5, 0.4, 0.3));
  EXPECT_EQ(scene.material.microfacet.metallic, 0.25);
  EXPECT_EQ(scene.material.microfacet.roughness, 0.6);
  EXPECT_EQ(scene.material.microfacet.baseIor, 1.6);
  EXPECT_EQ(scene.material.microfacet.edgeTint, Rgb(1, 0.9, 0.8));
  // No light: vtkRenderer's automatic headlight, alone, so the shader's light at the eye.
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.vtkLoneHeadlight);

  auto errorWith = [](const std::string& rest) { return sceneFileErrorOf("{ " + pbrViewer + ", " + rest + " }"); };
  EXPECT_EQ(errorWith(R"("material": { "roughness": 0 }, "lights": [])"),
    "scene.json: /material/roughness: must be a number above 0 and at most 1 (at 0, VTK's GGX distribution is 0/0 "
    "in the mirror direction)");
  EXPECT_EQ(errorWith(R"("material": { "metallic": 1.5 }, "lights": [])"),
    "scene.json: /material/metallic: must be a number from 0 to 1");
  EXPECT_EQ(errorWith(R"("material": { "base_ior": 0.9 }, "lights": [])"),
    "scene.json: /material/base_ior: must be a number >= 1");
  EXPECT_EQ(errorWith(R"("material": { "kd": [1, 1, 1] }, "lights": [])"),
    "scene.json: /material/kd: unknown field; allowed here: base_color, metallic, roughness, base_ior, edge_tint");
  EXPECT_EQ(errorWith(R"("lights": [ { "type": "ambient" } ])"),
    "scene.json: /lights/0/type: VTK's renderer has no ambient light, and its PBR shader no ambient term: use the "
    "vtk or lecture model");
  EXPECT_EQ(errorWith(R"("lights": [ { "type": "sphere", "center": [0, 0, 2], "radius": 0.1 } ])"),
    "scene.json: /lights/0/type: the vtk_pbr model has VTK's punctual lights only (its image-based lighting is not "
    "reproduced): use the lecture model");
  EXPECT_EQ(errorWith(R"("lights": [], "ambient_occlusion": { "rays": 16 })"),
    "scene.json: /ambient_occlusion: VTK's PBR shader has no ambient term for the occlusion to darken: use the vtk "
    "or lecture model");
  EXPECT_EQ(errorWith(R"("lights": [], "interreflection": { "bounces": 1 })"),
    "scene.json: /interreflection: the vtk_pbr model does not compute interreflection: use the lecture model");
  EXPECT_EQ(errorWith(R"("lights": [], "spectral": {})"),
    "scene.json: /spectral: the vtk_pbr model is VTK's renderer, whose colours are RGB: use the lecture model");
  EXPECT_EQ(errorWith(R"("lights": [ { "type": "point", "position": [0, 0, 2] } ])"),
    "scene.json: /lights/0/attenuation: the vtk_pbr model has only vtkLight's constant-linear-quadratic "
    "attenuation (or none)");
  EXPECT_EQ(errorWith(R"("material": { "base_color": [1.2, 0.5, 0.5] }, "lights": [])"),
    "scene.json: /material/base_color: components must be numbers from 0 to 1");
  EXPECT_EQ(errorWith(R"("lights": [ { "type": "distant", "direction": [0, 0, -1] },
      { "type": "point", "position": [0, 0, 2], "attenuation": { "model": "none" } } ])"),
    "scene.json: /lights/0/type: beside a point or spot light, VTK's PBR shader makes a directional light shine "
    "from its position, which a distant light has not: give it as a point light with \"attenuation\": {\"model\": "
    "\"none\"}");
  EXPECT_EQ(sceneFileErrorOf(R"({ "model": "vtk_pbr", "viewer": { "direction": [0, 0, -1] }, "lights": [] })"),
    "scene.json: /viewer/position: the vtk_pbr model needs a camera position (VTK's renderer always has a local "
    "viewer)");
}

// A base colour from an array is VTK's scalar colouring under PBR: kd's array in the material,
// its scale (the property's Diffuse) the base colour's bound. The model has no other coefficient
// to take from an array.
TEST(Microfacet, ABaseColourFromAnArrayIsKdsArray)
{
  const Scene scene = parseScene("{ " + pbrViewer +
      R"(, "material": { "base_color": { "array": "RGB", "scale": 0.7 }, "metallic": 0.5 }, "lights": [] })",
    "scene.json");
  const std::optional<ArrayCoefficient>& source = scene.material.arrays[MaterialCoefficient::Diffuse];
  ASSERT_TRUE(source.has_value());
  EXPECT_EQ(source->array, "RGB");
  EXPECT_EQ(source->scale, 0.7);
  EXPECT_EQ(scene.material.microfacet.baseColor, Rgb(0.7));
  EXPECT_FALSE(scene.material.arrays[MaterialCoefficient::Ambient].has_value());
  EXPECT_EQ(sceneFileErrorOf(
              "{ " + pbrViewer + R"(, "material": { "base_color": { "array": "RGB", "scale": -1 } }, "lights": [] })"),
    "scene.json: /material/base_color/scale: must be a number >= 0");
  EXPECT_EQ(sceneFileErrorOf(
              "{ " + pbrViewer + R"(, "material": { "base_color": { "array": "RGB", "scale": 1.5 } }, "lights": [] })"),
    "scene.json: /material/base_color/scale: must be a number from 0 to 1 (the property's Diffuse)");
  Scene withSpecularArray = scene;
  withSpecularArray.material.arrays[MaterialCoefficient::Specular] = ArrayCoefficient{ "RGB" };
  const std::vector<SceneProblem> problems = sceneProblems(withSpecularArray);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].path, "/material");
  EXPECT_EQ(problems[0].message,
    "the vtk_pbr model takes its base colour, metallic factor and roughness from arrays (VTK's scalar colouring, a "
    "glTF file's parts): it has no ka, ks or shininess");
}

TEST(Microfacet, TheMetallicFactorAndRoughnessFromArraysAreScaledByTheirNumbers)
{
  const Scene scene = parseScene("{ " + pbrViewer +
      R"(, "material": { "metallic": { "array": "m", "scale": 0.5 }, "roughness": { "array": "r" } }, "lights": [] })",
    "scene.json");
  for (const auto& [coefficient, name, scale] :
    { std::tuple{ MaterialCoefficient::Metallic, "m", 0.5 }, std::tuple{ MaterialCoefficient::Roughness, "r", 1.0 } })
  {
    const std::optional<ArrayCoefficient>& source = scene.material.arrays[coefficient];
    ASSERT_TRUE(source.has_value()) << name;
    EXPECT_EQ(source->array, name);
    EXPECT_EQ(source->scale, scale);
  }
  EXPECT_EQ(scene.material.microfacet.metallic, 0.5);
  EXPECT_EQ(scene.material.microfacet.roughness, 1.0);
  EXPECT_FALSE(scene.material.arrays[MaterialCoefficient::Diffuse].has_value());
  auto errorOf = [](const std::string& material)
  { return sceneFileErrorOf("{ " + pbrViewer + R"(, "material": )" + material + R"(, "lights": [] })"); };
  EXPECT_EQ(errorOf(R"({ "metallic": { "array": "m", "scale": 1.5 } })"),
    "scene.json: /material/metallic/scale: must be a number from 0 to 1");
  EXPECT_EQ(errorOf(R"({ "roughness": { "array": "r", "scale": 0 } })"),
    "scene.json: /material/roughness/scale: must be a number above 0 and at most 1 (at 0, VTK's GGX distribution is "
    "0/0 in the mirror direction)");
  EXPECT_EQ(errorOf(R"({ "roughness": { "array": "r", "clamp": true } })"),
    "scene.json: /material/roughness/clamp: a roughness cannot be clamped: (0, 1] has no value nearest to 0 or below; "
    "correct the array's values");
  // One number per vertex: no encoding nor colour map.
  EXPECT_EQ(errorOf(R"({ "metallic": { "array": "m", "colormap": "rainbow" } })"),
    "scene.json: /material/metallic/colormap: unknown field; allowed here: array, scale, clamp");
}

TEST(Microfacet, AHeadlightShinesFromTheCameraWhereVtksPbrShaderPutsIt)
{
  // Alone (lighting complexity 1) and beside a point light (complexity 3), VTK's PBR shader
  // takes the headlight's direction from the camera's position: an unattenuated point light
  // there. Beside distant lights alone (complexity 2) it stays distant.
  auto headlightIn = [](const std::string& otherLights)
  {
    const Scene scene =
      parseScene("{ " + pbrViewer + R"(, "lights": [ { "name": "head", "type": "headlight" })" + otherLights + " ] }",
        "scene.json");
    return scene.lights.at(0).source;
  };
  for (const std::string& others : { std::string(),
         std::string(R"(, { "type": "point", "position": [1, 2, 2], "attenuation": { "model": "none" } })") })
  {
    const LightSource head = headlightIn(others);
    ASSERT_TRUE(std::holds_alternative<PointLight>(head)) << others;
    EXPECT_EQ(std::get<PointLight>(head).position, glm::dvec3(0, 0, 3));
    EXPECT_EQ(std::get<PointLight>(head).attenuation.model, AttenuationModel::None);
  }
  EXPECT_TRUE(std::holds_alternative<Headlight>(headlightIn(R"(, { "type": "distant", "direction": [0, -1, 0] })")));
}
}
