// Scene files: what a valid file means, and the exact message for each kind of bad input.
#include "ArrayCatalog.h"
#include "DefaultLightKit.h"
#include "EnvironmentMap.h"
#include "NearestName.h"
#include "SceneFile.h"
#include "SceneFileErrors.h"
#include "SceneSource.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace
{
using namespace shadelab;

std::string errorOf(const std::string& text)
{
  return shadelab::testing::sceneFileErrorOf(text);
}

TEST(SceneFile, ReadsEveryLightType)
{
  const Scene scene = parseScene(R"({
    "viewer": { "position": [0, 0, 5], "focal_point": [0, 0, 0] },
    "material": { "kd": [0.5, 0.4, 0.3], "ks": 0.2, "shininess": 12, "specular": "phong", "two_sided": true },
    "lights": [
      { "name": "sun", "type": "distant", "direction": [0, 0, -2], "intensity_from_length": true },
      { "name": "head", "type": "headlight", "color": 0.5 },
      { "name": "bulb", "type": "point", "position": [1, 2, 3], "intensity": 4,
        "attenuation": { "model": "vtk", "constant": 1, "linear": 0.5 }, "min_distance": 0.1 },
      { "name": "cone", "type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0],
        "attenuation": { "model": "gltf_range", "range": 20 },
        "cone": { "model": "gltf", "inner_angle": 5, "outer_angle": 25 } },
      { "type": "ambient", "intensity": 0.1 }
    ]
  })",
    "scene.json");
  ASSERT_EQ(scene.lights.size(), 5u);
  EXPECT_EQ(scene.model, ShadingModel::Lecture);
  EXPECT_EQ(scene.material.kd, Rgb(0.5, 0.4, 0.3));
  EXPECT_EQ(scene.material.ka, Rgb(0.5, 0.4, 0.3)); // docs/formulas.md section 7: ka defaults to kd
  EXPECT_EQ(scene.material.ks, Rgb(0.2));
  EXPECT_EQ(scene.material.specular, SpecularModel::Phong);
  EXPECT_TRUE(scene.material.twoSided);

  const auto& sun = std::get<DistantLight>(scene.lights[0].source);
  EXPECT_TRUE(sun.intensityFromLength);
  EXPECT_EQ(std::get<Headlight>(scene.lights[1].source).color, Rgb(0.5));
  const auto& bulb = std::get<PointLight>(scene.lights[2].source);
  EXPECT_EQ(bulb.attenuation.model, AttenuationModel::ConstantLinearQuadratic);
  EXPECT_EQ(bulb.attenuation.linear, 0.5);
  EXPECT_EQ(bulb.attenuation.quadratic, 0.0);
  EXPECT_EQ(bulb.attenuation.minDistance, 0.1);
  const auto& cone = std::get<SpotLight>(scene.lights[3].source);
  EXPECT_EQ(cone.attenuation.range, 20.0);
  EXPECT_EQ(cone.cone.model, ConeModel::Gltf);
  EXPECT_EQ(cone.cone.outerAngleDegrees, 25.0);
  EXPECT_EQ(scene.lights[4].name, "ambient4"); // unnamed: type and index
}

TEST(SceneFile, EveryBundledSceneIsValid)
{
  int scenes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(shadelab::testing::sourcePath("data/scenes")))
  {
    if (entry.path().extension() != ".json")
    {
      continue; // a scene's mesh, its materials and textures (data/scenes/still_life)
    }
    SCOPED_TRACE(entry.path().string());
    const Scene scene = readSceneFile(entry.path().string());
    EXPECT_FALSE(scene.lights.empty());
    EXPECT_TRUE(sceneProblems(scene, Precision::Float32).empty());
    ++scenes;
  }
  EXPECT_GE(scenes, 5);
}

TEST(SceneFile, VtkModelUsesVtkPropertyDefaultsAndDetectsTheLoneHeadlight)
{
  const Scene scene = parseScene(R"({ "model": "vtk", "viewer": { "position": [0, 0, 1], "focal_point": [0, 0, 0] },
    "lights": [ { "type": "headlight" } ] })",
    "scene.json");
  EXPECT_EQ(scene.model, ShadingModel::VtkOpenGL2);
  EXPECT_TRUE(scene.vtkLoneHeadlight);
  EXPECT_EQ(scene.material.ka, Rgb(0.0));
  EXPECT_EQ(scene.material.kd, Rgb(1.0));
  EXPECT_EQ(scene.material.ks, Rgb(0.0));
  EXPECT_EQ(scene.material.shininess, 1.0);

  const Scene none = parseScene(R"({ "model": "vtk", "viewer": { "position": [0, 0, 1], "focal_point": [0, 0, 0] },
    "lights": [] })",
    "scene.json");
  ASSERT_EQ(none.lights.size(), 1u); // VTK's automatic headlight
  EXPECT_TRUE(none.vtkLoneHeadlight);
}

TEST(SceneFile, MalformedJson)
{
  EXPECT_EQ(errorOf("{ \"lights\": [ }"),
    "scene.json: not valid JSON: parse error at line 1, column 15: syntax error while parsing "
    "value - unexpected '}'; expected '[', '{', or a literal");
}

TEST(SceneFile, NumberTooLargeForADouble)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "ambient", "intensity": 1e400 } ] })"),
    "scene.json: not valid JSON: number overflow parsing '1e400'");
}

TEST(SceneFile, UnknownLightType)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "distant", "direction": [0, 0, 1] }, { "type": "laser" } ] })"),
    "scene.json: /lights/1/type: \"laser\" is not one of \"distant\", \"headlight\", \"point\", "
    "\"spot\", \"ambient\", \"polygon\", \"rectangle\", \"disk\", \"sphere\", \"environment\"");
}

