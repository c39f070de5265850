// The transmittance of the lights estimated on a strided light grid
// (mmvLightGrid.glsl), interpolated trilinearly to every irradiance voxel of
// the draw; the write mask keeps the other lights' channels. Empty voxels
// get 0, as the shadow passes give them (the fill pass decides their values).

uniform sampler3D lightGrid;    // RGBA32F, the light grid's points
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
  ivec3 last = ivec3(lightGridDims[0] - 1, lightGridDims[1] - 1, lightGridDims[2] - 1);
  vec3 q = clamp(vec3(voxel) * indexToLightGrid, vec3(0.0), vec3(last));
  ivec3 i0 = min(ivec3(q), max(last - 1, ivec3(0)));
  ivec3 i1 = min(i0 + 1, last);
  vec3 f = q - vec3(i0);
  vec4 c00 = mix(texelFetch(lightGrid, i0, 0), texelFetch(lightGrid, ivec3(i1.x, i0.y, i0.z), 0), f.x);
  vec4 c10 = mix(texelFetch(lightGrid, ivec3(i0.x, i1.y, i0.z), 0),
    texelFetch(lightGrid, ivec3(i1.x, i1.y, i0.z), 0), f.x);
  vec4 c01 = mix(texelFetch(lightGrid, ivec3(i0.x, i0.y, i1.z), 0),
    texelFetch(lightGrid, ivec3(i1.x, i0.y, i1.z), 0), f.x);
  vec4 c11 = mix(texelFetch(lightGrid, ivec3(i0.x, i1.y, i1.z), 0), texelFetch(lightGrid, i1, 0), f.x);
  mmvWrite(mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z));
}
