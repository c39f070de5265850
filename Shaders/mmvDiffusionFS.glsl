// Multiple scattering of the irradiance volume (Zhang & Ma eq. 15), one
// fragment per voxel of z slice `slice`, four lights at once (RGBA).
//
// Without a define (ExponentialDiffusion off): one Jacobi sweep, on the
// diffusion grid (vtkIrradianceDiffusion.h), of a backward-Euler step (I + dt*A) x = b, A the
// flux-form operator of Filters/vtkIrradianceDiffusion.cxx (face coefficient
// = harmonic mean of the two voxels' s over h^2, missing neighbours give the
// zero-flux boundary):
//   J(x) = (C b + dt * sum_f c_f x_f) / (C + dt * sum_f c_f),
// C the block's capacity (a convex combination, so a plain sweep cannot
// leave [min b, max b]), accelerated by Chebyshev weights:
//   x_new = x_previous + omega * (J(x) - x_previous).
// A sub-step stops once every |J(x) - x| <= (1 - rho) tol, which bounds the
// error |x - x*| by tol (J contracts by rho); checked only in sub-steps whose
// error bound asks for many sweeps (vtkIrradianceEstimator.cxx).
//
// With MMV_FILL_PASS defined (the final write): empty voxels bordering
// non-empty ones take the mean of those neighbours, as the CPU filter's
// FillEmptyNeighborVoxels() does; the rest is copied. The classification
// gives each empty voxel the bits of its non-empty neighbours. With
// MMV_SCENE_TRANSMITTANCE as well, every voxel is multiplied by the
// transmittance toward its lights through the other volumes of the scene
// (vtkSceneTransmittance.h), read once here rather than per ray-cast sample.

uniform sampler3D current; // x of the previous sweep (fill pass: the result)
uniform sampler3D classes; // s per voxel, < 0 where the voxel is empty
                           // (Jacobi sweeps: the diffusion grid's strength)
uniform int dims[3];

// The diffusion grid's s per block (sweeps and the exponential's steps).
float mmvStrength(ivec3 voxel)
{
  return max(texelFetch(classes, voxel, 0).r, 0.0);
}

// s = 0 on either side blocks the flux (the arithmetic mean would not).
float mmvHarmonicMean(float a, float b)
{
  return (a > 0.0 && b > 0.0) ? 2.0 * a * b / (a + b) : 0.0;
}

// Over the faces of `voxel` (s > 0) that exchange light: sum of c_f x_f and of
// c_f, c_f = harmonic mean of the two s over h^2 (inverseH2: 1 / h^2 per
// axis). Blocks that do not scatter are never drawn: never read them.
void mmvNeighborSums(ivec3 voxel, float s, sampler3D x, vec3 inverseH2, out vec4 weighted,
  out float total)
{
  weighted = vec4(0.0);
  total = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    for (int side = -1; side <= 1; side += 2)
    {
      ivec3 neighbor = voxel;
      neighbor[a] += side;
      if (neighbor[a] >= 0 && neighbor[a] < dims[a])
      {
        float c = mmvHarmonicMean(s, mmvStrength(neighbor)) * inverseH2[a];
        if (c > 0.0)
        {
          weighted += c * texelFetch(x, neighbor, 0);
          total += c;
        }
      }
    }
  }
}

#ifdef MMV_FILL_PASS

#ifdef MMV_SCENE_TRANSMITTANCE
uniform sampler3D sceneTransmittance; // one channel per light, on a coarser grid
uniform vec3 sceneScale; // this grid's texture coordinates -> the coarser one's
uniform vec3 sceneBias;  // (the same first and last voxel centres)
#endif

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 value = texelFetch(current, voxel, 0);
  float voxelClass = texelFetch(classes, voxel, 0).r;
  if (voxelClass < 0.0)
  {
    // Empty voxels hold 0 unless they border non-empty ones (piecewise
    // shadow rays computed them too: later chunks read them), which take
    // their mean. The loop runs over the set bits only: a software
    // rasterizer executes a branch's body for every fragment, but leaves a
    // loop once no fragment of the batch has bits left.
    int neighbors = int(-voxelClass) - 1;
    vec4 sum = vec4(0.0);
    int count = 0;
    for (int bit = 0; neighbors != 0; ++bit, neighbors >>= 1)
    {
      if ((neighbors & 1) != 0)
      {
        ivec3 neighbor = voxel;
        neighbor[bit >> 1] += 2 * (bit & 1) - 1;
        sum += texelFetch(current, neighbor, 0);
        ++count;
      }
    }
    value = count > 0 ? sum / float(count) : vec4(0.0);
  }
