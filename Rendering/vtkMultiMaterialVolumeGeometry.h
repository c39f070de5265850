/**
 * @file   vtkMultiMaterialVolumeGeometry.h
 * @brief  Where the volume's points land for vtkMultiMaterialVolumeMapper: in
 *         its textures (texture-coordinate maps), on the screen (pixels per
 *         voxel) and along a ray (the sample distance VTK will use).
 */
#ifndef vtkMultiMaterialVolumeGeometry_h
#define vtkMultiMaterialVolumeGeometry_h

#include "vtkIrradianceGrid.h"            // IrradianceGrid
#include "vtkMultiMaterialVolumeModule.h" // export macro

class vtkImageData;
class vtkRenderer;
class vtkVolume;

namespace mmv
{

/// Scale and bias that map texture coordinates of `n` points to those of `m`
/// texels spanning the same points (point i at (i + 0.5) / n, texel j at
/// (j + 0.5) / m); an axis of one texel maps to its centre.
VTKMULTIMATERIALVOLUME_EXPORT void SamePointsMap(double n, double m, float& scale, float& bias);

/// The maps from a brick's texture coordinates to the whole volume's, which
/// the gradient and irradiance textures cover (Shaders/mmvRayCastDec.glsl,
/// mmvWholeTexCoord): object space -> the whole volume's point index
/// (column-major 4x4), and the texture-coordinate gradient -> object space as
/// VTK's whole-volume inverse texture matrix gives it (column-major 3x3).
VTKMULTIMATERIALVOLUME_EXPORT void WholeVolumeMaps(vtkImageData* image, float physicalToIndex[16],
  float gradientToObject[9], float dimensions[3], float spacing[3]);

/// Scale and bias from the texture coordinates of a piece of `pieceDims`
/// points, whose first point is point `offset` of the whole volume, to those
/// of the whole volume's irradiance `grid` (global shadows under MPI).
VTKMULTIMATERIALVOLUME_EXPORT void PieceToGlobalIrradianceMap(const IrradianceGrid& grid,
  const double offset[3], const int pieceDims[3], float scale[3], float bias[3]);

/// The sample distance VTK's ray caster will use (object units), as
/// vtkOpenGLGPUVolumeRayCastMapper computes it, so the segment tables match it
/// and the shader's length correction stays near 1.
VTKMULTIMATERIALVOLUME_EXPORT double ExpectedSampleDistance(vtkVolume* vol, vtkImageData* image,
  double sampleDistance, bool autoAdjust, bool lock, double spacingAdjusted);

/// Pixels one data voxel step covers on screen at the volume's centre,
/// the largest over the three index axes; 0 when it cannot be told.
VTKMULTIMATERIALVOLUME_EXPORT double ProjectedPixelsPerVoxel(
  vtkRenderer* ren, vtkVolume* vol, vtkImageData* image);

} // namespace mmv

#endif
