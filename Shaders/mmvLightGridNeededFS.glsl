// Which points of a strided light grid (mmvLightGrid.glsl) a non-empty
// irradiance voxel needs: 1 where the trilinear interpolation to some
// non-empty voxel reads the point, else 0. The CPU twin and what it mirrors:
// vtkIrradianceEstimator's LightGridNeededOnCPU. Per axis, the voxels that
// read point p are one run of indices, given by `neededRanges` (made on the
// CPU from the same per-axis arithmetic, so float rounding cannot move a
// boundary); the point is needed when a voxel of the box they span is
// non-empty.

uniform sampler3D classes;      // s per irradiance voxel, < 0 where it is empty
uniform sampler2D neededRanges; // row a: (first, last) voxel index along axis a per point
uniform int lightDims[3];       // the light grid's points per axis

void mmvVoxelMain()
{
  ivec3 p = ivec3(floor(texCoord * vec2(lightDims[0], lightDims[1])), slice);
  ivec2 rx = ivec2(texelFetch(neededRanges, ivec2(p.x, 0), 0).rg);
  ivec2 ry = ivec2(texelFetch(neededRanges, ivec2(p.y, 1), 0).rg);
  ivec2 rz = ivec2(texelFetch(neededRanges, ivec2(p.z, 2), 0).rg);
  for (int k = rz.x; k <= rz.y; ++k)
  {
    for (int j = ry.x; j <= ry.y; ++j)
    {
      for (int i = rx.x; i <= rx.y; ++i)
      {
        if (texelFetch(classes, ivec3(i, j, k), 0).r >= 0.0)
        {
          mmvWrite(vec4(1.0));
          return;
        }
      }
    }
  }
  mmvWrite(vec4(0.0));
}
