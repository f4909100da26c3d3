#pragma once
// A glTF 2.0 metallic-roughness material read as the lecture's coefficients
// (docs/formulas.md section 7.3), so that a glTF file's materials shade in the lecture model.
#include "Vec3.h"

namespace shadelab
{
struct LectureCoefficients
{
  Rgb kd{ 0.0 };
  Rgb ks{ 0.0 };
  double shininess = 0;
};

/// The glTF 2.0 specification's split (Appendix B, "BRDF Implementation"): the diffuse colour
/// is the base colour times (1 - metallic), the specular reflectance at normal incidence F0 is
/// 0.04 blended toward the base colour by metallic; and the Blinn-Phong exponent whose lobe
/// matches a Beckmann lobe of alpha = roughness^2, eta = 2 / alpha^2 - 2 (Walter, Marschner, Li
/// and Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, section
/// 5.2). A roughness below 0.03 is taken as 0.03, whose eta, about 2.5e6, is already a mirror's.
LectureCoefficients lectureCoefficients(const Rgb& baseColor, double metallic, double roughness);
}
