// What every irradiance voxel pass (mmvIrradianceFS, mmvPiecewiseShadowFS,
// mmvDiffusionFS, mmvDiffusionGridFS) sees, whether it runs as a fragment
// shader over a layered draw or as a compute shader (MMV_COMPUTE): the voxel
// as `texCoord` (the centre of voxel (i, j) in the target's xy) and `slice`
// (k), and mmvWrite() for its result. A pass that returns from
// mmvVoxelMain() without writing leaves the voxel as it was (a discarded
// fragment; no image store). mmvVoxelPassMain.glsl holds main().
#ifdef MMV_COMPUTE
vec2 texCoord;
int slice;
#else
flat in int slice;  // the layer (mmvLayerGS.glsl)
in vec2 texCoord;   // the quad's, at the centre of voxel (i, j)
#endif

vec4 mmvResult = vec4(0.0);
bool mmvWritten = false;

// Leaves the voxel as it was, at once: a fragment discarded here lets a
// software rasterizer skip the rest of the shader for a batch whose
// fragments all left, which a return from mmvVoxelMain() does not.
#ifdef MMV_COMPUTE
#define mmvLeaveUnwritten() return
#else
#define mmvLeaveUnwritten() discard
#endif

void mmvWrite(vec4 value)
{
  mmvResult = value;
  mmvWritten = true;
}
