/**
 * @file   vtkDiffusionGridTransfer.h
 * @brief  The transfers between the irradiance grid and a diffusion grid,
 *         on the CPU, as the GPU's passes compute them.
 *
 * With the diffusion's series on the CPU (vtkBlockDiffusionSeries.h), the
 * restriction to the diffusion grid and the prolongation of its change are
 * loops here too: on a CPU rasterizer each was a fragment pass over the
 * irradiance grid (0.1-0.2 s each on a 237 x 237 x 119 grid), against one
 * read-back of the irradiance before the diffusion and one upload after it.
 *
 * Both mirror Shaders/mmvDiffusionGridFS.glsl in float and in its order:
 *  - restriction (MMV_RESTRICT): a block's value is the mean of the
 *    irradiance over its voxels whose class is above 0 (0 when none);
 *  - prolongation: a voxel whose class is above 0 adds the change,
 *    interpolated trilinearly at its coarse coordinate
 *    u = clamp((i - (f - 1) / 2) / f, 0, n - 1) and divided by the same
 *    interpolation of the blocks' "scatters" flags (where that is above 0),
 *    clamped at 0; other voxels keep their value.
 * The irradiance grid's values have 4 channels per voxel (the estimator's
 * RGBA scratch); the diffusion grid's `channels` (1, 2 or 4).
 */
#ifndef vtkDiffusionGridTransfer_h
#define vtkDiffusionGridTransfer_h

#include "vtkIrradianceDiffusion.h"              // DiffusionGrid
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

namespace mmv
{

/// The restriction of `fine` (4 floats per voxel of `dims`) to the blocks of
/// `coarse` in `blocks` (inclusive bounds), `channels` floats per block, into
/// `restricted`; `classes` holds each voxel's class (s, or < 0 empty).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void RestrictToDiffusionBlocks(const int dims[3],
  const float* fine, const float* classes, const DiffusionGrid& coarse, int channels,
  const int blocks[6], float* restricted);

/// The prolongation of `change` (`channels` floats per block; `facesZ` the
/// blocks' texels of DiffusionBlockTexels, whose fourth float flags the
/// blocks that scatter) onto the voxels of `box`, into the channels of
/// `mask` (bit c: channel c) of `out` (4 floats per voxel), from `fine`.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void ProlongDiffusionChange(const int dims[3],
  const float* fine, const float* classes, const DiffusionGrid& coarse, int channels,
  const float* change, const float* facesZ, int mask, const int box[6], float* out);

} // namespace mmv

#endif
