/**
 * @class   vtkVectorScalarsCache
 * @brief   The one-component arrays made of vectors (mmv::MakeVectorScalars),
 *          kept so that a vector seen again gets the very same array.
 *
 * The irradiance and gradient volumes of earlier inputs are kept under the
 * scalar array's pointer and modification time (vtkIrradianceStepCache): a
 * magnitude made afresh whenever a series' step comes back would be a new
 * array and never match. An entry lives as long as the vector it was made
 * of is unmodified and alive (ParaView's animation cache holds each step's
 * data), and only while KeepAll is on; otherwise just the latest is kept.
 */
#ifndef vtkVectorScalarsCache_h
#define vtkVectorScalarsCache_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkSmartPointer.h"                     // entries
#include "vtkType.h"                             // vtkMTimeType
#include "vtkWeakPointer.h"                      // entries

#include <cstddef>
#include <list>
#include <string>

class vtkDataArray;

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkVectorScalarsCache
{
public:
  /// `vectors` reduced by `mode` and `component` (mmv::VectorModes): the
  /// array made before for this unmodified vector, or a new one. Null (with
  /// `error` set) where mmv::MakeVectorScalars fails.
  vtkDataArray* Get(vtkDataArray* vectors, int mode, int component, std::string* error);

  /// Keep every array whose vector is alive and unmodified (on while
  /// earlier steps' irradiance is kept), not only the latest.
  void SetKeepAll(bool keep) { this->KeepAll = keep; }
  bool GetKeepAll() const { return this->KeepAll; }

  int GetNumberOfEntries() const { return static_cast<int>(this->Entries.size()); }
  /// Memory of the kept arrays.
  size_t GetBytes() const;
  /// Number of arrays made (not served from an entry).
  int GetNumberOfReductions() const { return this->Reductions; }

  void Clear() { this->Entries.clear(); }

private:
  struct Entry
  {
    vtkWeakPointer<vtkDataArray> From; // null once the vector is deleted
    vtkMTimeType FromTime = 0;
    int Mode = 0;
    int Component = 0;
    vtkSmartPointer<vtkDataArray> Reduced;
  };
  std::list<Entry> Entries; // most recently used first
  bool KeepAll = false;
  int Reductions = 0;
};

#endif
