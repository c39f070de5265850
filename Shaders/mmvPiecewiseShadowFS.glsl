// Piecewise shadow rays of one directional light (Filters/vtkShadowSweep.h),
// one fragment per voxel of the chunk being drawn: the ray runs toward the
// light up to slice `sweepPlane` of axis `sweepAxis`, where it takes the
// transmittance an earlier chunk wrote into this same texture (a texture
// barrier separates the chunks' draws, and a chunk never reads its own
// slices). Mirrors SweepPiecewiseShadowRays() of
// Filters/vtkIrradianceVolumeFilter.cxx, and a directional light's sweep
// mmv::SweepTransmittanceOnCPU (Filters/vtkSweptTransmittance.h, which a
// CPU rasterizer runs instead). Prepended by the pass: the material
// prelude, mmv::ShadowRayGLSLPrelude(), mmvShadowRay.glsl and
// mmvLightGrid.glsl: the voxels, slices and planes are the light grid's, the
// rays march in the irradiance grid's index space.
//
// With MMV_POINT_SWEEP (and the light model) the light is light 0 of the
// light uniforms, a point or spot light outside the grid
// (mmv::PointLightSweepDirection), or inside it with MMV_PYRAMID_SWEEP as
// well, swept in six pyramids (mmv::InsideLightSweeps): each voxel's ray
// runs toward the light's
// position, and the channel holds pure transmittance until a last draw with
// applyGeometry multiplies each voxel's by its falloff and cone
// (mmvLightGeometryTerm), as the full rays of mmvIrradianceFS.glsl write it.

uniform sampler3D transmittance; // the target itself: earlier chunks' results
uniform int channel;             // the light's channel in it
uniform mat3 worldToIndex;
uniform vec3 toLight;            // unit, world space
uniform int sweepAxis;
uniform int sweepPlane;          // -1: the first chunk, rays run to the boundary
uniform int readSlice;           // the slice the next chunk reads (-1: none)
// The part of sweepPlane the rays may read, {lo, hi} along in-slice axes
// (sweepAxis + 1) % 3 and (sweepAxis + 2) % 3 (mmv::SliceReadRange): the
// whole slice, or a pyramid's part of it; lo > hi: none, rays run on.
uniform int sliceRange[4];
uniform bool computeEmptyVoxels; // on: every voxel (to measure what skipping saves)
#ifdef MMV_PYRAMID_SWEEP
// A point light inside the grid: this draw computes only its pyramid on the
// side of the light away from sweepTowardPositive (mmv::InsideLightSweeps).
uniform vec3 pyramidLight; // the light, light grid index
uniform bool sweepTowardPositive;
#endif
#ifdef MMV_POINT_SWEEP
uniform vec3 origin;
uniform mat3 indexToWorld;
uniform bool applyGeometry; // the last draw: transmittance x the light's geometry term
#endif

// mmv::ReachesSweepPlane: does the ray reach the plane before leaving the box?
// `plane` is the plane's coordinate along the axis (irradiance index).
bool mmvReachesSweepPlane(float start, float direction, float plane, float exitDistance,
  out float distance)
{
  distance = 0.0;
  if (plane < 0.0 || direction == 0.0)
  {
    return false;
  }
  distance = (plane - start) / direction;
  return distance >= 0.0 &&
    distance <= exitDistance * (1.0 + MMV_SWEEP_PLANE_RELATIVE_TOLERANCE) +
      MMV_SWEEP_PLANE_ABSOLUTE_TOLERANCE;
}

#ifdef MMV_PYRAMID_SWEEP
// mmv::InSweptPyramid (vtkShadowSweep.h).
bool mmvInSweptPyramid(vec3 voxel)
{
  vec3 d = voxel - pyramidLight;
  float along = abs(d[sweepAxis]);
  return along >= abs(d[(sweepAxis + 1) % 3]) && along >= abs(d[(sweepAxis + 2) % 3]) &&
    (d[sweepAxis] >= 0.0) == !sweepTowardPositive;
}
#endif

