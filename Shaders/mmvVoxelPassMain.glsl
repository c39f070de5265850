// main() of the irradiance voxel passes (see mmvVoxelPassDec.glsl).
#ifdef MMV_COMPUTE

// 8x8x4: no slower than 4x4x4 or 16x8x1 on the GPU of docs/performance.md
// ("On a GPU: NVIDIA H100").
layout(local_size_x = 8, local_size_y = 8, local_size_z = 4) in;
writeonly uniform image3D mmvTarget;
uniform sampler3D mmvTargetBefore; // the same texture: channels the mask keeps
uniform ivec3 mmvBoxMin;           // the voxels to compute, inclusive
uniform ivec3 mmvBoxMax;
uniform ivec2 mmvTargetSize;
uniform bvec4 mmvWriteMask;        // as glColorMask in a fragment pass
uniform bool mmvCountWrites;       // as a GL_SAMPLES_PASSED query
layout(binding = 0, offset = 0) uniform atomic_uint mmvWrites;

void main()
{
  ivec3 voxel = mmvBoxMin + ivec3(gl_GlobalInvocationID);
  if (any(greaterThan(voxel, mmvBoxMax)))
  {
    return;
  }
  texCoord = (vec2(voxel.xy) + 0.5) / vec2(mmvTargetSize);
  slice = voxel.z;
  mmvVoxelMain();
  if (!mmvWritten)
  {
    return;
  }
  vec4 value = mmvResult;
  if (!all(mmvWriteMask))
  {
    // Selected per channel, not mixed: 0 * NaN in a scratch channel would
    // still be NaN.
    vec4 before = texelFetch(mmvTargetBefore, voxel, 0);
    value = vec4(mmvWriteMask.x ? value.x : before.x, mmvWriteMask.y ? value.y : before.y,
      mmvWriteMask.z ? value.z : before.z, mmvWriteMask.w ? value.w : before.w);
  }
  imageStore(mmvTarget, voxel, value);
  if (mmvCountWrites)
  {
    atomicCounterIncrement(mmvWrites);
  }
}

#else

void main()
{
  mmvVoxelMain();
  if (!mmvWritten)
  {
    discard;
  }
  gl_FragData[0] = mmvResult;
}

#endif
