/**
 * @file   vtkMultiMaterialCutaway.h
 * @brief  What the mapper's cropping region and clipping planes remove, so
 *         that the irradiance estimation treats it as empty (what is cut
 *         away casts no shadow).
 *
 * VTK's conventions (vtkOpenGLGPUVolumeRayCastMapper): a clipping plane
 * (world coordinates) removes the points x with dot(x - origin, normal) < 0;
 * the cropping region planes (xmin, xmax, ymin, ymax, zmin, zmax, data
 * coordinates) split each axis into regions 0 (below), 1 (between), 2
 * (above), and region (i, j, k) stays when bit i + 3 j + 9 k of
 * CroppingRegionFlags is set.
 *
 * The shadow rays test samples in irradiance-grid index space, so the
 * cutaway is converted once per grid (ToIndexSpace); mmvIsCut mirrors the
 * GLSL function of the same name in Shaders/mmvCutaway.glsl line for line.
 */
#ifndef vtkMultiMaterialCutaway_h
#define vtkMultiMaterialCutaway_h

#include "vtkIrradianceGrid.h"
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

#include <glm/glm.hpp>

#include <string>
#include <vector>

class vtkMatrix4x4;
class vtkPlaneCollection;
class vtkVolumeMapper;

namespace mmv
{

/// Clipping planes the irradiance estimation honours (more are ignored, with
/// a warning from the mapper).
constexpr int MaxCutPlanes = 6;

/// The uniforms of Shaders/mmvCutaway.glsl: CutawayGLSLPrelude() declares
/// them from this table and the Rendering module sets them by these names.
enum CutawayUniform : int
{
  CutPlaneCountUniform = 0,
  CutPlanesUniform,
  CroppingUniform,
  CropAxesUniform,
  CropBoundsUniform,
  CropFlagsUniform,
  CutawayUniformCount
};

struct CutawayUniformInfo
{
  const char* GLSLType;
  const char* Name;
  const char* ArraySize; // "" for a single value
  const char* Meaning;
};

constexpr CutawayUniformInfo CutawayUniformLayout[CutawayUniformCount] = {
  { "int", "mmv_cutPlaneCount", "", "0: no clipping planes" },
  { "vec4", "mmv_cutPlanes", "MMV_MAX_CUT_PLANES", "removed where dot(xyz, index) + w < 0" },
  { "int", "mmv_cropping", "", "0: no cropping region" },
  { "vec4", "mmv_cropAxes", "3", "object coordinate a = dot(xyz, index) + w" },
  { "float", "mmv_cropBounds", "6", "the region's planes, (min, max) per axis" },
  { "int", "mmv_cropFlags", "", "VTK's CroppingRegionFlags" },
};

/// The removed part of the volume in object (data) coordinates.
struct Cutaway
{
  int NumberOfPlanes = 0;
  /// (normal, offset): x is removed where dot(normal, x) + offset < 0.
  glm::dvec4 Planes[MaxCutPlanes];
  bool Cropping = false;
  double CropBounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  int CropFlags = 0x0002000; // VTK_CROP_SUBVOLUME

  bool IsEmpty() const { return this->NumberOfPlanes == 0 && !this->Cropping; }
  /// A flat description for cache keys.
  std::vector<double> Key() const;
};

/// The same in the index space of an irradiance grid: planes as
/// dot(n, index) + d, and the three object coordinates as affine functions
/// of the index (row a: (d obj_a / d index, obj_a at index 0)).
struct IndexCutaway
{
  int NumberOfPlanes = 0;
  glm::dvec4 Planes[MaxCutPlanes];
  bool Cropping = false;
  glm::dvec4 CropAxes[3];
  double CropBounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  int CropFlags = 0;
};

/// The mapper's cropping and clipping planes in object space (worldToObject:
/// the inverse of the volume's matrix). Planes beyond MaxCutPlanes are
/// dropped and counted in `dropped` (if given).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT Cutaway MakeCutaway(
  vtkVolumeMapper* mapper, const vtkMatrix4x4* worldToObject, int* dropped = nullptr);

/// The same from the settings themselves (the CPU filter's), planes in world
/// coordinates (worldToObject null: identity).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT Cutaway MakeCutaway(bool cropping,
  const double croppingPlanes[6], int croppingFlags, vtkPlaneCollection* planes,
  const vtkMatrix4x4* worldToObject, int* dropped = nullptr);

VTKMULTIMATERIALVOLUMEFILTERS_EXPORT IndexCutaway ToIndexSpace(
  const Cutaway& cutaway, const IrradianceGrid& grid);

/// True where the cutaway removes the point at continuous index `index`.
inline bool mmvIsCut(const IndexCutaway& c, const glm::dvec3& index)
{
  for (int p = 0; p < c.NumberOfPlanes; ++p)
  {
    if (glm::dot(glm::dvec3(c.Planes[p]), index) + c.Planes[p].w < 0.0)
    {
      return true;
    }
  }
  if (c.Cropping)
  {
    int bit = 0;
    int weight = 1;
    for (int a = 0; a < 3; ++a)
    {
      const double x = glm::dot(glm::dvec3(c.CropAxes[a]), index) + c.CropAxes[a].w;
      const int region = x < c.CropBounds[2 * a] ? 0 : (x > c.CropBounds[2 * a + 1] ? 2 : 1);
      bit += region * weight;
      weight *= 3;
    }
    if (((c.CropFlags >> bit) & 1) == 0)
    {
      return true;
    }
  }
  return false;
}

/// The GLSL `#define` of MaxCutPlanes (MMV_MAX_CUT_PLANES).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT std::string CutawayGLSLPrelude();

/// The GLSL `#define` that turns Shaders/mmvCutaway.glsl's test on, in the
/// shaders marching a volume while something is cut (without it the test
/// compiles away).
constexpr const char* CutawayGLSLDefine = "#define MMV_CUTAWAY\n";

} // namespace mmv

#endif
