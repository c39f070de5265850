// Tells the CPU references (Filters/) how to read vtkMultiMaterialVolumeMapper,
// which they cannot include: see vtkMultiMaterialMapperSettings.h.
#include "vtkMultiMaterialMapperSettings.h"
#include "vtkMultiMaterialVolumeMapper.h"

namespace
{
bool ReadMultiMaterialVolumeMapper(vtkAbstractVolumeMapper* mapper, mmv::MapperSettings& settings)
{
  auto* mmvMapper = vtkMultiMaterialVolumeMapper::SafeDownCast(mapper);
  if (!mmvMapper)
  {
    return false;
  }
  settings.Materials = mmvMapper->GetMaterialTransferFunction();
  settings.Illumination = mmvMapper->GetSettings();
  return true;
}

// Registered when this library loads (it is always shared: see the top-level
// CMakeLists.txt), before any mapper can exist.
const bool ReaderRegistered = (mmv::SetMapperSettingsReader(&ReadMultiMaterialVolumeMapper), true);
}
