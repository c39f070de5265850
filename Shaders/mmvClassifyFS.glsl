// The class of every irradiance voxel, on the GPU: s (>= 0) where the
// opacity table is positive at the voxel's pre-filtered value, -1 where it is
// empty. The same arithmetic as the CPU's mmv::voxelpass::LookupTable (a
// linear interpolation of TableSize entries over the normalised range), so
// that an opacity edit uploads the two small tables and not a class volume.

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
  mmvWrite(vec4(table.x > 0.0 ? max(0.0, table.y) : -1.0));
}
