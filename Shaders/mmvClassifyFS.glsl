// The class of every irradiance voxel, on the GPU: s (>= 0) where the
// opacity table is positive at the voxel's pre-filtered value, -1 where it is
// empty. The same arithmetic as the CPU's mmv::voxelpass::LookupTable (a
// linear interpolation of TableSize entries over the normalised range), so
// that an opacity edit uploads the two small tables and not a class volume.
// With MMV_COUNT_NON_EMPTY the empty voxels are not written, so the number
// of voxels written (an occlusion query, or the compute pass's atomic
// counter) is the number of non-empty ones; the others are rewritten with
// the value the class pass gave them.

uniform sampler3D classifyScalars; // normalised pre-filtered values (R32F)
uniform sampler2D classifyTables;  // TableSize x 1, (opacity, scattering) per entry
uniform int classifyTableSize;
uniform int dims[3];

vec2 mmvLookupTables(float t)
{
  int n = classifyTableSize;
  float x = min(max(t, 0.0), 1.0) * float(n - 1);
  int i0 = min(int(x), n - 2);
  float f = x - float(i0);
  vec2 a = texelFetch(classifyTables, ivec2(i0, 0), 0).rg;
  vec2 b = texelFetch(classifyTables, ivec2(i0 + 1, 0), 0).rg;
  return (1.0 - f) * a + f * b;
}

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec2 table = mmvLookupTables(texelFetch(classifyScalars, voxel, 0).r);
  float s = table.x > 0.0 ? max(0.0, table.y) : -1.0;
#ifdef MMV_COUNT_NON_EMPTY
  if (s < 0.0)
  {
    return;
  }
#endif
  mmvWrite(vec4(s));
}
