// What the mapper's cropping region and clipping planes remove, in the
// irradiance grid's index space: the shadow rays see it as empty. Mirrors
// mmvIsCut() of Filters/vtkMultiMaterialCutaway.h line for line. Needs
// mmv::CutawayGLSLPrelude() first: MMV_MAX_CUT_PLANES and the uniforms of
// mmv::CutawayUniformLayout. Without MMV_CUTAWAY (the pass defines it only
// while something is cut) nothing is cut and the test compiles away: it runs
// at every shadow-ray step, a large share of the estimation's cost.

bool mmvIsCut(vec3 index)
{
#ifdef MMV_CUTAWAY
  for (int p = 0; p < mmv_cutPlaneCount; ++p)
  {
    if (dot(mmv_cutPlanes[p].xyz, index) + mmv_cutPlanes[p].w < 0.0)
    {
      return true;
    }
  }
  if (mmv_cropping != 0)
  {
    int bit = 0;
    int weight = 1;
    for (int a = 0; a < 3; ++a)
    {
      float x = dot(mmv_cropAxes[a].xyz, index) + mmv_cropAxes[a].w;
      int region = x < mmv_cropBounds[2 * a] ? 0 : (x > mmv_cropBounds[2 * a + 1] ? 2 : 1);
      bit += region * weight;
      weight *= 3;
    }
    if (((mmv_cropFlags >> bit) & 1) == 0)
    {
      return true;
    }
  }
#endif
  return false;
}
