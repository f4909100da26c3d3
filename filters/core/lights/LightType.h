#pragma once
// What every light type provides, in the manner of pbrt-v4's lights.h: each type is a struct
// of its parameters, in a file pair of its own (DistantLight.h/.cpp, ...), with these members
// beside them, declared by SHADELAB_LIGHT_TYPE below and defined in its .cpp. LightSource.h
// registers the types; the rest of ShadeLab reaches a light only through these members, so a
// type missing one does not link.
//
//   static constexpr LightRole role;      how the kernel evaluates it (LightEvaluation.h)
//   static constexpr bool positional;     true: it has members `position` and `attenuation`
//   static constexpr bool castsShadows;   true: "shadows" is allowed on it (visibility/)
//   static const std::vector<SceneFileType>& sceneFileTypes();
//                                         its "type" names in a scene file, each with its fields
//   static T read(const JsonNode& node, const SceneFileType& type, const std::string& sceneFile);
//                                         the light from its JSON object (fields already known good)
//   std::string typeName() const;         its "type" name in messages: the shape it was read as
//                                         ("polygon" for a light read as a "rectangle")
//   Rgb emitted() const;                  colour x intensity: the RGB it delivers before
//                                         attenuation, cone and material
//   void check(LightChecks& checks) const;          every problem of its values
//   double peakContribution(const Material&) const; the largest RGB value it can add at a vertex
//   bool hasTerm(LightTerm term) const;   which per-light arrays it has
//   void placeOn(const MeshPlacement&);   from the mesh's frame to the world (scene/SceneFrame.h)
//   LightEvaluation prepare(const EvaluationContext&) const;  its form for the kernel
//
// A Distributed type also declares, beside the macro (planning/ asks it; a distributed type
// without it does not compile):
//
//   ToleranceBounds toleranceBounds(const Material& m, bool shadowed) const;
//                                         what a tolerance can bound of its estimator
#include "LightChecks.h"
#include "LightEvaluation.h"
#include "LightTerms.h"
#include "Material.h"
#include "MeshPlacement.h"
#include "Vec3.h"

#include <algorithm>
#include <string>
#include <vector>

namespace shadelab
{
class JsonNode;

enum class LightRole
{
  Local,       // one direction per vertex: a LocalEvaluation
  Ambient,     // the same light everywhere: an AmbientEvaluation
  Distributed, // integrated over a solid angle: a DistributedEvaluation
};

/// A light type's name in a scene file's "type", and the fields it allows besides "name",
/// "type", "color" and "intensity", which every light has.
struct SceneFileType
{
  const char* name;
  std::vector<const char*> fields;
};

/// What a tolerance can bound of a distributed light's estimator (planning/MethodChoice.cpp):
/// whether its E is sampled, the largest error of an E that is not, or why it cannot be bounded.
struct ToleranceBounds
{
  /// E is drawn to a target. (Under shadows it is, whatever the estimator: an exact E times
  /// the samples' visible fraction.)
  bool sampledIrradiance = false;
  /// The largest error of an E that is not sampled (spherical harmonics' band limit).
  double irradianceError = 0;
  /// Why no tolerance can bound it, naming what to use instead; "" where one can.
  std::string unbounded;
  /// How the scene file (and the command line) asks for its samples to be drawn to a target.
  std::string autoSamples;
};

/// The larger of kd and ks: the most of a light's colour a vertex can reflect.
inline double largestReflectance(const Material& m)
{
  return std::max(largestComponent(m.kd), largestComponent(m.ks));
}

/// 2 pi: a distributed light gives E of at most pi L and S of at most 2 pi L (a lobe of 1 over
/// the hemisphere).
constexpr double distributedPeakFactor = 6.283185307179586;
}

/// Declares the members listed at the top of this file in a light type's struct, as
/// vtkTypeMacro declares a VTK class's (a macro, so that the struct stays an aggregate:
/// DistantLight{ direction, color, intensity, false }).
#define SHADELAB_LIGHT_TYPE(Type, lightRole, isPositional, hasShadows)                                                 \
  static constexpr LightRole role = LightRole::lightRole;                                                              \
  static constexpr bool positional = isPositional;                                                                     \
  static constexpr bool castsShadows = hasShadows;                                                                     \
  static const std::vector<SceneFileType>& sceneFileTypes();                                                           \
  static Type read(const JsonNode& node, const SceneFileType& type, const std::string& sceneFile);                     \
  std::string typeName() const;                                                                                        \
  Rgb emitted() const;                                                                                                 \
  void check(LightChecks& checks) const;                                                                               \
  double peakContribution(const Material& m) const;                                                                    \
  bool hasTerm(LightTerm term) const;                                                                                  \
  void placeOn(const MeshPlacement& placement);                                                                        \
  LightEvaluation prepare(const EvaluationContext& context) const
