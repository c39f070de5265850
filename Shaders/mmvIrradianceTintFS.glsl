// The tint K of one light (vtkMultiMaterialParameters.h, a non-white
// transmission colour), one fragment per voxel of the tint grid (every
// mmv::TintResolutionDivisor-th irradiance point): a full shadow ray of the
// selective extinction through the irradiance grid's pre-filtered values.
// Mirrors ComputeTint() of Filters/vtkIrradianceVolumeFilter.cxx. Prepended
// as mmvIrradianceFS.glsl, with MMV_TINT; light 0 of the uniforms is the
// light.

uniform int tintDims[3];
uniform vec3 tintToIndex; // tint voxel -> irradiance index, per axis
uniform vec3 origin;
uniform mat3 indexToWorld;
uniform mat3 worldToIndex;

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(tintDims[0], tintDims[1])), slice);
  vec3 start = vec3(voxel) * tintToIndex;
  vec3 x = origin + indexToWorld * start;
  float lightDistance;
  vec3 dir = mmvDirectionToLight(
    mmv_lightKind[0], mmv_lightPosition[0], mmv_lightToLight[0], x, lightDistance);
  vec3 indexDir = worldToIndex * dir;
  float end = mmvExitDistance(start, indexDir);
  if (lightDistance >= 0.0)
  {
    end = min(end, lightDistance);
  }
  mmvWrite(vec4(mmvMarchTint(start, indexDir, end, mmvSampleScalar(start)), 1.0));
}