#ifdef MMV_SCENE_TRANSMITTANCE
  vec3 own = (vec3(voxel) + 0.5) / vec3(dims[0], dims[1], dims[2]);
  value *= textureLod(sceneTransmittance, own * sceneScale + sceneBias, 0.0);
#endif
  mmvWrite(value);
}

#elif defined(MMV_EXPONENTIAL)

// With MMV_EXPONENTIAL (ExponentialDiffusion, vtkIrradianceDiffusion.h):
// one step of the Clenshaw recurrence of exp(-T C^-1 A) = sum_k c_k T_k(B),
// B = I - C^-1 A / R (R the rate bound), mirroring
// DiffusionSystem::Clenshaw() of Filters/vtkIrradianceDiffusion.cxx:
//   out = alpha u0 + beta B(current) + gamma previous.
// A voxel that exchanges nothing keeps u0 exactly.
uniform sampler3D initial;  // u0: the restricted irradiance
uniform sampler3D previous; // b_k+2
uniform float alpha;
uniform float beta;
uniform float gammaWeight;
uniform float invRate;      // 1 / R
uniform vec3 invH2;         // 1 / h^2 per axis, h in data voxels

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  float s = mmvStrength(voxel);
  vec4 u0 = texelFetch(initial, voxel, 0);
  vec4 b = texelFetch(current, voxel, 0);
  vec4 weighted = vec4(0.0);
  float total = 0.0;
  if (s > 0.0)
  {
    mmvNeighborSums(voxel, s, current, invH2, weighted, total);
  }
  vec4 flux = weighted - total * b;
  bool exchanges = total > 0.0;
  if (!exchanges)
  {
    mmvWrite(u0);
    return;
  }
  float capacity = texelFetch(classes, voxel, 0).g;
  vec4 applied = b + invRate * flux / capacity;
  // Weights of 0 select: the first steps' b_k+1 and b_k+2 are zero.
  vec4 result = alpha * u0;
  if (beta != 0.0)
  {
    result += beta * applied;
  }
  if (gammaWeight != 0.0)
  {
    result += gammaWeight * texelFetch(previous, voxel, 0);
  }
  mmvWrite(result);
}

#else

uniform sampler3D rhs;      // b: the irradiance at the start of the time step
uniform sampler3D previous; // the iterate before `current`
uniform float omega;        // Chebyshev weight of this sweep (1: plain Jacobi)
// > 0: the residual check instead of a sweep. A voxel whose Jacobi correction
// |J(x) - x| (every channel) is at most this is discarded; the others pass,
// and an occlusion query counts them.
uniform float residualThreshold;
uniform bvec4 residualChannels; // the lights being updated (the others: scratch)
uniform vec3 invH2;         // 1 / h^2 per axis, h in data voxels
uniform float dt;

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  float s = mmvStrength(voxel);
  // The block's capacity (its fraction of scattering voxels); blocks without
  // any have s = 0 and keep b.
  float capacity = s > 0.0 ? texelFetch(classes, voxel, 0).g : 1.0;
  vec4 numerator = capacity * texelFetch(rhs, voxel, 0);
  float denominator = capacity;
  if (s > 0.0)
  {
    vec4 weighted;
    float total;
    mmvNeighborSums(voxel, s, current, invH2, weighted, total);
    numerator += dt * weighted;
    denominator += dt * total;
  }
  if (residualThreshold > 0.0)
  {
    vec4 correction = abs(numerator / denominator - texelFetch(current, voxel, 0));
    // Selected, not multiplied: 0 * NaN would still be NaN.
    correction = vec4(residualChannels.x ? correction.x : 0.0,
      residualChannels.y ? correction.y : 0.0, residualChannels.z ? correction.z : 0.0,
      residualChannels.w ? correction.w : 0.0);
    if (max(max(correction.x, correction.y), max(correction.z, correction.w)) <= residualThreshold)
    {
      return; // not written: the voxel keeps its value
    }
    mmvWrite(vec4(1.0));
    return;
  }
  vec4 previousValue = texelFetch(previous, voxel, 0);
  mmvWrite(previousValue + omega * (numerator / denominator - previousValue));
}

#endif
