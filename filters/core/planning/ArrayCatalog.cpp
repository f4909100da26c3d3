#include "ArrayCatalog.h"

#include "EnvironmentLight.h"
#include "ShBands.h"

#include <algorithm>
#include <stdexcept>

namespace shadelab
{
namespace
{
const std::array<TermInfo, LightTermCount> lightTerms = { {
  { "to_light", 3, "s: unit vector from the vertex to the light" },
  { "distance", 1, "d: distance from the vertex to the light" },
  { "attenuation", 1, "distance attenuation of the light (1 for distant lights)" },
  { "spot_factor", 1, "spotlight cone factor (1 outside spotlights)" },
  { "cos_incidence", 1, "n.s, cosine of the angle of incidence (negative below the horizon)" },
  { "incidence_angle", 1, "theta_i = acos(n.s) in degrees" },
  { "reflection", 3, "r = 2 (n.s) n - s, mirror direction of s" },
  { "r_dot_v", 1, "r.v, cosine of the angle between r and the viewer" },
  { "half_vector", 3, "h = (s + v)/|s + v| (0 where s = -v)" },
  { "n_dot_h", 1, "n.h" },
  { "ggx_d", 1,
    "vtk_pbr model: D, GGX's distribution of microfacet normals at n.h (alpha = roughness^2), from VTK 9.1's "
    "PBR shader, with its cosines clamped to [1e-5, 1]" },
  { "smith_v", 1,
    "vtk_pbr model: V = G / (4 (n.s)(n.v)), the height-correlated Smith masking-shadowing over the BRDF's "
    "denominator, as VTK 9.1's PBR shader computes it" },
  { "schlick_f", 3, "vtk_pbr model: F, Schlick's Fresnel reflectance at h.s, RGB" },
  { "diffuse", 3, "this light's diffuse term, RGB" },
  { "specular", 3, "this light's specular term, RGB" },
  { "irradiance", 3, "E: irradiance, the integral of L max(0, n.w) over the light's solid angle, RGB" },
  { "irradiance_std_error", 3, "Monte Carlo standard error of the irradiance, RGB" },
  { "specular_std_error", 3, "Monte Carlo standard error of the specular term, RGB" },
  { "visibility", 1,
    "lights with shadows: 1 where the mesh does not hide the light, 0 where it does; for an area light or a map, "
    "the fraction of its irradiance that gets past the mesh (1 where the light is below the horizon)" },
  { "visibility_std_error", 1, "Monte Carlo standard error of an area light's or a map's visibility" },
  { "short_of_target", 1,
    "with \"samples\": \"auto\" under a tolerance, 1 where the vertex stopped at \"max_samples\" with a standard "
    "error above its target, else 0" },
  { "sh_transfer", 0,
    "\"estimator\": \"prt\": the vertex's transfer vector, (order + 1)^2 spherical-harmonic coefficients (world axes, "
    "Y_lm at l (l + 1) + m) whose dot product with a map's is the irradiance under it; with shadows, from the mesh's "
    "shadow rays" },
  { "sh_transfer_std_error", 0,
    "\"estimator\": \"prt\" with shadows: the standard error of each transfer coefficient" },
} };

const std::array<TermInfo, TotalTermCount> totalTerms = { {
  { "ambient", 3, "ambient term ka La, RGB" },
  { "diffuse", 3, "diffuse terms summed over lights, RGB" },
  { "specular", 3, "specular terms summed over lights, RGB" },
  { "total", 3, "the complete model: ambient + diffuse + specular, RGB" },
} };

const std::array<TermInfo, OcclusionTermCount> occlusionTerms = { {
  { "ambient_occlusion", 1,
    "the cosine-weighted fraction of the hemisphere from which the mesh does not hide the sky" },
  { "ambient_occlusion_std_error", 1, "Monte Carlo standard error of ambient_occlusion" },
  { "bent_normal", 3, "the mean direction from which the sky is seen (0 where it is not)" },
  { "sky_view_factor", 1, "the uniformly weighted fraction of the hemisphere from which the sky is seen" },
  { "ambient_occlusion_rays", 1,
    "with \"rays\": \"auto\", the occlusion rays the vertex drew to meet its share of the tolerance (at the "
    "maximum: its standard error may be above the share)" },
  { "ambient_occlusion_short_of_target", 1,
    "with \"rays\": \"auto\", 1 where the vertex stopped at \"max_rays\" with a standard error above its share, "
    "else 0" },
} };

const std::array<TermInfo, InterreflectionTermCount> interreflectionTerms = { {
  { "indirect_irradiance", 3,
    "E_ind: the irradiance from the light the mesh reflects onto itself (diffusely, over the scene's bounces), "
    "RGB; its diffuse term kd E_ind is in diffuse and total" },
  { "indirect_irradiance_std_error", 3, "Monte Carlo standard error of indirect_irradiance, RGB" },
  { "indirect", 3, "kd E_ind, the diffuse term of the indirect light (included in diffuse and total), RGB" },
  { "ambient_minus_indirect", 3,
    "the ambient term ka La less the indirect diffuse term it stands in for: how far the ambient term is from "
    "the light it imitates, RGB" },
} };

/// Whether the model computes the term: the microfacet terms only the vtk_pbr model does.
bool modelHasTerm(ShadingModel model, LightTerm term)
{
  return !isMicrofacetTerm(term) || model == ShadingModel::VtkPbr;
}

/// What bounce n adds: "indirect_bounce_<n>".
const char* const indirectBouncePrefix = "indirect_bounce_";
const char* const indirectBounceDescription = "the irradiance that bounce n alone adds to indirect_irradiance, RGB";
const std::string plannedBounceDescription = std::string(indirectBounceDescription) +
  "; under \"bounces\": \"auto\", written for each bounce the tolerance's plan makes";

/// How many indirect_bounce_<n> arrays the scene can write: its bounces, or under "bounces":
/// "auto" as many as a plan may choose, since the count is known only once the direct light is.
int bounceArrayCount(const Scene& scene)
{
  if (!scene.interreflection)
  {
    return 0;
  }
  return scene.interreflection->bouncesFromTolerance ? Interreflection::maxBounces : scene.interreflection->bounces;
}

/// A "prt" map's transfer carried through the bounces: "<light>_sh_transfer_indirect".
const char* const indirectTransferTerm = "sh_transfer_indirect";
const char* const indirectTransferDescription =
  "\"estimator\": \"prt\" with interreflection: what the bounces add to the transfer vector, per channel "
  "(component 3 k + c: coefficient k, channel c), so that the indirect irradiance under any map is the dot product "
  "of its coefficients with each channel's";
}

const TermInfo flagsInfo = { "shading_flags", 1,
  "diagnostic bits: 1 degenerate normal, 2 light at minimum distance, 4 light below horizon, "
  "8 half vector undefined, 16 non-finite input, 32 normal flipped to face the viewer, "
  "64 a shadowed light it faces hidden by a triangle around it, 128 a shadowed light hidden from it enclosed by the "
  "mesh" };

const TermInfo& termInfo(LightTerm term)
{
  return lightTerms[static_cast<int>(term)];
}

const TermInfo& termInfo(TotalTerm term)
{
  return totalTerms[static_cast<int>(term)];
}

const TermInfo& termInfo(OcclusionTerm term)
{
  return occlusionTerms[static_cast<int>(term)];
}

const TermInfo& termInfo(InterreflectionTerm term)
{
  return interreflectionTerms[static_cast<int>(term)];
}

bool sceneLightHasTerm(const Scene& scene, std::size_t light, LightTerm term)
{
  return lightHasTerm(scene.lights.at(light), term) && modelHasTerm(scene.model, term);
}

int lightTermComponents(const NamedLight& light, LightTerm term)
{
  const int fixed = termInfo(term).components;
  if (fixed > 0)
  {
    return fixed;
  }
  const auto* map = std::get_if<EnvironmentLight>(&light.source);
  return map ? shCount(map->shOrder) : 0;
}

bool sceneHasTerm(const Scene& scene, OcclusionTerm term)
{
  const bool drawnToTarget = term == OcclusionTerm::Rays || term == OcclusionTerm::ShortOfTarget;
  return scene.ambientOcclusion && (!drawnToTarget || scene.ambientOcclusion->sampling.fromTolerance);
}

bool ArrayRequest::any(LightTerm term) const
{
  return std::any_of(
    lights.begin(), lights.end(), [term](const auto& perLight) { return perLight[static_cast<int>(term)]; });
}

std::string lightArrayName(const std::string& prefix, const std::string& light, LightTerm term)
{
  return prefix + light + "_" + termInfo(term).name;
}

std::string totalArrayName(const std::string& prefix, TotalTerm term)
{
  return prefix + termInfo(term).name;
}

std::string totalXyzArrayName(const std::string& prefix, TotalTerm term)
{
  return totalArrayName(prefix, term) + "_xyz";
}

std::string rgbDifferenceArrayName(const std::string& prefix)
{
  return totalArrayName(prefix, TotalTerm::Total) + "_rgb_difference";
}

std::vector<std::string> spectralArrayNames(const Scene& scene, const std::string& prefix)
{
  std::vector<std::string> names;
  for (int t = 0; t < TotalTermCount && scene.spectral; ++t)
  {
    names.push_back(totalXyzArrayName(prefix, TotalTerm(t)));
  }
  if (scene.spectral)
  {
    names.push_back(rgbDifferenceArrayName(prefix));
  }
  return names;
}

std::string flagsArrayName(const std::string& prefix)
{
  return prefix + flagsInfo.name;
}

std::string visibilityFlagsArrayName(const std::string& prefix)
{
  return prefix + "visibility_flags";
}

std::string hiddenSamplesArrayName(const std::string& prefix, const std::string& light)
{
  return prefix + light + "_hidden_samples";
}

bool specularComputed(const Scene& scene, const ArrayRequest& request, std::size_t light)
{
  return hasSpecularTerm(scene) &&
    (request.lights[light][int(LightTerm::Specular)] || request.totals[int(TotalTerm::Specular)] ||
      request.totals[int(TotalTerm::Total)]);
}

std::string shadowedTermsArrayName(const std::string& prefix, const std::string& light)
{
  return prefix + light + "_shadowed_terms";
}

std::string occlusionArrayName(const std::string& prefix, OcclusionTerm term)
{
  return prefix + termInfo(term).name;
}

std::string interreflectionArrayName(const std::string& prefix, InterreflectionTerm term)
{
  return prefix + termInfo(term).name;
}

std::string indirectBounceArrayName(const std::string& prefix, int bounce)
{
  return prefix + indirectBouncePrefix + std::to_string(bounce);
}

std::string indirectTransferArrayName(const std::string& prefix, const std::string& light)
{
  return prefix + light + "_" + indirectTransferTerm;
}

bool hasIndirectTransfer(const Scene& scene, std::size_t light)
{
  return scene.interreflection && lightHasTerm(scene.lights.at(light), LightTerm::ShTransfer);
}

bool needsInterreflection(const Scene& scene, const ArrayRequest& request)
{
  auto any = [](const auto& asked) { return std::any_of(asked.begin(), asked.end(), [](bool b) { return b; }); };
  const bool own = any(request.interreflection) || any(request.bounces) || any(request.indirectTransfer);
  return scene.interreflection &&
    (own || request.totals[int(TotalTerm::Diffuse)] || request.totals[int(TotalTerm::Total)]);
}

std::vector<ArrayDescription> availableArrays(const Scene& scene, const std::string& prefix)
{
  std::vector<ArrayDescription> arrays;
  for (int t = 0; t < TotalTermCount; ++t)
  {
    const TermInfo& info = totalTerms[t];
    arrays.push_back({ totalArrayName(prefix, TotalTerm(t)), info.components, info.description });
  }
  arrays.push_back({ flagsArrayName(prefix), flagsInfo.components, flagsInfo.description });
  for (int t = 0; t < OcclusionTermCount; ++t)
  {
    const TermInfo& info = occlusionTerms[t];
    if (sceneHasTerm(scene, OcclusionTerm(t)))
    {
      arrays.push_back({ occlusionArrayName(prefix, OcclusionTerm(t)), info.components, info.description });
    }
  }
  for (int t = 0; t < InterreflectionTermCount && scene.interreflection; ++t)
  {
    const TermInfo& info = interreflectionTerms[t];
    arrays.push_back({ interreflectionArrayName(prefix, InterreflectionTerm(t)), info.components, info.description });
  }
  const bool planned = scene.interreflection && scene.interreflection->bouncesFromTolerance;
  for (int n = 1; n <= bounceArrayCount(scene); ++n)
  {
    arrays.push_back(
      { indirectBounceArrayName(prefix, n), 3, planned ? plannedBounceDescription : indirectBounceDescription });
  }
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    const NamedLight& light = scene.lights[l];
    for (int t = 0; t < LightTermCount; ++t)
    {
      if (sceneLightHasTerm(scene, l, LightTerm(t)))
      {
        const TermInfo& info = lightTerms[t];
        arrays.push_back({ lightArrayName(prefix, light.name, LightTerm(t)), lightTermComponents(light, LightTerm(t)),
          "light '" + light.name + "': " + info.description });
      }
    }
    if (hasIndirectTransfer(scene, l))
    {
      arrays.push_back(
        { indirectTransferArrayName(prefix, light.name), 3 * lightTermComponents(light, LightTerm::ShTransfer),
          "light '" + light.name + "': " + indirectTransferDescription });
    }
  }
  return arrays;
}