TEST(SceneFile, NegativeField)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "intensity": -2 } ] })"),
    "scene.json: /lights/0/intensity: must be a number >= 0");
  EXPECT_EQ(errorOf(R"({ "material": { "shininess": -1 }, "lights": [] })"),
    "scene.json: /material/shininess: must be a number >= 0");
}

TEST(SceneFile, MissingField)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "distant" } ] })"), "scene.json: /lights/0/direction: missing");
  EXPECT_EQ(errorOf(R"({ "material": {} })"), "scene.json: /lights: missing");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "name": "x" } ] })"), "scene.json: /lights/0/type: missing");
}

TEST(SceneFile, TheNearestNameIsOneWithinAThirdOfTheLettersAndUnique)
{
  EXPECT_EQ(editDistance("tolerence", "tolerance"), 1u);
  EXPECT_EQ(editDistance("materail", "material"), 1u); // a swap of neighbours counts once
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(nearestName("intesity", { "position", "intensity", "name" }), "intensity");
  EXPECT_EQ(nearestName("colour", { "color", "intensity" }), "color");
  EXPECT_EQ(nearestName("hue", { "color", "intensity" }), ""); // nothing within a third of its letters
  EXPECT_EQ(nearestName("ks", { "ka", "kd" }), "");            // as near to both
  EXPECT_EQ(nearestName("shinyness", { "shininess", "specular" }), "shininess");
}

TEST(SceneFile, WrongTypesAndUnknownFields)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "distant", "direction": [0, 1] } ] })"),
    "scene.json: /lights/0/direction: must be an array of 3 numbers, got [0,1]");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "cone": {} } ] })"),
    "scene.json: /lights/0/cone: unknown field; allowed here: name, type, color, spectrum, intensity, shadows, "
    "position, attenuation, min_distance");
  EXPECT_EQ(errorOf(R"({ "lights": [], "materail": {} })"),
    "scene.json: /materail: unknown field; did you mean \"material\"? allowed here: model, frame, viewer, material, "
    "lights, shadows, self_shadowing, ambient_occlusion, interreflection, spectral");
  EXPECT_EQ(errorOf(R"({ "lights": [], "colour": {} })"),
    "scene.json: /colour: unknown field; allowed here: model, frame, viewer, material, lights, shadows, "
    "self_shadowing, ambient_occlusion, interreflection, spectral");
  // Fields of another model are errors too, not silently ignored.
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "point", "position": [0, 0, 1],
      "attenuation": { "model": "inverse", "range": 2 } } ] })"),
    "scene.json: /lights/0/attenuation/range: unknown field; allowed here: model");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "spot", "position": [0, 0, 1], "direction": [0, 0, -1],
      "cone": { "model": "vtk", "angle": 20, "outer_angle": 30 } } ] })"),
    "scene.json: /lights/0/cone/outer_angle: unknown field; allowed here: model, angle, exponent");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "attenuation": "quadratic" } ] })"),
    "scene.json: /lights/0/attenuation: \"quadratic\" is not one of \"none\", \"inverse\", "
    "\"inverse_square\", \"vtk\", \"gltf_range\"");
}

TEST(SceneFile, RulesOfTheModel)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "min_distance": 0 } ] })"),
    "scene.json: /lights/0/min_distance: must be > 0: this attenuation is infinite at distance 0");
  EXPECT_EQ(errorOf(R"({ "model": "vtk", "viewer": { "position": [0, 0, 1] }, "lights": [ { "type": "ambient" } ] })"),
    "scene.json: /lights/0/type: VTK's renderer has no ambient light: with the vtk model, put the "
    "ambient colour in material.ka");
  EXPECT_EQ(errorOf(R"({ "model": "vtk", "lights": [] })"),
    "scene.json: /viewer/position: the vtk model needs a camera position (VTK's renderer always "
    "has a local viewer)");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "headlight" } ], "viewer": { "position": [0, 0, 1] } })"),
    "scene.json: /lights/0: a headlight shines along the viewer's line of sight: give the viewer a focal_point");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "name": "a", "type": "ambient" }, { "name": "a", "type": "ambient" } ] })"),
    "scene.json: /lights/1/name: another light is already named 'a'");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "name": "2nd", "type": "ambient" } ] })"),
    "scene.json: /lights/0/name: '2nd' is not a valid light name: use letters, digits and _, "
    "starting with a letter");
}

TEST(SceneFile, MaterialFromTheMeshsArrays)
{
  const Scene scene = parseScene(R"({
    "material": { "kd": { "array": "Colors" }, "ks": { "array": "gloss", "encoding": "linear", "scale": 0.5, "clamp": true },
                  "shininess": { "array": "eta", "scale": 200 } },
    "lights": [ { "type": "distant", "direction": [0, 0, -1] } ] })",
    "scene.json");
  const MaterialArrays& arrays = scene.material.arrays;
  ASSERT_TRUE(arrays[MaterialCoefficient::Diffuse] && arrays[MaterialCoefficient::Ambient]);
  // docs/formulas.md section 7: ka follows kd, its array included.
  EXPECT_EQ(arrays[MaterialCoefficient::Ambient]->array, "Colors");
  EXPECT_FALSE(arrays[MaterialCoefficient::Diffuse]->encoding); // the default for the array's type
  EXPECT_EQ(arrays[MaterialCoefficient::Specular]->encoding, ArrayEncoding::Linear);
  EXPECT_TRUE(arrays[MaterialCoefficient::Specular]->clamp);
  // The numbers are the largest the arrays can give: their scales.
  EXPECT_EQ(scene.material.kd, Rgb(1.0));
  EXPECT_EQ(scene.material.ks, Rgb(0.5));
  EXPECT_EQ(scene.material.shininess, 200.0);
  EXPECT_TRUE(arrays.clamps());

  const Scene field =
    parseScene(R"({ "material": { "kd": { "array": "T", "colormap": "cool to warm", "range": [250, 400] } },
    "lights": [] })",
      "scene.json");
  EXPECT_EQ(field.material.arrays[MaterialCoefficient::Diffuse]->colorMap, "cool to warm");
  EXPECT_EQ(*field.material.arrays[MaterialCoefficient::Diffuse]->range, (std::array<double, 2>{ 250, 400 }));
}

