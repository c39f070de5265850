/**
 * @file   vtkMultiMaterialInputCheck.h
 * @brief  Whether vtkMultiMaterialVolumeMapper can shade its inputs with
 *         materials, and if not, why: one verdict the mapper only reports.
 *
 * Multi-material shading needs composite blending, vtkImageData with as many
 * point or cell scalars as points or cells (one component, or 2-4
 * independent components: several fields), a 1D transfer
 * function and an OpenGL render window; anything else is rendered by VTK's
 * own shading (the mapper warns once with the reason). Vectors reach it as
 * one component through the mapper's VectorMode, which puts the reduced
 * array in the ray caster's copy of the input (GetTransformedInput): the
 * scalars are read from that copy when there is one.
 */
#ifndef vtkMultiMaterialInputCheck_h
#define vtkMultiMaterialInputCheck_h

#include "vtkMultiMaterialVolumeModule.h" // export macro

#include <string>

class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkVolumeMapper;

namespace mmv
{

struct InputCheck
{
  bool Supported = false;
  /// Why VTK's shading renders instead; empty when the base class reports
  /// the problem itself or there is nothing to say (other blend modes).
  std::string Reason;
  /// A caveat about input that passed the checks before it (a single slice).
  std::string Caveat;
  /// What passed, when Supported.
  vtkImageData* Image = nullptr;
  vtkDataArray* Scalars = nullptr;
  /// Whether Scalars are cell data (one value per cell of Image).
  bool CellData = false;
  vtkOpenGLRenderWindow* Context = nullptr;
};

/// The verdict on `mapper`'s input, rendered by `ren` as `vol`.
VTKMULTIMATERIALVOLUME_EXPORT InputCheck CheckMultiMaterialInputs(
  vtkVolumeMapper* mapper, vtkRenderer* ren, vtkVolume* vol);

} // namespace mmv

#endif
