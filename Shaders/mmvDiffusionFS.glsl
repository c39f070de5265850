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
uniform int dims[3];

#ifndef MMV_FILL_PASS
// The diffusion grid's blocks (mmv::DiffusionBlockTexels): face coefficients
// c_f (the harmonic mean of the two s over h^2, 0 where a face exchanges
// nothing), capacity, whether the block scatters.
uniform sampler3D facesXY; // toward -x, +x, -y, +y
uniform sampler3D facesZ;  // toward -z, +z; capacity; scatters

// c_f x_f, or 0 where the face exchanges nothing: selected, not multiplied,
// as the neighbour may never have been drawn and 0 * NaN would be NaN.
vec4 mmvFaceFlux(float c, vec4 x)
{
  return c > 0.0 ? c * x : vec4(0.0);
}

// The block's face coefficients: toward -x, +x, -y, +y in `xy`, -z, +z in
// z.xy, its capacity in z.z; and their sum, 0 where it exchanges nothing.
float mmvFaces(ivec3 voxel, out vec4 xy, out vec4 z)
{
  xy = texelFetch(facesXY, voxel, 0);
  z = texelFetch(facesZ, voxel, 0);
  return xy.x + xy.y + xy.z + xy.w + z.x + z.y;
}

// Over the faces of `voxel`: the sum of c_f x_f. Written out face by face: a
// software rasterizer ran a loop over faces with a dynamically indexed
// coordinate slower (llvmpipe: a quarter more time for the head's sweeps).
vec4 mmvNeighborSum(ivec3 voxel, sampler3D x, vec4 xy, vec4 z)
{
  ivec3 lo = max(voxel - 1, ivec3(0));
  ivec3 hi = min(voxel + 1, ivec3(dims[0], dims[1], dims[2]) - 1);
  return mmvFaceFlux(xy.x, texelFetch(x, ivec3(lo.x, voxel.yz), 0)) +
    mmvFaceFlux(xy.y, texelFetch(x, ivec3(hi.x, voxel.yz), 0)) +
    mmvFaceFlux(xy.z, texelFetch(x, ivec3(voxel.x, lo.y, voxel.z), 0)) +
    mmvFaceFlux(xy.w, texelFetch(x, ivec3(voxel.x, hi.y, voxel.z), 0)) +
    mmvFaceFlux(z.x, texelFetch(x, ivec3(voxel.xy, lo.z), 0)) +
    mmvFaceFlux(z.y, texelFetch(x, ivec3(voxel.xy, hi.z), 0));
}
#endif

#ifdef MMV_FILL_PASS

uniform sampler3D classes; // s per voxel, < 0 where the voxel is empty

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

#elif defined(MMV_CHANGE)

// With MMV_CHANGE (after the sweeps): the change the diffusion made where the
// block exchanges light, 0 elsewhere (the sweeps never wrote those blocks:
// they keep their value), which the prolongation (mmvDiffusionGridFS.glsl)
// interpolates.
uniform sampler3D initial; // the restricted irradiance

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 xy;
  vec4 z;
  // Selected, not multiplied: a block the sweeps never drew may hold NaN.
  mmvWrite(mmvFaces(voxel, xy, z) > 0.0
      ? texelFetch(current, voxel, 0) - texelFetch(initial, voxel, 0)
      : vec4(0.0));
}

#elif defined(MMV_EXPONENTIAL)

// With MMV_EXPONENTIAL (ExponentialDiffusion, vtkIrradianceDiffusion.h):
// one step of the Clenshaw recurrence of exp(-T C^-1 A) = sum_k c_k T_k(B),
// B = I - C^-1 A / R (R the rate bound), mirroring
// DiffusionSystem::Clenshaw() of Filters/vtkIrradianceDiffusion.cxx:
//   out = alpha u0 + beta B(current) + gamma previous.
// A block that exchanges nothing keeps u0 exactly: it is left unwritten, and
// the change pass (MMV_CHANGE) gives it none.
uniform sampler3D initial;  // u0: the restricted irradiance
uniform sampler3D previous; // b_k+2
uniform float alpha;
uniform float beta;
uniform float gammaWeight;
uniform float invRate;      // 1 / R

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 xy;
  vec4 z;
  float total = mmvFaces(voxel, xy, z);
  if (!(total > 0.0))
  {
    // It keeps u0, which the change pass knows: its change is 0.
    mmvLeaveUnwritten();
  }
  vec4 b = texelFetch(current, voxel, 0);
  vec4 applied = b + invRate * (mmvNeighborSum(voxel, current, xy, z) - total * b) / z.z;
  vec4 u0 = texelFetch(initial, voxel, 0);
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
uniform float dt;

void mmvVoxelMain()
{
  ivec3 voxel = ivec3(floor(texCoord * vec2(dims[0], dims[1])), slice);
  vec4 xy;
  vec4 z;
  float total = mmvFaces(voxel, xy, z);
  if (!(total > 0.0))
  {
    // It keeps b, which the change pass knows: its change is 0.
    mmvLeaveUnwritten();
  }
  float capacity = z.z;
  vec4 numerator = capacity * texelFetch(rhs, voxel, 0) + dt * mmvNeighborSum(voxel, current, xy, z);
  float denominator = capacity + dt * total;
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