TEST(SceneFile, MaterialArrayErrors)
{
  EXPECT_EQ(errorOf(R"({ "material": { "kd": { "array": "" } }, "lights": [] })"),
    "scene.json: /material/kd/array: must name a point-data array of the mesh");
  EXPECT_EQ(errorOf(R"({ "material": { "kd": { "array": "T", "colormap": "jet" } }, "lights": [] })"),
    "scene.json: /material/kd/colormap: \"jet\" is not one of \"cool to warm\", \"rainbow\", \"grayscale\"");
  EXPECT_EQ(errorOf(R"({ "material": { "kd": { "array": "T", "range": [0, 1] } }, "lights": [] })"),
    "scene.json: /material/kd/range: a range is the colour map's: give \"colormap\" too, or leave the range out");
  EXPECT_EQ(
    errorOf(R"({ "material": { "kd": { "array": "T", "colormap": "rainbow", "range": [1, 1] } }, "lights": [] })"),
    "scene.json: /material/kd/range: must be [low, high] with low < high, got [1,1]");
  EXPECT_EQ(errorOf(R"({ "material": { "kd": { "array": "T", "encoding": "gamma" } }, "lights": [] })"),
    "scene.json: /material/kd/encoding: \"gamma\" is not one of \"srgb\", \"linear\"");
  EXPECT_EQ(errorOf(R"({ "material": { "shininess": { "array": "eta", "colormap": "rainbow" } }, "lights": [] })"),
    "scene.json: /material/shininess/colormap: unknown field; allowed here: array, scale, clamp");
  EXPECT_EQ(errorOf(R"({ "material": { "ks": { "array": "gloss", "scale": -1 } }, "lights": [] })"),
    "scene.json: /material/ks: components must be numbers >= 0");
  EXPECT_EQ(errorOf(R"({ "model": "vtk", "viewer": { "position": [0, 0, 5] },
      "material": { "kd": { "array": "Colors" }, "ka": 0.1 }, "lights": [] })"),
    "scene.json: /material/ka: with kd from an array, VTK's mapper takes the ambient colour from the array too: "
    "give ka as {\"array\": \"Colors\", \"scale\": <the property's Ambient>}");
  // An area light samples one lobe for all vertices.
  EXPECT_EQ(errorOf(R"({ "material": { "shininess": { "array": "eta" } },
      "lights": [ { "name": "panel", "type": "disk", "center": [0, 0, 2], "normal": [0, 0, -1], "radius": 0.5 } ] })"),
    "scene.json: /material/shininess: light 'panel' (disk) samples one specular lobe for every vertex, so the "
    "shininess cannot vary per vertex: give a number, or make ks 0");
}

TEST(MaterialArrays, SrgbDecodingAndItsChecks)
{
  // IEC 61966-2-1: the linear segment below the knee, the power curve above it.
  EXPECT_DOUBLE_EQ(srgbToLinear(0.04045), 0.04045 / 12.92);
  EXPECT_NEAR(srgbToLinear(0.5), 0.21404114048223255, 1e-15);
  EXPECT_DOUBLE_EQ(srgbToLinear(1.0), 1.0);
  EXPECT_DOUBLE_EQ(decodeByte(128, ArrayEncoding::Srgb, 0.5), 0.5 * srgbToLinear(128 / 255.0));
  EXPECT_DOUBLE_EQ(decodeByte(51, ArrayEncoding::Linear, 1.0), 0.2);
  EXPECT_EQ(defaultEncoding(true, false), ArrayEncoding::Srgb);
  EXPECT_EQ(defaultEncoding(false, false), ArrayEncoding::Linear);
  EXPECT_EQ(defaultEncoding(true, true), ArrayEncoding::Linear); // VTK's mapper does not decode

  using C = MaterialCoefficient;
  EXPECT_TRUE(isUsableValue(0.25, C::Specular));
  EXPECT_FALSE(isUsableValue(1.5, C::Specular));
  EXPECT_FALSE(isUsableValue(std::nan(""), C::Diffuse));
  EXPECT_TRUE(isUsableValue(500, C::Shininess));
  EXPECT_FALSE(isUsableValue(HUGE_VAL, C::Shininess));
  EXPECT_EQ(unusableValueReason(1.5, C::Specular), "it is 1.5, outside [0, 1]");
  EXPECT_EQ(unusableValueReason(std::nan(""), C::Specular), "it is NaN");
  EXPECT_EQ(unusableValueReason(-HUGE_VAL, C::Ambient), "it is infinite");
  EXPECT_EQ(unusableValueReason(-3, C::Shininess), "it is -3, below 0");
  EXPECT_EQ(decodeReal(0.25, C::Specular, ArrayEncoding::Linear, 2.0), 0.5);
  EXPECT_EQ(decodeReal(500, C::Shininess, ArrayEncoding::Linear, 1.0), 500);
  // Clamped into the domain where a source clamps: NaN to 0.
  EXPECT_EQ(decodeReal(1.5, C::Specular, ArrayEncoding::Linear, 1.0), 1.0);
  EXPECT_EQ(decodeReal(-0.5, C::Specular, ArrayEncoding::Srgb, 1.0), 0.0);
  EXPECT_EQ(decodeReal(std::nan(""), C::Diffuse, ArrayEncoding::Srgb, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(decodeReal(0.5, C::Diffuse, ArrayEncoding::Srgb, 1.0), srgbToLinear(0.5));
  ArrayCoefficient source;
  source.array = "gloss";
  EXPECT_EQ(vertexValueProblem(source, 17, "it is NaN"), "array 'gloss', vertex 17: it is NaN");
}

TEST(SceneFile, SpectraAreTheirRgbInTheRgbModel)
{
  const Scene scene = parseScene(R"({
    "material": { "kd": { "spectrum": { "start_nm": 350, "step_nm": 100, "values": [0.5, 0.5, 0.5, 0.5, 0.5, 0.5] } } },
    "lights": [
      { "name": "day", "type": "distant", "direction": [0, 0, -1], "spectrum": { "illuminant": "D65" } },
      { "name": "bulb", "type": "point", "position": [0, 0, 2], "spectrum": { "blackbody": 2700 }, "intensity": 2 },
      { "name": "lamp", "type": "ambient", "spectrum": { "illuminant": "F11" } } ] })",
    "scene.json");
  // D65 is sRGB's white; its luminance is scaled to 1.
  const Rgb day = std::get<DistantLight>(scene.lights[0].source).color;
  EXPECT_NEAR(day.r, 1.0, 2e-3);
  EXPECT_NEAR(day.g, 1.0, 2e-3);
  EXPECT_NEAR(day.b, 1.0, 2e-3);
  // A 2700 K bulb is orange: red above green above blue, and its intensity stays its own.
  const PointLight& bulb = std::get<PointLight>(scene.lights[1].source);
  EXPECT_GT(bulb.color.r, bulb.color.g);
  EXPECT_GT(bulb.color.g, bulb.color.b);
  EXPECT_EQ(bulb.intensity, 2.0);
  ASSERT_TRUE(scene.lights[2].spectrum);
  EXPECT_EQ(scene.lights[2].spectrum->values.size(), 81u); // F11, 380 to 780 nm
  // A flat reflectance is its grey, exactly; ka follows kd's spectrum.
  EXPECT_NEAR(scene.material.kd.r, 0.5, 1e-12);
  EXPECT_NEAR(scene.material.kd.b, 0.5, 1e-12);
  EXPECT_TRUE(scene.material.spectra[int(MaterialCoefficient::Ambient)]);
}