namespace
{
void requestAll(const Scene& scene, ArrayRequest& request)
{
  request.totals.fill(true);
  request.flags = true;
  for (int t = 0; t < OcclusionTermCount; ++t)
  {
    request.occlusion[t] = sceneHasTerm(scene, OcclusionTerm(t));
  }
  request.interreflection.fill(scene.interreflection.has_value());
  request.bounces.assign(request.bounces.size(), true);
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    for (int t = 0; t < LightTermCount; ++t)
    {
      request.lights[l][t] = sceneLightHasTerm(scene, l, LightTerm(t));
    }
    request.indirectTransfer[l] = hasIndirectTransfer(scene, l);
  }
}

// "*_TERM": the term on every light that has it. Returns false if TERM is not a term name.
bool requestTermOnEveryLight(const Scene& scene, const std::string& term, ArrayRequest& request)
{
  if (term == indirectTransferTerm)
  {
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      request.indirectTransfer[l] = request.indirectTransfer[l] || hasIndirectTransfer(scene, l);
    }
    return true;
  }
  for (int t = 0; t < LightTermCount; ++t)
  {
    if (term == lightTerms[t].name && modelHasTerm(scene.model, LightTerm(t)))
    {
      for (std::size_t l = 0; l < scene.lights.size(); ++l)
      {
        request.lights[l][t] = request.lights[l][t] || sceneLightHasTerm(scene, l, LightTerm(t));
      }
      return true;
    }
  }
  return false;
}

