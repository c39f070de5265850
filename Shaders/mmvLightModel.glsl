// Light-source terms of Zhang & Ma eqs. 11-14. Mirrors
// Rendering/vtkMultiMaterialLightModel.h function for function.
// Light kinds: 0 directional, 1 point, 2 spot (cone half-angle, as vtkLight).

// eq. 12: epsilon^2 / max(epsilon^2, d^2); radius 0 gives 1 at the light and
// 0 elsewhere (the formula's limit) instead of 0/0.
float mmvPointFalloff(float radius, float distance2)
{
  float e2 = radius * radius;
  return distance2 <= e2 ? 1.0 : e2 / distance2;
}

// eq. 14: 1 inside the open cone, 0 outside and on its edge.
float mmvSpotVisibility(vec3 lightToPoint, vec3 axis, float cosCone)
{
  float len = length(lightToPoint);
  if (len <= 0.0)
  {
    return 1.0;
  }
  return dot(lightToPoint / len, axis) > cosCone ? 1.0 : 0.0;
}

// Unit direction and distance from x toward the light; distance -1 for
// directional lights (infinitely far).
vec3 mmvDirectionToLight(int kind, vec3 lightPosition, vec3 toLight, vec3 x, out float lightDistance)
{
  if (kind == 0)
  {
    lightDistance = -1.0;
    return toLight;
  }
  vec3 d = lightPosition - x;
  lightDistance = length(d);
  return lightDistance > 0.0 ? d / lightDistance : vec3(0.0, 0.0, 1.0);
}

// Unshadowed part of I_k(x) (eqs. 11-13 without the transmittance).
float mmvLightGeometryTerm(int kind, vec3 lightPosition, vec3 spotAxis, float cosCone,
  float radius, vec3 x)
{
  if (kind == 0)
  {
    return 1.0;
  }
  vec3 lightToPoint = x - lightPosition;
  float term = mmvPointFalloff(radius, dot(lightToPoint, lightToPoint));
  if (kind == 2)
  {
    term *= mmvSpotVisibility(lightToPoint, spotAxis, cosCone);
  }
  return term;
}