TEST(SceneFile, SpectrumErrors)
{
  const std::string light = R"({ "lights": [ { "type": "ambient", )";
  EXPECT_EQ(errorOf(light + R"("color": 1, "spectrum": { "illuminant": "A" } } ] })"),
    "scene.json: /lights/0/color: give the light a colour or a spectrum, not both");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "illuminant": "D60" } } ] })"),
    "scene.json: /lights/0/spectrum/illuminant: \"D60\" is not one of \"A\", \"B\", \"C\", \"D50\", \"D55\", "
    "\"D65\", \"D93\", \"E\", \"F1\", \"F2\", \"F3\", \"F4\", \"F5\", \"F6\", \"F7\", \"F8\", \"F9\", "
    "\"F10\", \"F11\", \"F12\"");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "illuminant": "A", "blackbody": 3000 } } ] })"),
    "scene.json: /lights/0/spectrum: give one of \"illuminant\" (a CIE name), \"blackbody\" (kelvin), or "
    "\"start_nm\", \"step_nm\" and \"values\" (a table)");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "blackbody": 100 } } ] })"),
    "scene.json: /lights/0/spectrum/blackbody: must be a temperature in kelvin from 500 to 1e6");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "start_nm": 380, "step_nm": 0, "values": [1, 1] } } ] })"),
    "scene.json: /lights/0/spectrum/step_nm: must be a number of nm > 0 and <= 100");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "start_nm": 380, "step_nm": 10, "values": [1, -1] } } ] })"),
    "scene.json: /lights/0/spectrum/values/1: must be a number >= 0");
  EXPECT_EQ(errorOf(light + R"("spectrum": { "start_nm": 900, "step_nm": 10, "values": [1, 1] } } ] })"),
    "scene.json: /lights/0/spectrum: emits no visible light (its luminance Y is 0)");
  EXPECT_EQ(errorOf(R"({ "material": { "kd": { "spectrum": { "illuminant": "A" }, "array": "x" } }, "lights": [] })"),
    "scene.json: /material/kd/array: unknown field; allowed here: spectrum");
}

