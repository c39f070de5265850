// Multiple scattering of the irradiance volume (Zhang & Ma eq. 15), one
// fragment per voxel of z slice `slice`, four lights at once (RGBA).
//
// Default: one Jacobi sweep of a backward-Euler step (I + dt*A) x = b, A the
// flux-form operator of Filters/vtkIrradianceDiffusion.cxx (face coefficient
// = harmonic mean of the two voxels' s over h^2, missing neighbours give the
// zero-flux boundary):
//   x_new = (b + dt * sum_f c_f x_f) / (1 + dt * sum_f c_f),
// a convex combination, so no sweep can leave [min b, max b].
//
// With MMV_FILL_PASS defined (the final write): empty voxels bordering
// non-empty ones take the mean of those neighbours, as the CPU filter's
// FillEmptyNeighborVoxels() does; the rest is copied.

uniform sampler3D current; // x of the previous sweep (fill pass: the result)
uniform sampler3D classes; // s per voxel, < 0 where the voxel is empty
uniform int dims[3];
uniform int slice;
in vec2 texCoord; // the quad's, at the centre of voxel (i, j)

#ifdef MMV_FILL_PASS

void main()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 value = texelFetch(current, voxel, 0);
  if (texelFetch(classes, voxel, 0).r < 0.0)
  {
    vec4 sum = vec4(0.0);
    int count = 0;
    for (int a = 0; a < 3; ++a)
    {
      for (int side = -1; side <= 1; side += 2)
      {
        ivec3 neighbor = voxel;
        neighbor[a] += side;
        if (neighbor[a] >= 0 && neighbor[a] < dims[a] &&
          texelFetch(classes, neighbor, 0).r >= 0.0)
        {
          sum += texelFetch(current, neighbor, 0);
          ++count;
        }
      }
    }
    if (count > 0)
    {
      value = sum / float(count);
    }
  }
  gl_FragData[0] = value;
}

#else

uniform sampler3D rhs; // b: the irradiance at the start of the time step
uniform vec3 invH2;    // 1 / h^2 per axis, h in data voxels
uniform float dt;

float mmvStrength(ivec3 voxel)
{
  return max(texelFetch(classes, voxel, 0).r, 0.0);
}

// s = 0 on either side blocks the flux (the arithmetic mean would not).
float mmvHarmonicMean(float a, float b)
{
  return (a > 0.0 && b > 0.0) ? 2.0 * a * b / (a + b) : 0.0;
}

void main()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  float s = mmvStrength(voxel);
  vec4 numerator = texelFetch(rhs, voxel, 0);
  float denominator = 1.0;
  if (s > 0.0)
  {
    for (int a = 0; a < 3; ++a)
    {
      for (int side = -1; side <= 1; side += 2)
      {
        ivec3 neighbor = voxel;
        neighbor[a] += side;
        if (neighbor[a] >= 0 && neighbor[a] < dims[a])
        {
          float c = dt * mmvHarmonicMean(s, mmvStrength(neighbor)) * invH2[a];
          numerator += c * texelFetch(current, neighbor, 0);
          denominator += c;
        }
      }
    }
  }
  gl_FragData[0] = numerator / denominator;
}

#endif
