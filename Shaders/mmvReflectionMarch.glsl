// I(x, w_r) of Zhang & Ma eq. 17: the transmittance along the mirror ray
// through the pre-filtered extinction of the irradiance pass, marched as its
// shadow rays march (mmvMarchTransmittance of mmvShadowRay.glsl, which comes
// before this file with its prelude and mmvCutaway.glsl: with MMV_CUTAWAY,
// what the cropping region and clipping planes remove does not occlude).
// Used per shaded sample by mmvReflection.glsl (MMV_REFLECTION_VISIBILITY 1)
// and per irradiance voxel by mmvReflectionVisibilityFS.glsl (2).

uniform mat3 mmv_visibilityToIndex; // object space -> pre-filtered grid index
uniform vec3 mmv_visibilityOrigin;  // object position of grid index (0, 0, 0)
uniform float mmv_visibilityOffset; // object units along the normal (self-occlusion)

// I(x, w_r): transmittance from object point x, moved off its surface along
// n, to the pre-filtered grid's boundary along w.
float mmvReflectionVisibility(vec3 x, vec3 n, vec3 w)
{
  vec3 start = mmv_visibilityToIndex * (x + mmv_visibilityOffset * n - mmv_visibilityOrigin);
  vec3 indexDir = mmv_visibilityToIndex * w;
  // Clip to the grid: a start outside it may still look back through it.
  vec3 hi = vec3(float(dims[0] - 1), float(dims[1] - 1), float(dims[2] - 1));
  float t0 = 0.0;
  float t1 = 3.0e38;
  for (int a = 0; a < 3; ++a)
  {
    if (indexDir[a] != 0.0)
    {
      float ta = (0.0 - start[a]) / indexDir[a];
      float tb = (hi[a] - start[a]) / indexDir[a];
      t0 = max(t0, min(ta, tb));
      t1 = min(t1, max(ta, tb));
    }
    else if (start[a] < 0.0 || start[a] > hi[a])
    {
      return 1.0;
    }
  }
  if (t1 <= t0)
  {
    return 1.0;
  }
  vec3 entry = start + t0 * indexDir;
  return mmvMarchTransmittance(entry, indexDir, t1 - t0, mmvSampleScalar(entry), 1.0);
}