TEST(SceneFile, ReadsAreaLightsAndEnvironmentMaps)
{
  // The map's path is relative to the scene file's folder.
  const Scene scene = parseScene(R"({
    "lights": [
      { "name": "panel", "type": "rectangle", "center": [0, 2, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 1],
        "intensity": 3, "two_sided": true, "estimator": "monte_carlo", "samples": 100, "stratified": false },
      { "type": "polygon", "vertices": [[0, 1, 0], [1, 1, 0], [0, 1, 1]], "estimator": "point" },
      { "type": "disk", "center": [0, 3, 0], "normal": [0, -1, 0], "radius": 0.5 },
      { "type": "sphere", "center": [1, 1, 1], "radius": 0.1, "color": [1, 0.5, 0.25] },
      { "name": "sky", "type": "environment", "file": "../envmaps/venice_sunset_1k.hdr", "rotation": 90,
        "estimator": "monte_carlo", "directions": "cosine", "brute_force_width": 64 }
    ]
  })",
    shadelab::testing::sourcePath("data/scenes/inline.json"));
  ASSERT_EQ(scene.lights.size(), 5u);
  const auto& panel = std::get<AreaLight>(scene.lights[0].source);
  const std::vector<glm::dvec3> corners = { { -1, 2, -0.5 }, { 1, 2, -0.5 }, { 1, 2, 0.5 }, { -1, 2, 0.5 } };
  EXPECT_EQ(std::get<PolygonEmitter>(panel.shape).vertices, corners);
  EXPECT_EQ(panel.intensity, 3);
  EXPECT_TRUE(panel.twoSided);
  EXPECT_EQ(panel.estimator, AreaEstimator::MonteCarlo);
  EXPECT_EQ(panel.sampling.samples, 100);
  EXPECT_FALSE(panel.sampling.stratified);
  EXPECT_EQ(scene.lights[1].name, "polygon1");
  EXPECT_EQ(std::get<AreaLight>(scene.lights[1].source).estimator, AreaEstimator::Point);
  const auto& disk = std::get<AreaLight>(scene.lights[2].source);
  EXPECT_EQ(scene.lights[2].name, "disk2");
  EXPECT_EQ(disk.estimator, AreaEstimator::Exact); // the defaults
  EXPECT_EQ(disk.sampling.samples, 64);
  EXPECT_TRUE(disk.sampling.stratified);
  EXPECT_FALSE(disk.twoSided);
  EXPECT_EQ(std::get<DiskEmitter>(disk.shape).radius, 0.5);
  EXPECT_EQ(scene.lights[3].name, "sphere3");
  EXPECT_EQ(std::get<SphereEmitter>(std::get<AreaLight>(scene.lights[3].source).shape).centre, glm::dvec3(1.0));
  const auto& sky = std::get<EnvironmentLight>(scene.lights[4].source);
  EXPECT_EQ(sky.file, shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr"));
  ASSERT_NE(sky.map, nullptr);
  EXPECT_EQ(sky.map->width, 1024);
  EXPECT_EQ(sky.rotationDegrees, 90);
  EXPECT_EQ(sky.estimator, EnvironmentEstimator::MonteCarlo);
  EXPECT_EQ(sky.directions, EnvironmentDirections::Cosine);
  EXPECT_EQ(sky.bruteForceWidth, 64);
}

TEST(SceneFile, AreaLightAndEnvironmentMapErrors)
{
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0]] } ] })"),
    "scene.json: /lights/0/vertices: a polygon needs at least 3 vertices");
  EXPECT_EQ(
    errorOf(R"({ "lights": [ { "type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 1]] } ] })"),
    "scene.json: /lights/0/vertices: the polygon's vertices must lie in one plane");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "polygon",
      "vertices": [[0, 0, 0], [2, 0, 0], [2, 2, 0], [1, 0.5, 0], [0, 2, 0]] } ] })"),
    "scene.json: /lights/0/vertices: the polygon must be convex, its vertices in order around it: split a "
    "concave emitter into convex lights");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "polygon", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0]] } ] })"),
    "scene.json: /lights/0/vertices: the polygon has no area");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "sphere", "center": [0, 0, 0], "radius": -1 } ] })"),
    "scene.json: /lights/0/radius: must be a number > 0");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "disk", "center": [0, 0, 0], "normal": [0, 0, 0], "radius": 1 } ] })"),
    "scene.json: /lights/0/normal: must be a non-zero vector");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "samples": 1 } ] })"),
    "scene.json: /lights/0/samples: must be a whole number from 2 to 1048576");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "estimator": "sh" } ] })"),
    "scene.json: /lights/0/estimator: \"sh\" is not one of \"exact\", \"monte_carlo\", \"point\"");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "two_sided": true } ] })"),
    "scene.json: /lights/0/two_sided: unknown field; allowed here: name, type, color, spectrum, intensity, shadows, "
    "center, radius, "
    "estimator, samples, max_samples, stratified");
  EXPECT_EQ(errorOf(R"({ "model": "vtk", "viewer": { "position": [0, 0, 1] },
      "lights": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1 } ] })"),
    "scene.json: /lights/0/type: VTK's renderer has no area lights or environment maps: use the lecture model");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "environment", "file": "no_such_map.hdr" } ] })"),
    "scene.json: /lights/0/file: no_such_map.hdr: no such file");
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "environment" } ] })"), "scene.json: /lights/0/file: missing");
  const std::string map = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");
  EXPECT_EQ(
    errorOf(R"({ "lights": [ { "type": "environment", "file": ")" + map + R"(", "brute_force_width": 100 } ] })"),
    "scene.json: /lights/0/brute_force_width: must be an even number that divides the map's width (1024), or at "
    "least that width");
}

