// The class of every irradiance voxel, on the GPU: s (>= 0) where the
// opacity table is positive at the voxel's pre-filtered value; where it is
// empty, -1 - m, m the bits of its non-empty face neighbours (bit 2 a for
// the one below on axis a, 2 a + 1 above), which the final write averages
// (mmv::EmptyVoxelClass in vtkIrradianceEstimatorInternals.h). The same
// arithmetic as the CPU's mmv::LookupTable (Filters/vtkTableLookup.h: a
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

bool mmvIsNonEmpty(ivec3 voxel)
{
  return mmvLookupTables(texelFetch(classifyScalars, voxel, 0).r).x > 0.0;
}

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec2 table = mmvLookupTables(texelFetch(classifyScalars, voxel, 0).r);
  float voxelClass = max(0.0, table.y);
  if (!(table.x > 0.0))
  {
    int neighbors = 0;
    for (int a = 0; a < 3; ++a)
    {
      for (int side = 0; side < 2; ++side)
      {
        ivec3 neighbor = voxel;
        neighbor[a] += 2 * side - 1;
        if (neighbor[a] >= 0 && neighbor[a] < dims[a] && mmvIsNonEmpty(neighbor))
        {
          neighbors |= 1 << (2 * a + side);
        }
      }
    }
    voxelClass = -1.0 - float(neighbors);
  }
  mmvWrite(vec4(voxelClass));
}
