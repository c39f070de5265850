/**
 * @class   vtkMaterialLibrary
 * @brief   Named material presets (plastic, metal, skin, bone, glass, leaf, matte, ...).
 *
 * A preset is one set of the material parameters plus a display colour
 * for swatches. The built-in presets are the JSON files of
 * Filters/Materials/, embedded in the library at build time; more can be
 * read from files and written back.
 *
 * JSON form of one preset:
 *   {"name": "metal", "color": [r, g, b], "ambient": .., "diffuse": .., ...}
 * A file holds one preset object or an array of them. Malformed JSON, a
 * missing name, a non-finite/negative/too large parameter or an unknown key is
 * an error (vtkErrorMacro) and leaves the library unchanged.
 */
#ifndef vtkMaterialLibrary_h
#define vtkMaterialLibrary_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"

#include <string> // for JSON strings

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMaterialLibrary : public vtkObject
{
public:
  /// A new library holding the built-in presets.
  static vtkMaterialLibrary* New();
  vtkTypeMacro(vtkMaterialLibrary, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int GetNumberOfPresets() const;
  /// Name of preset i in insertion order (nullptr if out of range).
  const char* GetPresetName(int i) const;
  bool HasPreset(const char* name) const;

  /// The 12 parameters of a preset (mmv::MaterialParameterCount); false
  /// (with an error) for unknown names.
  bool GetPreset(const char* name, double parameters[12]) const;
  /// Display colour (RGB in 0..1) of a preset.
  bool GetPresetColor(const char* name, double rgb[3]) const;

  /// Adds or replaces a preset; false (with an error) on invalid values.
  bool AddPreset(const char* name, const double parameters[12], const double rgb[3] = nullptr);
  bool RemovePreset(const char* name);
  /// Drops user changes and reloads the built-in presets.
  void ResetToBuiltins();

  ///@{
  /// Adds/replaces presets from JSON (one object or an array of objects).
  bool AddPresetsFromJSON(const std::string& json);
  bool ReadJSONFile(const char* path);
  /// All presets as a JSON array.
  std::string ToJSON() const;
  bool WriteJSONFile(const char* path) const;
  ///@}

protected:
  vtkMaterialLibrary();
  ~vtkMaterialLibrary() override;

private:
  vtkMaterialLibrary(const vtkMaterialLibrary&) = delete;
  void operator=(const vtkMaterialLibrary&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