// Bilinear transmittance in light grid slice `plane` at the in-slice
// coordinates of q (light grid index), clamped to sliceRange (texelFetch: no
// filtering reaches another slice).
float mmvSampleSlice(int axis, int plane, vec3 q)
{
  int b = (axis + 1) % 3;
  int c = (axis + 2) % 3;
  ivec3 i0 = ivec3(0);
  i0[axis] = plane;
  vec3 f = vec3(0.0);
  ivec3 db = ivec3(0);
  ivec3 dc = ivec3(0);
  for (int k = 0; k < 2; ++k)
  {
    int a = k == 0 ? b : c;
    int lo = sliceRange[2 * k];
    int hi = sliceRange[2 * k + 1];
    float x = clamp(q[a], float(lo), float(hi));
    i0[a] = min(int(x), max(hi - 1, lo));
    f[a] = hi > lo ? x - float(i0[a]) : 0.0;
  }
  db[b] = sliceRange[1] > sliceRange[0] ? 1 : 0;
  dc[c] = sliceRange[3] > sliceRange[2] ? 1 : 0;
  float v00 = texelFetch(transmittance, i0, 0)[channel];
  float v10 = texelFetch(transmittance, i0 + db, 0)[channel];
  float v01 = texelFetch(transmittance, i0 + dc, 0)[channel];
  float v11 = texelFetch(transmittance, i0 + db + dc, 0)[channel];
  return (1.0 - f[c]) * ((1.0 - f[b]) * v00 + f[b] * v10) +
    f[c] * ((1.0 - f[b]) * v01 + f[b] * v11);
}

void mmvVoxelMain()
{
  ivec3 voxel = mmvTargetVoxel();
  vec3 start = vec3(voxel) * targetToIndex;
#ifdef MMV_POINT_SWEEP
  vec3 x = origin + indexToWorld * start;
  float geometry = mmvLightGeometryTerm(mmv_lightKind[0], mmv_lightPosition[0],
    mmv_lightSpotAxis[0], mmv_lightCosCone[0], mmv_lightSpotExponent[0],
    mmv_lightAttenuation[0], mmv_lightRadius[0], x);
  if (applyGeometry)
  {
    // Each fragment reads only its own texel, written by an earlier draw.
    mmvWrite(vec4(geometry * texelFetch(transmittance, voxel, 0)[channel]));
    return;
  }
#ifdef MMV_PYRAMID_SWEEP
  if (!mmvInSweptPyramid(vec3(voxel)))
  {
    mmvLeaveUnwritten(); // another pyramid's: it keeps its value
  }
#endif
  float lightDistance;
  vec3 indexDir = worldToIndex * mmvDirectionToLight(mmv_lightKind[0], mmv_lightPosition[0],
    mmv_lightToLight[0], x, lightDistance);
  bool unlit = geometry <= 0.0; // outside a spot light's cone
#else
  vec3 indexDir = worldToIndex * toLight;
  bool unlit = false;
#endif
  if (!computeEmptyVoxels && voxel[sweepAxis] != readSlice &&
    (unlit || mmvLightGridIsEmpty(voxel)))
  {
    // Empty or unlit, and no later chunk reads it: its value is 0, or the
    // fill pass decides it.
    mmvWrite(vec4(0.0));
    return;
  }
  float exitDistance = mmvExitDistance(start, indexDir);
#ifdef MMV_POINT_SWEEP
  exitDistance = min(exitDistance, lightDistance);
#endif
  float far = 1.0;
  float distance;
  float plane = sweepPlane < 0 ? -1.0 : float(sweepPlane) * targetToIndex[sweepAxis];
  if (sliceRange[0] <= sliceRange[1] && sliceRange[2] <= sliceRange[3] &&
    mmvReachesSweepPlane(start[sweepAxis], indexDir[sweepAxis], plane, exitDistance, distance))
  {
    exitDistance = distance;
    far = mmvSampleSlice(sweepAxis, sweepPlane, (start + distance * indexDir) / targetToIndex);
  }
  // The colour mask keeps the other lights' channels.
  mmvWrite(vec4(mmvMarchTransmittance(start, indexDir, exitDistance,
    mmvStartValue(voxel, start), far)));
}
