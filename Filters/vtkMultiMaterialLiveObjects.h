/**
 * @class   vtkMultiMaterialLiveObjects
 * @brief   Live instances of the project's classes, for leak tests.
 *
 * The Debian VTK is built without vtkDebugLeaks (VTK_DEBUG_LEAKS is off in
 * vtkDebug.h), so nothing in VTK counts live objects. The classes that own
 * or travel with GPU state (the mapper, its render pass, its pre-integration
 * tables and irradiance input cache, ParaView's representation) report their
 * construction and destruction here; a test that creates, renders and
 * deletes them in a loop asserts that the counts return to where they were.
 * Thread-safe; a few nanoseconds per object.
 */
#ifndef vtkMultiMaterialLiveObjects_h
#define vtkMultiMaterialLiveObjects_h

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMultiMaterialLiveObjects : public vtkObject
{
public:
  static vtkMultiMaterialLiveObjects* New();
  vtkTypeMacro(vtkMultiMaterialLiveObjects, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Live instances of all counted classes.
  static int GetCount();
  /// Live instances of the counted class `className` (0 for others).
  static int GetCount(const char* className);

  ///@{
  /// Called by the counted classes' constructors and destructors.
  static void Constructed(const char* className);
  static void Destroyed(const char* className);
  ///@}

protected:
  vtkMultiMaterialLiveObjects() = default;
  ~vtkMultiMaterialLiveObjects() override = default;

private:
  vtkMultiMaterialLiveObjects(const vtkMultiMaterialLiveObjects&) = delete;
  void operator=(const vtkMultiMaterialLiveObjects&) = delete;
};

#endif