TEST(SceneFile, Interreflection)
{
  // "interreflection": its bounces and gather rays, its arrays in the default selection; 0
  // bounces leave it out; "auto" bounces and samples (with max_samples) are a tolerance's.
  const Scene scene = parseScene(
    R"({ "lights": [], "interreflection": { "bounces": 3, "samples": 32, "stratified": false } })", "scene.json");
  ASSERT_TRUE(scene.interreflection);
  EXPECT_EQ(scene.interreflection->bounces, 3);
  EXPECT_EQ(scene.interreflection->sampling.samples, 32);
  EXPECT_FALSE(scene.interreflection->sampling.stratified);
  const ArrayRequest defaults = selectArrays(scene, { "default" });
  EXPECT_TRUE(defaults.interreflection[int(InterreflectionTerm::IndirectIrradiance)]);
  EXPECT_TRUE(defaults.interreflection[int(InterreflectionTerm::Indirect)]);
  EXPECT_FALSE(defaults.interreflection[int(InterreflectionTerm::AmbientMinusIndirect)]);
  EXPECT_EQ(defaults.bounces, std::vector<bool>(3, false));
  EXPECT_EQ(selectArrays(scene, { "indirect_bounce_2" }).bounces, std::vector<bool>({ false, true, false }));
  EXPECT_EQ(selectArrays(scene, { "all" }).bounces, std::vector<bool>(3, true));
  EXPECT_EQ(selectedArrayNames(scene, { "indirect_bounce_3", "indirect" }),
    std::vector<std::string>({ "indirect", "indirect_bounce_3" }));
  EXPECT_FALSE(parseScene(R"({ "lights": [], "interreflection": { "bounces": 0 } })", "scene.json").interreflection);
  EXPECT_EQ(parseScene(R"({ "lights": [], "interreflection": {} })", "scene.json").interreflection->bounces, 1);

  const Scene automatic =
    parseScene(R"({ "lights": [], "interreflection": { "bounces": "auto", "samples": "auto", "max_samples": 256 } })",
      "scene.json");
  EXPECT_TRUE(automatic.interreflection->bouncesFromTolerance);
  EXPECT_TRUE(automatic.interreflection->sampling.fromTolerance);
  EXPECT_EQ(automatic.interreflection->sampling.maximum, 256);
  // The plan chooses the bounces once the direct light is known: any of them can be asked for.
  EXPECT_EQ(selectArrays(automatic, { "all" }).bounces, std::vector<bool>(Interreflection::maxBounces, true));
  EXPECT_EQ(
    selectedArrayNames(automatic, { "indirect_bounce_64" }), std::vector<std::string>({ "indirect_bounce_64" }));
  EXPECT_EQ(
    parseScene(R"({ "lights": [], "interreflection": {} })", "scene.json").interreflection->sampling.maximum, 1024);
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": { "bounces": "many" } })"),
    "scene.json: /interreflection/bounces: must be a whole number of bounces, or \"auto\" (as many as a tolerance "
    "needs)");
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": { "max_samples": 256 } })"),
    "scene.json: /interreflection/max_samples: is the most \"samples\": \"auto\" may draw per vertex: give "
    "\"samples\": \"auto\" with it, or leave it out");
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": { "bounces": 65 } })"),
    "scene.json: /interreflection/bounces: must be a whole number from 0 to 64");
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": { "samples": 1 } })"),
    "scene.json: /interreflection/samples: must be a whole number from 2 to 1048576");
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": { "bounce": 2 } })"),
    "scene.json: /interreflection/bounce: unknown field; did you mean \"bounces\"? allowed here: bounces, samples, "
    "max_samples, stratified");
  EXPECT_EQ(errorOf(R"({ "lights": [], "material": { "kd": 1.5 }, "interreflection": {} })"),
    "scene.json: /material/kd: is the albedo each bounce of \"interreflection\" reflects, and above 1 it reflects "
    "more light than arrives: give components <= 1");
  EXPECT_EQ(errorOf(R"({ "lights": [], "interreflection": {}, "spectral": {} })"),
    "scene.json: /interreflection: is computed in RGB (each bounce multiplies by the material's RGB kd), which "
    "\"spectral\" replaces by spectra: remove one of them");
}

TEST(SceneFile, ShadowsAndAmbientOcclusion)
{
  // The scene's "shadows" is the default of the lights that can cast shadows, area lights
  // included, as --shadows is; a light's own setting wins; an ambient light casts none.
  const Scene scene = parseScene(R"({
    "shadows": true,
    "ambient_occlusion": { "rays": 128, "stratified": false, "max_distance": 0.5 },
    "lights": [
      { "name": "sun", "type": "distant", "direction": [0, 0, -1] },
      { "name": "bulb", "type": "point", "position": [1, 2, 3], "shadows": false },
      { "name": "panel", "type": "rectangle", "center": [0, 0, 2], "edge_u": [1, 0, 0], "edge_v": [0, -1, 0] },
      { "type": "ambient", "intensity": 0.1 }
    ]
  })",
    "scene.json");
  EXPECT_TRUE(scene.lights[0].shadows);
  EXPECT_FALSE(scene.lights[1].shadows);
  EXPECT_TRUE(scene.lights[2].shadows);
  EXPECT_FALSE(scene.lights[3].shadows);
  ASSERT_TRUE(scene.ambientOcclusion);
  EXPECT_EQ(scene.ambientOcclusion->sampling.samples, 128);
  EXPECT_FALSE(scene.ambientOcclusion->sampling.stratified);
  EXPECT_EQ(scene.ambientOcclusion->maxDistance, 0.5);
  EXPECT_TRUE(scene.needsVisibility());
  const ArrayRequest defaults = selectArrays(scene, { "default" });
  EXPECT_TRUE(defaults.lights[0][int(LightTerm::Visibility)]);
  EXPECT_FALSE(defaults.lights[1][int(LightTerm::Visibility)]);
  EXPECT_TRUE(defaults.lights[2][int(LightTerm::VisibilityStdError)]);
  EXPECT_TRUE(defaults.occlusion[int(OcclusionTerm::AmbientOcclusion)]);
  EXPECT_TRUE(defaults.occlusion[int(OcclusionTerm::AmbientOcclusionStdError)]);
  EXPECT_FALSE(defaults.occlusion[int(OcclusionTerm::BentNormal)]);
  EXPECT_FALSE(defaults.occlusion[int(OcclusionTerm::SkyViewFactor)]);
  EXPECT_FALSE(parseScene(R"({ "lights": [] })", "scene.json").needsVisibility());

  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "ambient", "shadows": true } ] })"),
    "scene.json: /lights/0/shadows: only distant, headlight, point, spot, polygon, rectangle, disk, sphere and "
    "environment lights cast shadows (an ambient light has no direction; the mesh's shadowing of it is ambient "
    "occlusion): remove \"shadows\" from this light");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "max_distance": 0 } })"),
    "scene.json: /ambient_occlusion/max_distance: must be a number > 0 (leave it out to count occluders at any "
    "distance)");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "rays": 1 } })"),
    "scene.json: /ambient_occlusion/rays: must be a whole number from 2 to 1048576");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "samples": 64 } })"),
    "scene.json: /ambient_occlusion/samples: unknown field; allowed here: rays, max_rays, stratified, max_distance");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "rays": "many" } })"),
    "scene.json: /ambient_occlusion/rays: must be a whole number per vertex, or \"auto\" (as many as a tolerance "
    "needs)");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "rays": 64, "max_rays": 128 } })"),
    "scene.json: /ambient_occlusion/max_rays: is the most \"rays\": \"auto\" may draw per vertex: give "
    "\"rays\": \"auto\" with it, or leave it out");
  EXPECT_EQ(errorOf(R"({ "lights": [], "ambient_occlusion": { "rays": "auto", "max_rays": 8 } })"),
    "scene.json: /ambient_occlusion/max_rays: must be a whole number from 16 to 1048576");
  const Scene automatic =
    parseScene(R"({ "lights": [], "ambient_occlusion": { "rays": "auto", "max_rays": 1000 } })", "scene.json");
  EXPECT_TRUE(automatic.ambientOcclusion->sampling.fromTolerance);
  EXPECT_EQ(automatic.ambientOcclusion->sampling.maximum, 1000);
  EXPECT_FALSE(automatic.ambientOcclusion->target) << "a tolerance's plan sets it";
  const std::vector<SceneProblem> untargeted = untargetedSamplingProblems(automatic, false);
  ASSERT_EQ(untargeted.size(), 1u);
  EXPECT_EQ(untargeted[0].path + ": " + untargeted[0].message,
    "/ambient_occlusion/rays: \"auto\" takes its count of rays from a tolerance: give one (shadelab shade "
    "--tolerance, the filter's Tolerance), or a number of rays");
  EXPECT_EQ(errorOf(R"({ "lights": [], "shadows": 1 })"), "scene.json: /shadows: must be true or false, got 1");
}

