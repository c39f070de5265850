// Transfers between the irradiance grid and the coarser diffusion grid
// (mmv::DiffuseIrradianceOnDiffusionGrid in Filters/vtkIrradianceDiffusion.cxx
// computes the same on the CPU), four lights at once (RGBA), one fragment per
// target voxel of layer `slice`.
//
// MMV_RESTRICT (target: diffusion grid): the mean of the irradiance over the
// block's voxels with s > 0 (0 when none).
// Otherwise (prolongation, target: irradiance grid): voxels with s > 0 add
// the change the diffusion made (mmvDiffusionFS.glsl, MMV_CHANGE),
// interpolated trilinearly at their coarse coordinate (i - (f - 1) / 2) / f
// over the corner blocks that scatter, and are clamped at 0.

uniform sampler3D fine;    // irradiance before the diffusion (irradiance grid)
uniform sampler3D classes; // s per voxel, < 0 where the voxel is empty
uniform int dims[3];       // irradiance grid
uniform int factor[3];
uniform int coarseDims[3];

#ifdef MMV_RESTRICT

void mmvVoxelMain()
{
  ivec3 block = ivec3(floor(texCoord * vec2(coarseDims[0], coarseDims[1])), slice);
  ivec3 first = block * ivec3(factor[0], factor[1], factor[2]);
  ivec3 last = min(first + ivec3(factor[0], factor[1], factor[2]), ivec3(dims[0], dims[1], dims[2]));
  vec4 sum = vec4(0.0);
  int count = 0;
  for (int k = first.z; k < last.z; ++k)
  {
    for (int j = first.y; j < last.y; ++j)
    {
      for (int i = first.x; i < last.x; ++i)
      {
        if (texelFetch(classes, ivec3(i, j, k), 0).r > 0.0)
        {
          sum += texelFetch(fine, ivec3(i, j, k), 0);
          ++count;
        }
      }
    }
  }
  mmvWrite(count > 0 ? sum / float(count) : vec4(0.0));
}

#else

uniform sampler3D change; // mmvDiffusionFS.glsl's MMV_CHANGE result, linear
uniform sampler3D blocks; // alpha: 1 where the block scatters, linear

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 value = texelFetch(fine, voxel, 0);
  if (texelFetch(classes, voxel, 0).r > 0.0)
  {
    vec3 f = vec3(factor[0], factor[1], factor[2]);
    vec3 n = vec3(coarseDims[0], coarseDims[1], coarseDims[2]);
    vec3 u = clamp((vec3(voxel) - 0.5 * (f - 1.0)) / f, vec3(0.0), n - 1.0);
    // Trilinear over the corner blocks that scatter, renormalised: the
    // change is 0 at the others, and the filtered flag sums the weights of
    // those that scatter.
    vec3 coordinate = (u + 0.5) / n;
    float weights = texture(blocks, coordinate).a;
    if (weights > 0.0)
    {
      value = max(value + texture(change, coordinate) / weights, vec4(0.0));
    }
  }
  mmvWrite(value);
}

#endif
