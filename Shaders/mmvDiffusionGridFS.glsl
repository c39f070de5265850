// Transfers between the irradiance grid and the coarser diffusion grid
// (mmv::DiffuseIrradianceOnDiffusionGrid in Filters/vtkIrradianceDiffusion.cxx
// computes the same on the CPU), four lights at once (RGBA), one fragment per
// target voxel of layer `slice`.
//
// MMV_RESTRICT (target: diffusion grid): the mean of the irradiance over the
// block's voxels with s > 0 (0 when none).
// Otherwise (prolongation, target: irradiance grid): voxels with s > 0 add
// the change the diffusion made, interpolated trilinearly at their coarse
// coordinate (i - (f - 1) / 2) / f over the corner blocks that scatter, and
// are clamped at 0.

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

uniform sampler3D after;          // the diffused irradiance (diffusion grid)
uniform sampler3D before;         // the restricted irradiance (diffusion grid)
uniform sampler3D coarseStrength; // s per block, 0 where no voxel scatters

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 value = texelFetch(fine, voxel, 0);
  if (texelFetch(classes, voxel, 0).r > 0.0)
  {
    vec3 f = vec3(factor[0], factor[1], factor[2]);
    ivec3 n = ivec3(coarseDims[0], coarseDims[1], coarseDims[2]);
    vec3 u = clamp((vec3(voxel) - 0.5 * (f - 1.0)) / f, vec3(0.0), vec3(n - 1));
    ivec3 lo = min(ivec3(u), n - 1);
    ivec3 hi = min(lo + 1, n - 1);
    vec3 w = u - vec3(lo);
    // Trilinear over the corner blocks that scatter, renormalised.
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int corner = 0; corner < 8; ++corner)
    {
      bvec3 upper = bvec3((corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0);
      ivec3 c = ivec3(upper.x ? hi.x : lo.x, upper.y ? hi.y : lo.y, upper.z ? hi.z : lo.z);
      float weight = (upper.x ? w.x : 1.0 - w.x) * (upper.y ? w.y : 1.0 - w.y) *
        (upper.z ? w.z : 1.0 - w.z);
      if (weight > 0.0 && texelFetch(coarseStrength, c, 0).r > 0.0)
      {
        sum += weight * (texelFetch(after, c, 0) - texelFetch(before, c, 0));
        weights += weight;
      }
    }
    if (weights > 0.0)
    {
      value = max(value + sum / weights, vec4(0.0));
    }
  }
  mmvWrite(value);
}

#endif
