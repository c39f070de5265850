// The transmittance of the lights estimated on a strided light grid
// (mmvLightGrid.glsl), interpolated trilinearly to every irradiance voxel of
// the draw; the write mask keeps the other lights' channels. Empty voxels
// get 0, as the shadow passes give them (the fill pass decides their values).
// One filtered fetch at the point's coordinate, clamped to the grid (as
// clamping to the edge texels does): a CPU rasterizer (llvmpipe) filters in
// about half the time of eight texel fetches and their weights in the shader.

uniform sampler3D lightGrid;    // RGBA32F, the light grid's points, linear
uniform int lightGridDims[3];
uniform vec3 indexToLightGrid;  // irradiance index -> light grid coordinate
uniform int dims[3];
uniform sampler3D classes;      // s per irradiance voxel, < 0 where it is empty

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  if (texelFetch(classes, voxel, 0).r < 0.0)
  {
    mmvWrite(vec4(0.0));
    return;
  }
  vec3 n = vec3(lightGridDims[0], lightGridDims[1], lightGridDims[2]);
  vec3 q = clamp(vec3(voxel) * indexToLightGrid, vec3(0.0), n - 1.0);
  mmvWrite(textureLod(lightGrid, (q + 0.5) / n, 0.0));
}
