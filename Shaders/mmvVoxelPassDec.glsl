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

void mmvWrite(vec4 value)
{
  mmvResult = value;
  mmvWritten = true;
}
