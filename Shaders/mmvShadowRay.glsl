// Shadow-ray marching through the pre-filtered volume (Zhang & Ma §5.1),
// shared by the full (mmvIrradianceFS.glsl) and piecewise
// (mmvPiecewiseShadowFS.glsl) shadow rays. Mirrors MarchTransmittance() of
// Filters/vtkIrradianceVolumeFilter.cxx line for line. Needs the shadow-ray
// constants of mmv::ShadowRayGLSLPrelude() (MMV_MIN_TRANSMITTANCE,
// MMV_STEP_TOLERANCE, MMV_REST_TOLERANCE) and mmvCutaway.glsl: a segment
// whose midpoint the cropping region or a clipping plane removes is empty.

uniform sampler3D scalars;     // normalised pre-filtered values, linear
uniform sampler2D shadowTable; // I_sigma(t1 along x, t2 along y), bilinear
uniform float tableSize;
uniform int dims[3];
uniform float stepLength;

// Trilinear value at a continuous index, as the CPU interpolates it.
float mmvSampleScalar(vec3 index)
{
  return texture(scalars, (index + 0.5) / vec3(dims[0], dims[1], dims[2])).r;
}

float mmvShadowOpacity(float t1, float t2)
{
  vec2 x = clamp(vec2(t1, t2), 0.0, 1.0) * (tableSize - 1.0);
  return texture(shadowTable, (x + 0.5) / tableSize).r;
}

// Distance along index-space direction d from p (inside) to the grid's box.
float mmvExitDistance(vec3 p, vec3 d)
{
  float t = 3.0e38;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 0.0)
    {
      t = min(t, (float(dims[a] - 1) - p[a]) / d[a]);
    }
    else if (d[a] < 0.0)
    {
      t = min(t, -p[a] / d[a]);
    }
  }
  return max(t, 0.0);
}

// Transmittance over [0, end] of the ray from index `start` along indexDir:
// pre-integrated segments of stepLength, then one shorter segment ending
// exactly at `end`, starting from `transmittance` (what lies beyond `end`).
float mmvMarchTransmittance(vec3 start, vec3 indexDir, float end, float startValue,
  float transmittance)
{
  float h = stepLength;
  int steps = int(floor(end / h + MMV_STEP_TOLERANCE));
  float previous = startValue;
  for (int n = 1; n <= steps; ++n)
  {
    if (transmittance < MMV_MIN_TRANSMITTANCE)
    {
      return transmittance;
    }
    float next = mmvSampleScalar(start + (float(n) * h) * indexDir);
    float alpha = mmvIsCut(start + ((float(n) - 0.5) * h) * indexDir)
      ? 0.0 : mmvShadowOpacity(previous, next);
    transmittance *= 1.0 - alpha;
    previous = next;
  }
  float rest = end - float(steps) * h;
  if (rest > MMV_REST_TOLERANCE * h && transmittance >= MMV_MIN_TRANSMITTANCE)
  {
    float next = mmvSampleScalar(start + end * indexDir);
    float alpha = mmvIsCut(start + (0.5 * (float(steps) * h + end)) * indexDir)
      ? 0.0 : mmvShadowOpacity(previous, next);
    // Optical depth is linear in the segment length for a linear value ramp.
    transmittance *= pow(max(0.0, 1.0 - alpha), rest / h);
  }
  return transmittance;
}

#ifdef MMV_TINT
uniform sampler2D tintTable; // I_tau per channel (rgb) of (t1, t2), bilinear

vec3 mmvTintOpacity(float t1, float t2)
{
  vec2 x = clamp(vec2(t1, t2), 0.0, 1.0) * (tableSize - 1.0);
  return texture(tintTable, (x + 0.5) / tableSize).rgb;
}

// The tint K over [0, end] (vtkMultiMaterialParameters.h): per channel the
// transmittance of the selective extinction alone, marched as
// mmvMarchTransmittance; stops once every channel is below
// MMV_MIN_TRANSMITTANCE. Mirrors MarchTint() of
// Filters/vtkIrradianceVolumeFilter.cxx.
vec3 mmvMarchTint(vec3 start, vec3 indexDir, float end, float startValue)
{
  float h = stepLength;
  int steps = int(floor(end / h + MMV_STEP_TOLERANCE));
  float previous = startValue;
  vec3 tint = vec3(1.0);
  for (int n = 1; n <= steps; ++n)
  {
    if (max(tint.r, max(tint.g, tint.b)) < MMV_MIN_TRANSMITTANCE)
    {
      return tint;
    }
    float next = mmvSampleScalar(start + (float(n) * h) * indexDir);
    vec3 alpha = mmvIsCut(start + ((float(n) - 0.5) * h) * indexDir)
      ? vec3(0.0) : mmvTintOpacity(previous, next);
    tint *= 1.0 - alpha;
    previous = next;
  }
  float rest = end - float(steps) * h;
  if (rest > MMV_REST_TOLERANCE * h && max(tint.r, max(tint.g, tint.b)) >= MMV_MIN_TRANSMITTANCE)
  {
    float next = mmvSampleScalar(start + end * indexDir);
    vec3 alpha = mmvIsCut(start + (0.5 * (float(steps) * h + end)) * indexDir)
      ? vec3(0.0) : mmvTintOpacity(previous, next);
    tint *= pow(max(vec3(0.0), 1.0 - alpha), vec3(rest / h));
  }
  return tint;
}
#endif