TEST(SceneFile, MissingFile)
{
  try
  {
    readSceneFile("no/such/scene.json");
    FAIL() << "no error";
  }
  catch (const SceneFileError& error)
  {
    EXPECT_STREQ(error.what(), "no/such/scene.json: cannot open the scene file (does it exist, and is it readable?)");
  }
}

// The names a selection ticks in a list of the scene's arrays (ParaView's panel).
TEST(ArraySelection, SelectedNamesInOutputOrder)
{
  const Scene scene = parseScene(R"({ "lights": [
      { "name": "sun", "type": "distant", "direction": [0, 0, -1] },
      { "name": "bulb", "type": "point", "position": [0, 0, 1] } ] })",
    "scene.json");
  EXPECT_EQ(selectedArrayNames(scene, { "default" }),
    (std::vector<std::string>{ "ambient", "diffuse", "specular", "total", "shading_flags" }));
  EXPECT_EQ(selectedArrayNames(scene, { "*_distance", "total", "sun_diffuse" }),
    (std::vector<std::string>{ "total", "sun_diffuse", "bulb_distance" }));
  EXPECT_EQ(selectedArrayNames(scene, { "all" }).size(), availableArrays(scene).size());
  EXPECT_THROW(selectedArrayNames(scene, { "moon_diffuse" }), std::invalid_argument);
}

TEST(ArraySelection, PatternsAndNames)
{
  const Scene scene = parseScene(R"({ "lights": [
      { "name": "sun", "type": "distant", "direction": [0, 0, -1] },
      { "name": "bulb", "type": "point", "position": [0, 0, 1] },
      { "name": "sky", "type": "ambient" } ] })",
    "scene.json");
  const ArrayRequest byDefault = selectArrays(scene, { "default" });
  EXPECT_TRUE(byDefault.flags);
  EXPECT_FALSE(byDefault.any(LightTerm::CosIncidence));

  const ArrayRequest distances = selectArrays(scene, { "*_distance", "sun_n_dot_h" });
  EXPECT_FALSE(distances.lights[0][int(LightTerm::Distance)]); // a distant light has none
  EXPECT_TRUE(distances.lights[1][int(LightTerm::Distance)]);
  EXPECT_TRUE(distances.lights[0][int(LightTerm::NDotH)]);
  EXPECT_FALSE(distances.lights[1][int(LightTerm::NDotH)]);
  EXPECT_FALSE(distances.flags);

  const ArrayRequest all = selectArrays(scene, { "all" });
  EXPECT_TRUE(all.flags);
  EXPECT_EQ(all.totals, (std::array<bool, TotalTermCount>{ true, true, true, true }));
  EXPECT_EQ(std::count(all.lights[0].begin(), all.lights[0].end(), true), 11); // no distance
  EXPECT_EQ(std::count(all.lights[1].begin(), all.lights[1].end(), true), 12);
  EXPECT_EQ(std::count(all.lights[2].begin(), all.lights[2].end(), true), 0); // ambient
  EXPECT_EQ(availableArrays(scene).size(), 5u + 11u + 12u);                   // totals+flags, sun, bulb

  try
  {
    selectArrays(scene, { "total", "sun_distance" });
    FAIL() << "no error";
  }
  catch (const std::invalid_argument& error)
  {
    const std::string message = error.what();
    EXPECT_EQ(message.substr(0, message.find(':')), "unknown array 'sun_distance'; this scene has");
    EXPECT_NE(message.find(", bulb_distance,"), std::string::npos);
  }
  try
  {
    selectArrays(scene, {});
    FAIL() << "no error";
  }
  catch (const std::invalid_argument& error)
  {
    EXPECT_EQ(std::string(error.what()).substr(0, 40), "no arrays selected; this scene has: defa");
  }
}

