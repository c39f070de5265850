// The Henyey-Greenstein phase function relative to isotropic scattering,
// 4 pi HG(g, cos) = (1 - g^2) / (1 + g^2 - 2 g cos)^1.5: 1 at g = 0 (exactly,
// in float), so the particle term of the isotropic model is its g = 0 case.
// Mirrors mmvHenyeyGreensteinRelative in Filters/vtkMultiMaterialPhaseFunction.h;
// TestShaderMirror runs both. Compiled in only when some material has g != 0
// (MMV_USE_ANISOTROPY).
//
// cosTheta: between the light's travel direction and the scattered one,
// -dot(v, l) for v toward the viewer and l toward the light.

float mmvHenyeyGreensteinRelative(float g, float cosTheta)
{
  // |g| <= 0.99 (the parameter's hard limits) keeps the denominator >= 1e-4.
  float denominator = 1.0 + g * g - 2.0 * g * cosTheta;
  return (1.0 - g * g) / (denominator * sqrt(denominator));
}
