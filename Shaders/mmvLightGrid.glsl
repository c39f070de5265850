// The grid a light's shadow rays start from: the irradiance grid itself, or,
// for a dim light (mmv::LightGridStride), every stride-th point of it, which
// mmvLightGridUpsampleFS.glsl then interpolates back. Either way the rays
// march the irradiance grid's pre-filtered values in its index space
// (mmvShadowRay.glsl); only where they start differs. Prepended after
// mmvShadowRay.glsl by the full and piecewise shadow rays.

uniform sampler3D classes;  // s per irradiance voxel, < 0 where it is empty
uniform int targetDims[3];  // the light grid's points per axis
uniform vec3 targetToIndex; // light grid point -> irradiance index, per axis
uniform bool strided;       // off: the light grid is the irradiance grid

ivec3 mmvTargetVoxel()
{
  return ivec3(floor(texCoord * vec2(targetDims[0], targetDims[1])), slice);
}

// Empty: no irradiance voxel the interpolation from this point reaches is
// non-empty (the fill pass decides the empty voxels' values). On a strided
// grid, lightGridClasses holds that, dilated on the CPU.
uniform sampler3D lightGridClasses; // > 0.5 where a strided point is needed

bool mmvLightGridIsEmpty(ivec3 voxel)
{
  return strided ? texelFetch(lightGridClasses, voxel, 0).r < 0.5
                 : texelFetch(classes, voxel, 0).r < 0.0;
}

// The pre-filtered value where the ray starts.
float mmvStartValue(ivec3 voxel, vec3 index)
{
  return strided ? mmvSampleScalar(index) : texelFetch(scalars, voxel, 0).r;
}