TEST(ArraySelection, LightArrayNamesCannotCollide)
{
  // <light>_<term> names of distinct lights could only coincide if a term name ended in "_"
  // followed by another term name (light "a_cos" with "incidence" against light "a" with
  // "cos_incidence"). None may.
  for (int t = 0; t < LightTermCount; ++t)
  {
    for (int u = 0; u < LightTermCount; ++u)
    {
      const std::string longer = termInfo(LightTerm(t)).name;
      const std::string suffix = std::string("_") + termInfo(LightTerm(u)).name;
      EXPECT_FALSE(
        longer.size() > suffix.size() && longer.compare(longer.size() - suffix.size(), suffix.size(), suffix) == 0)
        << longer << " ends in " << suffix;
    }
  }
}

TEST(ScenePrecision, ValuesThatWouldOverflowFloat32AreRefused)
{
  const auto problemsOf = [](const std::string& text, Precision precision)
  {
    const std::vector<SceneProblem> problems = sceneProblems(parseScene(text, "scene.json"), precision);
    return problems.empty() ? std::string("none") : problems.front().path + ": " + problems.front().message;
  };
  const std::string farLight = R"({ "lights": [ { "type": "point", "position": [1e30, 0, 0] } ] })";
  EXPECT_EQ(problemsOf(farLight, Precision::Float64), "none");
  EXPECT_EQ(problemsOf(farLight, Precision::Float32),
    "/lights/0/position: must be a finite point with coordinates within +-2.3e+18 for float32 arithmetic");
  const std::string bright = R"({ "lights": [ { "type": "distant", "direction": [0, 0, -1], "intensity": 1e39 } ] })";
  EXPECT_EQ(problemsOf(bright, Precision::Float64), "none");
  EXPECT_EQ(problemsOf(bright, Precision::Float32),
    "/lights/0/intensity: this light alone can reach 1e+39 at a vertex (colour x intensity x k x "
    "attenuation at min_distance), beyond what float32 holds: use float64 or a smaller intensity or colour");
  // Two lights each within float32, together beyond it (a quarter of its largest value).
  const std::string twoBright = R"({ "lights": [ { "type": "distant", "direction": [0, 0, -1], "intensity": 6e37 },
    { "type": "ambient", "intensity": 6e37 } ] })";
  EXPECT_EQ(problemsOf(twoBright, Precision::Float32),
    "/lights: together the lights can reach 1.1e+38 at a vertex (colour x intensity x k x "
    "attenuation at min_distance), beyond what float32 holds: use float64 or smaller intensities");
  // A tiny minimum distance: 1/d^2 at 1e-30 is 1e60.
  const std::string close = R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "min_distance": 1e-30 } ] })";
  EXPECT_EQ(problemsOf(close, Precision::Float64), "none");
  EXPECT_EQ(problemsOf(close, Precision::Float32),
    "/lights/0/min_distance: this light alone can reach 1e+60 at a vertex (colour x intensity x k x attenuation at "
    "min_distance), beyond what float32 holds: use float64 or a larger min_distance");
  // Even float64 cannot hold colour 1e200 x intensity 1e200 (the file reader checks float64).
  EXPECT_EQ(errorOf(R"({ "lights": [ { "type": "ambient", "color": 1e200, "intensity": 1e200 } ] })"),
    "scene.json: /lights/0/intensity: this light alone can reach more than 1.8e+308 at a vertex (colour x "
    "intensity x k x attenuation at min_distance), beyond what float64 holds: use a smaller intensity or colour");
}

// Where a filter's scene comes from: JSON text, else a file, else a Scene set in C++, else the
// default light kit; and the set one last among a Scene and the strings is the one used.
TEST(SceneSource, JsonTextThenFileThenSceneThenTheDefaultLightKit)
{
  SceneSource source;
  EXPECT_EQ(source.scene().lights.size(), defaultLightKit().lights.size());
  EXPECT_EQ(source.scene().lights.front().name, defaultLightKit().lights.front().name);

  Scene made;
  made.lights.push_back({ "made", AmbientLight{} });
  source.setScene(made);
  EXPECT_EQ(source.scene().lights.front().name, "made");

  const std::string studio = shadelab::testing::sourcePath("data/scenes/studio.json");
  EXPECT_TRUE(source.setFileName(studio));
  EXPECT_FALSE(source.setFileName(studio)); // no change
  EXPECT_EQ(source.scene().lights.front().name, "key");

  EXPECT_TRUE(source.setJson(R"({ "lights": [ { "name": "text", "type": "ambient" } ] })"));
  EXPECT_EQ(source.scene().lights.front().name, "text");

  source.setScene(made); // forgets both strings
  EXPECT_EQ(source.fileName(), "");
  EXPECT_EQ(source.json(), "");
  EXPECT_EQ(source.scene().lights.front().name, "made");
}

TEST(SceneSource, ErrorsAreTheSceneFilesWithSceneJsonForTheText)
{
  SceneSource source;
  source.setJson(R"({ "lights": [ { "type": "ambient", "intensity": -1 } ] })");
  try
  {
    source.scene();
    FAIL() << "a negative intensity was accepted";
  }
  catch (const SceneFileError& error)
  {
    EXPECT_STREQ(error.what(), "SceneJson: /lights/0/intensity: must be a number >= 0");
  }
  source.setJson("");
  source.setFileName("no_such_scene.json");
  try
  {
    source.scene();
    FAIL() << "a missing file was accepted";
  }
  catch (const SceneFileError& error)
  {
    EXPECT_STREQ(error.what(), "no_such_scene.json: cannot open the scene file (does it exist, and is it readable?)");
  }
}
}
