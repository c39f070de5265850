#include "vtkMultiMaterialMapperSettings.h"

namespace
{
// Constant-initialised, so a reader registered from another library's static
// initialiser can never be overwritten by this one's.
mmv::MapperSettingsReader RegisteredReader = nullptr;
}

namespace mmv
{
void SetMapperSettingsReader(MapperSettingsReader reader)
{
  RegisteredReader = reader;
}

bool ReadMapperSettings(vtkAbstractVolumeMapper* mapper, MapperSettings& settings)
{
  return mapper && RegisteredReader && RegisteredReader(mapper, settings);
}
}