// A full array name. Returns false if no array has that name.
bool requestByName(const Scene& scene, const std::string& name, ArrayRequest& request)
{
  for (int t = 0; t < TotalTermCount; ++t)
  {
    if (name == totalTerms[t].name)
    {
      request.totals[t] = true;
      return true;
    }
  }
  if (name == flagsInfo.name)
  {
    request.flags = true;
    return true;
  }
  for (int t = 0; t < OcclusionTermCount; ++t)
  {
    if (sceneHasTerm(scene, OcclusionTerm(t)) && name == occlusionTerms[t].name)
    {
      request.occlusion[t] = true;
      return true;
    }
  }
  for (int t = 0; t < InterreflectionTermCount && scene.interreflection; ++t)
  {
    if (name == interreflectionTerms[t].name)
    {
      request.interreflection[t] = true;
      return true;
    }
  }
  for (std::size_t n = 1; n <= request.bounces.size(); ++n)
  {
    if (name == indirectBounceArrayName("", int(n)))
    {
      request.bounces[n - 1] = true;
      return true;
    }
  }
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    for (int t = 0; t < LightTermCount; ++t)
    {
      if (sceneLightHasTerm(scene, l, LightTerm(t)) && name == lightArrayName("", scene.lights[l].name, LightTerm(t)))
      {
        request.lights[l][t] = true;
        return true;
      }
    }
    if (hasIndirectTransfer(scene, l) && name == indirectTransferArrayName("", scene.lights[l].name))
    {
      request.indirectTransfer[l] = true;
      return true;
    }
  }
  return false;
}

