/**
 * @file  vtkMaterialLibraryBuiltins.h
 * @brief The built-in material presets: the JSON files of Filters/Materials/,
 *        embedded at build time. The table ends with a {nullptr, nullptr} entry.
 */
#ifndef vtkMaterialLibraryBuiltins_h
#define vtkMaterialLibraryBuiltins_h

namespace mmv
{
struct BuiltinMaterial
{
  const char* Name; // file name without .json
  const char* JSON; // file contents
};
extern const BuiltinMaterial BuiltinMaterials[];
}

#endif
