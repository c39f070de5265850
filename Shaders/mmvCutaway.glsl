// What the mapper's cropping region and clipping planes remove, in the
// irradiance grid's index space: the shadow rays see it as empty. Mirrors
// mmvIsCut() of Filters/vtkMultiMaterialCutaway.h line for line. Needs
// MMV_MAX_CUT_PLANES (mmv::CutawayGLSLPrelude()). Without MMV_CUTAWAY (the
// pass defines it only while something is cut) nothing is cut and the test
// compiles away: it runs at every shadow-ray step, a large share of the
// estimation's cost.

uniform int cutPlaneCount;                   // 0: no clipping planes
uniform vec4 cutPlanes[MMV_MAX_CUT_PLANES];  // removed where dot(xyz, index) + w < 0
uniform int cropping;                        // 0: no cropping region
uniform vec4 cropAxes[3];                    // object coordinate a = dot(xyz, index) + w
uniform float cropBounds[6];
uniform int cropFlags;                       // VTK's CroppingRegionFlags

bool mmvIsCut(vec3 index)
{
#ifdef MMV_CUTAWAY
  for (int p = 0; p < cutPlaneCount; ++p)
  {
    if (dot(cutPlanes[p].xyz, index) + cutPlanes[p].w < 0.0)
    {
      return true;
    }
  }
  if (cropping != 0)
  {
    int bit = 0;
    int weight = 1;
    for (int a = 0; a < 3; ++a)
    {
      float x = dot(cropAxes[a].xyz, index) + cropAxes[a].w;
      int region = x < cropBounds[2 * a] ? 0 : (x > cropBounds[2 * a + 1] ? 2 : 1);
      bit += region * weight;
      weight *= 3;
    }
    if (((cropFlags >> bit) & 1) == 0)
    {
      return true;
    }
  }
#endif
  return false;
}
