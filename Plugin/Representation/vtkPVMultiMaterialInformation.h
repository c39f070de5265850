/**
 * @class   vtkPVMultiMaterialInformation
 * @brief   The information properties of a Multi-Material Volume
 *          representation as the processes that render it hold them.
 *
 * The server manager reads information properties from the client's copy of
 * a representation, which does not render in client/server mode (its
 * counters stay 0). vtkSMMultiMaterialVolumeRepresentationProxy gathers this
 * from the render server instead: CopyFromObject() reads every information
 * property's getter of a vtkPVMultiMaterialVolumeRepresentation, and
 * AddInformation() combines the ranks of a parallel server: numbers take the
 * largest value (a count of any rank that rendered, the slowest rank's
 * seconds), texts and the applied nodes the first rank's that has them.
 */
#ifndef vtkPVMultiMaterialInformation_h
#define vtkPVMultiMaterialInformation_h

#include "vtkMultiMaterialVolumeParaViewModule.h" // export macro
#include "vtkPVInformation.h"

#include <map>    // for the values
#include <string> // for the names
#include <vector> // for the values

class VTKMULTIMATERIALVOLUMEPARAVIEW_EXPORT vtkPVMultiMaterialInformation : public vtkPVInformation
{
public:
  static vtkPVMultiMaterialInformation* New();
  vtkTypeMacro(vtkPVMultiMaterialInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void CopyFromObject(vtkObject* object) override;
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;

  /// Whether a representation was read (false on a process without one).
  bool HasValues() const { return !this->Numbers.empty(); }

  ///@{
  /// The values by information property name; false when not gathered.
  bool GetNumbers(const std::string& name, std::vector<double>& values) const;
  bool GetText(const std::string& name, std::string& text) const;
  ///@}

protected:
  vtkPVMultiMaterialInformation();
  ~vtkPVMultiMaterialInformation() override;

private:
  vtkPVMultiMaterialInformation(const vtkPVMultiMaterialInformation&) = delete;
  void operator=(const vtkPVMultiMaterialInformation&) = delete;

  std::map<std::string, std::vector<double>> Numbers;
  std::map<std::string, std::string> Texts;
};

#endif
