// Full shadow rays of the irradiance volume (Zhang & Ma §5.1), one fragment
// per voxel of z slice `slice`, up to four lights per output texture. Mirrors
// ShadowTransmittance() of Filters/vtkIrradianceVolumeFilter.cxx line for
// line. Prepended by the pass: the material prelude, the shadow-ray constants
// of mmv::ShadowRayGLSLPrelude(), the light uniforms of
// mmv::LightUniformDeclarations() (vtkMultiMaterialLightUniforms.h, the
// ray cast's layout), mmvLightModel.glsl, mmvShadowRay.glsl and
// mmvLightGrid.glsl: the fragment's voxel is a point of the lights' grid.

uniform vec3 origin;
uniform mat3 indexToWorld;
uniform mat3 worldToIndex;
uniform int numberOfLights;
uniform bool computeEmptyVoxels; // off (default): empty voxels cost nothing
uniform int lightMask; // bit k: light k needs its irradiance (the others keep theirs)
// The lights: mmv::LightUniformDeclarations(), prepended by the pass.

// Transmittance from voxel `start` toward the light: a full shadow ray, to the
// boundary (or the light).
float mmvShadowTransmittance(int light, vec3 start, vec3 x, float startValue)
{
  float lightDistance;
  vec3 dir = mmvDirectionToLight(mmv_lightKind[light], mmv_lightPosition[light],
    mmv_lightToLight[light], x, lightDistance);
  vec3 indexDir = worldToIndex * dir;
  float end = mmvExitDistance(start, indexDir);
  if (lightDistance >= 0.0)
  {
    end = min(end, lightDistance);
  }
  return mmvMarchTransmittance(start, indexDir, end, startValue, 1.0);
}

void mmvVoxelMain()
{
  ivec3 voxel = mmvTargetVoxel();
  vec3 start = vec3(voxel) * targetToIndex;
  vec4 irradiance = vec4(0.0);
  if (computeEmptyVoxels || !mmvLightGridIsEmpty(voxel))
  {
    vec3 x = origin + indexToWorld * start;
    float startValue = mmvStartValue(voxel, start);
    for (int light = 0; light < numberOfLights; ++light)
    {
      if (((lightMask >> light) & 1) == 0)
      {
        continue;
      }
      float geometry = mmvLightGeometryTerm(mmv_lightKind[light], mmv_lightPosition[light],
        mmv_lightSpotAxis[light], mmv_lightCosCone[light], mmv_lightSpotExponent[light],
        mmv_lightAttenuation[light], mmv_lightRadius[light], x);
      if (geometry > 0.0) // outside a spot light's cone: no ray
      {
        irradiance[light] = geometry * mmvShadowTransmittance(light, start, x, startValue);
      }
    }
  }
  mmvWrite(irradiance);
}
