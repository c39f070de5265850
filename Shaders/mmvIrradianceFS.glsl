// Shadow rays of the irradiance volume (Zhang & Ma §5.1), one fragment per
// voxel of z slice `slice`, up to four lights per output texture. Mirrors
// ShadowTransmittance() of Filters/vtkIrradianceVolumeFilter.cxx line for
// line. Prepended by the pass: the material prelude, the shadow-ray constants
// of mmv::ShadowRayGLSLPrelude() (MMV_MIN_TRANSMITTANCE, MMV_STEP_TOLERANCE,
// MMV_REST_TOLERANCE) and mmvLightModel.glsl.

uniform sampler3D scalars;     // normalised pre-filtered values, linear
uniform sampler3D classes;     // s per voxel, < 0 where the voxel is empty
uniform sampler2D shadowTable; // I_sigma(t1 along x, t2 along y), bilinear
uniform float tableSize;
uniform int dims[3];
flat in int slice; // the layer (mmvLayerGS.glsl)
in vec2 texCoord; // the quad's, at the centre of voxel (i, j)
uniform vec3 origin;
uniform mat3 indexToWorld;
uniform mat3 worldToIndex;
uniform float stepLength;
uniform int numberOfLights;
uniform bool computeEmptyVoxels; // off (default): empty voxels cost nothing
uniform int lightMask; // bit k: light k needs its irradiance (the others keep theirs)
uniform int lightKind[4];
uniform vec3 lightPosition[4];
uniform vec3 lightToLight[4];
uniform vec3 lightSpotAxis[4];
uniform float lightCosCone[4];
uniform float lightRadius[4];

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

// Transmittance from voxel `start` toward the light: pre-integrated segments
// of stepLength, then one shorter segment ending exactly on the boundary (or
// at the light).
float mmvShadowTransmittance(int light, vec3 start, vec3 x, float startValue)
{
  float lightDistance;
  vec3 dir = mmvDirectionToLight(lightKind[light], lightPosition[light], lightToLight[light], x,
    lightDistance);
  vec3 indexDir = worldToIndex * dir;
  float end = mmvExitDistance(start, indexDir);
  if (lightDistance >= 0.0)
  {
    end = min(end, lightDistance);
  }
  float h = stepLength;
  int steps = int(floor(end / h + MMV_STEP_TOLERANCE));
  float previous = startValue;
  float transmittance = 1.0;
  for (int n = 1; n <= steps; ++n)
  {
    float next = mmvSampleScalar(start + (float(n) * h) * indexDir);
    transmittance *= 1.0 - mmvShadowOpacity(previous, next);
    if (transmittance < MMV_MIN_TRANSMITTANCE)
    {
      return transmittance;
    }
    previous = next;
  }
  float rest = end - float(steps) * h;
  if (rest > MMV_REST_TOLERANCE * h)
  {
    float next = mmvSampleScalar(start + end * indexDir);
    float alpha = mmvShadowOpacity(previous, next);
    // Optical depth is linear in the segment length for a linear value ramp.
    transmittance *= pow(max(0.0, 1.0 - alpha), rest / h);
  }
  return transmittance;
}

void main()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 irradiance = vec4(0.0);
  if (computeEmptyVoxels || texelFetch(classes, voxel, 0).r >= 0.0)
  {
    vec3 start = vec3(voxel);
    vec3 x = origin + indexToWorld * start;
    float startValue = texelFetch(scalars, voxel, 0).r;
    for (int light = 0; light < numberOfLights; ++light)
    {
      if (((lightMask >> light) & 1) == 0)
      {
        continue;
      }
      float geometry = mmvLightGeometryTerm(lightKind[light], lightPosition[light],
        lightSpotAxis[light], lightCosCone[light], lightRadius[light], x);
      if (geometry > 0.0) // outside a spot light's cone: no ray
      {
        irradiance[light] = geometry * mmvShadowTransmittance(light, start, x, startValue);
      }
    }
  }
  gl_FragData[0] = irradiance;
}