std::string knownSelections(const Scene& scene)
{
  std::string known = "default, totals, all";
  for (int t = 0; t < LightTermCount; ++t)
  {
    if (modelHasTerm(scene.model, LightTerm(t)))
    {
      known += std::string(", *_") + lightTerms[t].name;
    }
  }
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    if (hasIndirectTransfer(scene, l))
    {
      known += std::string(", *_") + indirectTransferTerm; // only where some light has it
      break;
    }
  }
  for (const ArrayDescription& array : availableArrays(scene))
  {
    known += ", " + array.name;
  }
  return known;
}
}

ArrayRequest selectArrays(const Scene& scene, const std::vector<std::string>& selection)
{
  if (selection.empty())
  {
    throw std::invalid_argument("no arrays selected; this scene has: " + knownSelections(scene));
  }
  ArrayRequest request;
  request.lights.resize(scene.lights.size());
  request.bounces.resize(std::size_t(bounceArrayCount(scene)));
  request.indirectTransfer.resize(scene.lights.size());
  for (const std::string& entry : selection)
  {
    bool known = true;
    if (entry == "all")
    {
      requestAll(scene, request);
    }
    else if (entry == "totals")
    {
      request.totals.fill(true);
    }
    else if (entry == "default")
    {
      // What a scene asks for when it turns visibility on is shown by default.
      request.totals.fill(true);
      request.flags = true;
      // An estimate comes with its standard error.
      request.occlusion[int(OcclusionTerm::AmbientOcclusion)] |= scene.ambientOcclusion.has_value();
      request.occlusion[int(OcclusionTerm::AmbientOcclusionStdError)] |= scene.ambientOcclusion.has_value();
      request.occlusion[int(OcclusionTerm::Rays)] |= sceneHasTerm(scene, OcclusionTerm::Rays);
      request.occlusion[int(OcclusionTerm::ShortOfTarget)] |= sceneHasTerm(scene, OcclusionTerm::ShortOfTarget);
      requestTermOnEveryLight(scene, termInfo(LightTerm::Visibility).name, request);
      requestTermOnEveryLight(scene, termInfo(LightTerm::VisibilityStdError).name, request);
      requestTermOnEveryLight(scene, termInfo(LightTerm::ShortOfTarget).name, request);
      for (const InterreflectionTerm term : { InterreflectionTerm::IndirectIrradiance,
             InterreflectionTerm::IndirectIrradianceStdError, InterreflectionTerm::Indirect })
      {
        request.interreflection[int(term)] |= scene.interreflection.has_value();
      }
      // Transfer vectors are what a "prt" map is chosen for.
      requestTermOnEveryLight(scene, termInfo(LightTerm::ShTransfer).name, request);
      requestTermOnEveryLight(scene, termInfo(LightTerm::ShTransferStdError).name, request);
      requestTermOnEveryLight(scene, indirectTransferTerm, request);
    }
    else if (entry.rfind("*_", 0) == 0)
    {
      known = requestTermOnEveryLight(scene, entry.substr(2), request);
    }
    else
    {
      known = requestByName(scene, entry, request);
    }
    if (!known)
    {
      // Quoted short and printable: the entry may be anything a user or a script passed.
      std::string shown = entry.size() > 60 ? entry.substr(0, 60) + "..." : entry;
      std::replace_if(
        shown.begin(), shown.end(), [](char c) { return c < 0x20 || c >= 0x7f; }, '?');
      throw std::invalid_argument("unknown array '" + shown + "'; this scene has: " + knownSelections(scene));
    }
  }
  return request;
}

namespace
{
/// Whether every array inner asks for, outer asks for too.
bool covers(const ArrayRequest& outer, const ArrayRequest& inner)
{
  auto all = [](const auto& big, const auto& small)
  {
    for (std::size_t i = 0; i < small.size(); ++i)
    {
      if (small[i] && !big[i])
      {
        return false;
      }
    }
    return true;
  };
  for (std::size_t l = 0; l < inner.lights.size(); ++l)
  {
    if (!all(outer.lights[l], inner.lights[l]))
    {
      return false;
    }
  }
  return all(outer.totals, inner.totals) && (outer.flags || !inner.flags) && all(outer.occlusion, inner.occlusion) &&
    all(outer.interreflection, inner.interreflection) && all(outer.bounces, inner.bounces) &&
    all(outer.indirectTransfer, inner.indirectTransfer);
}
}

std::vector<std::string> selectedArrayNames(const Scene& scene, const std::vector<std::string>& selection)
{
  const ArrayRequest request = selectArrays(scene, selection);
  std::vector<std::string> names;
  for (const ArrayDescription& array : availableArrays(scene))
  {
    if (covers(request, selectArrays(scene, { array.name })))
    {
      names.push_back(array.name);
    }
  }
  return names;
}
}
