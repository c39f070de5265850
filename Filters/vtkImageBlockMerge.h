/**
 * @file   vtkImageBlockMerge.h
 * @brief  Several vtkImageData blocks of one lattice as one image.
 *
 * Readers and filters hand image data over in blocks (a vtkMultiBlockDataSet
 * or vtkPartitionedDataSet of vtkImageData: XML .vtm/.vtpd files, ParaView's
 * distributed pieces split further). The ray caster, its irradiance volume and
 * the MPI exchange of the global pre-filtered volume all take one
 * vtkImageData per process, so the blocks a process holds are merged into
 * the box they tile. Point extents of neighbouring blocks may overlap (shared
 * faces, ghost layers): the data there must agree, and the last block wins.
 *
 * Errors (returned as text, no image): a leaf that is not vtkImageData, blocks
 * of different spacing or direction, origins off the common lattice, a union
 * that leaves points uncovered (blocks must tile a box), or no point array
 * common to every block. No image block at all is not an error: the result
 * is an empty image (a rank without data still joins the exchange).
 */
#ifndef vtkImageBlockMerge_h
#define vtkImageBlockMerge_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkSmartPointer.h"

#include <string>

class vtkDataObject;
class vtkImageData;

namespace mmv
{

/// The leaves of `composite` (any vtkCompositeDataSet) merged into one image
/// with every point array all blocks share (same name, type and components),
/// the first block's active scalars active. On an error returns nullptr and
/// says why in `error`.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkSmartPointer<vtkImageData> MergeImageBlocks(
  vtkDataObject* composite, std::string& error);

} // namespace mmv

#endif
