// Light-source terms (eqs. 11-14 with VTK's light conventions). Mirrors
// Filters/vtkMultiMaterialLightModel.h function for function; see there
// for the conventions. Light kinds: MMV_DIRECTIONAL_LIGHT, MMV_POINT_LIGHT,
// MMV_SPOT_LIGHT (cone half-angle, as vtkLight). Prepended after the prelude
// (mmv::MaterialGLSLPrelude) that defines them and
// MMV_MIN_ATTENUATION_DENOMINATOR.

// eq. 12: epsilon^2 / max(epsilon^2, d^2).
float mmvPointFalloff(float radius, float distance2)
{
  float e2 = radius * radius;
  return distance2 <= e2 ? 1.0 : e2 / distance2;
}

// VTK's Phong: 1 / (c0 + c1 d + c2 d^2), the polynomial clamped below.
float mmvAttenuationFalloff(vec3 attenuation, float distance2)
{
  float d = sqrt(distance2);
  float p = attenuation.x + attenuation.y * d + attenuation.z * distance2;
  return 1.0 / (p > MMV_MIN_ATTENUATION_DENOMINATOR ? p : MMV_MIN_ATTENUATION_DENOMINATOR);
}

// eq. 12 when radius > 0, else VTK's attenuation.
float mmvDistanceFalloff(float radius, vec3 attenuation, float distance2)
{
  return radius > 0.0 ? mmvPointFalloff(radius, distance2)
                      : mmvAttenuationFalloff(attenuation, distance2);
}

// VTK's spot cone: cos^exponent inside (edge included), 0 outside; exponent
// 0 is the hard cone of eq. 14.
float mmvSpotFactor(vec3 lightToPoint, vec3 axis, float cosCone, float exponent)
{
  float len = length(lightToPoint);
  if (len <= 0.0)
  {
    return 1.0;
  }
  float c = dot(lightToPoint / len, axis);
  if (!(c >= cosCone))
  {
    return 0.0;
  }
  return exponent > 0.0 ? pow(c > 0.0 ? c : 0.0, exponent) : 1.0;
}

// eq. 14: the hard cone.
float mmvSpotVisibility(vec3 lightToPoint, vec3 axis, float cosCone)
{
  return mmvSpotFactor(lightToPoint, axis, cosCone, 0.0);
}

// Unit direction and distance from x toward the light; distance -1 for
// directional lights (infinitely far).
vec3 mmvDirectionToLight(int kind, vec3 lightPosition, vec3 toLight, vec3 x, out float lightDistance)
{
  if (kind == MMV_DIRECTIONAL_LIGHT)
  {
    lightDistance = -1.0;
    return toLight;
  }
  vec3 d = lightPosition - x;
  lightDistance = length(d);
  return lightDistance > 0.0 ? d / lightDistance : vec3(0.0, 0.0, 1.0);
}

// Unshadowed part of I_k(x) (eqs. 11-14 without the transmittance).
float mmvLightGeometryTerm(int kind, vec3 lightPosition, vec3 spotAxis, float cosCone,
  float spotExponent, vec3 attenuation, float radius, vec3 x)
{
  if (kind == MMV_DIRECTIONAL_LIGHT)
  {
    return 1.0;
  }
  vec3 lightToPoint = x - lightPosition;
  float term = mmvDistanceFalloff(radius, attenuation, dot(lightToPoint, lightToPoint));
  if (kind == MMV_SPOT_LIGHT)
  {
    term *= mmvSpotFactor(lightToPoint, spotAxis, cosCone, spotExponent);
  }
  return term;
}
