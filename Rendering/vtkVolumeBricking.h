/**
 * @file   vtkVolumeBricking.h
 * @brief  How many bricks (VTK's texture partitions) a volume needs so that
 *         every brick fits the largest 3D texture of the OpenGL context.
 *
 * VTK 9.2 uploads a volume as one 3D texture unless told to partition it;
 * a volume longer than GL_MAX_3D_TEXTURE_SIZE along an axis then fails the
 * upload and asserts in vtkTextureObject::Bind, aborting the process. VTK's
 * vtkVolumeTexture::SplitVolume cuts an axis of N points into p blocks of
 * extent [floor(i d), floor((i + 1) d)], d = (N - 1) / p: a block holds
 * between d + 1 and d + 2 points, so the fewest bricks that fit lie between
 * ceil((N - 1) / (max - 1)) and ceil((N - 1) / (max - 2)).
 */
#ifndef vtkVolumeBricking_h
#define vtkVolumeBricking_h

#include "vtkMultiMaterialVolumeModule.h" // export macro

namespace mmv
{

/// The most points a brick of an axis of `points` points cut into `parts`
/// holds, as vtkVolumeTexture::SplitVolume cuts it.
VTKMULTIMATERIALVOLUME_EXPORT int LargestBrickPoints(int points, int parts);

/**
 * Partitions per axis for a volume of `pointDims` points: the requested ones
 * (SetPartitions; values < 1 count as 1) where their bricks fit
 * `maxTextureSize`, otherwise the fewest that fit. False when no
 * partitioning fits (maxTextureSize < 3, or more than 65535 parts).
 */
VTKMULTIMATERIALVOLUME_EXPORT bool ChooseBrickPartitions(
  const int pointDims[3], int maxTextureSize, const int requested[3], int partitions[3]);

/**
 * Raises `partitions` (from ChooseBrickPartitions) until no brick holds more
 * than `maxBrickBytes` at `bytesPerPoint`: a texture allocation that fails
 * (llvmpipe refuses 3D textures over 1 GiB; GPUs have their own limits)
 * also ends in VTK's assertion. Each step cuts the axis whose bricks are
 * longest. False when even bricks of 2 points per axis are too large.
 */
VTKMULTIMATERIALVOLUME_EXPORT bool LimitBrickBytes(
  const int pointDims[3], double bytesPerPoint, double maxBrickBytes, int partitions[3]);

} // namespace mmv

#endif
