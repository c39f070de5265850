/**
 * @file   vtkMultiMaterialMapperSettings.h
 * @brief  The mapper settings the CPU references adopt in RenderToImage().
 *
 * The references (this module) render what vtkMultiMaterialVolumeMapper
 * approximates, and RenderToImage(renderer, volume) takes the mapper's
 * materials and switches. The mapper lives in the OpenGL rendering module,
 * which depends on this one, so this module cannot name it: the rendering
 * module registers a reader when its library loads
 * (Rendering/vtkMultiMaterialMapperSettingsReader.cxx). A mapper exists only
 * once that library is loaded, so the reader is always there when needed.
 */
#ifndef vtkMultiMaterialMapperSettings_h
#define vtkMultiMaterialMapperSettings_h

#include "vtkMultiMaterialSettings.h"            // IlluminationSettings
#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro

class vtkAbstractVolumeMapper;
class vtkMaterialTransferFunction;

namespace mmv
{
/// What a reference adopts from a multi-material mapper.
struct MapperSettings
{
  vtkMaterialTransferFunction* Materials = nullptr;
  IlluminationSettings Illumination;
};

/// Fills `settings` from `mapper` and returns true when it is a mapper the
/// reader knows; false (settings untouched) otherwise.
using MapperSettingsReader = bool (*)(vtkAbstractVolumeMapper* mapper, MapperSettings& settings);

/// Installs the reader (the rendering module does, once, at load time).
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT void SetMapperSettingsReader(MapperSettingsReader reader);

/// The registered reader applied to `mapper`; false without a reader or
/// when `mapper` is null or not a multi-material mapper.
VTKMULTIMATERIALVOLUMEFILTERS_EXPORT bool ReadMapperSettings(
  vtkAbstractVolumeMapper* mapper, MapperSettings& settings);
}

#endif
