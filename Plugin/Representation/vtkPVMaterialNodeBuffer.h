/**
 * @file   vtkPVMaterialNodeBuffer.h
 * @brief  Collects a MaterialNodes property pushed value by value.
 *
 * ParaView pushes a repeated, indexed DoubleVectorProperty as its count
 * (set_number_command) followed by one call per value. Collecting the values
 * and applying them once the last one arrived lets SetNodes() validate the
 * whole list: a count that makes no whole nodes is seen (a per-node command
 * would silently drop the remainder) and a bad value rejects the list, all or
 * nothing.
 */
#ifndef vtkPVMaterialNodeBuffer_h
#define vtkPVMaterialNodeBuffer_h

#include "vtkMaterialTransferFunction.h"
#include "vtkSetGet.h"

#include <algorithm>
#include <vector>

class vtkPVMaterialNodeBuffer
{
public:
  /// Starts a new list; true if it is already complete (no values follow).
  bool Announce(int count)
  {
    this->Values.assign(static_cast<size_t>(std::max(count, 0)), 0.0);
    this->Received = 0;
    return this->Values.empty();
  }

  /// Stores one value; true once every announced value has arrived.
  bool Receive(int index, double value)
  {
    if (index < 0 || index >= static_cast<int>(this->Values.size()))
    {
      return false;
    }
    this->Values[index] = value;
    return ++this->Received == static_cast<int>(this->Values.size());
  }

  /// Replaces the nodes of `function`; on invalid input reports an error on
  /// `owner` and leaves `function` unchanged. Returns success.
  bool Apply(vtkObject* owner, vtkMaterialTransferFunction* function) const
  {
    const int count = static_cast<int>(this->Values.size());
    if (vtkMaterialTransferFunction::DetectNodeStride(count, this->Values.data()) == 0)
    {
      vtkErrorWithObjectMacro(owner,
        "MaterialNodes needs " << vtkMaterialTransferFunction::NodeStride
                               << " numbers per node (value, ambient, diffuse, specular, "
                                  "shininess, attenuation, scattering, reflection, anisotropy, "
                                  "emission, transmission r, g, b; or the older "
                               << vtkMaterialTransferFunction::EmissionNodeStride
                               << " without transmission, "
                               << vtkMaterialTransferFunction::AnisotropyNodeStride
                               << " without emission or "
                               << vtkMaterialTransferFunction::LegacyNodeStride
                               << " without anisotropy); got " << count
                               << ". Keeping the previous nodes.");
      return false;
    }
    // SetNodes reports NaN, negative and too large values itself.
    return function->SetNodes(count, this->Values.data());
  }

private:
  std::vector<double> Values;
  int Received = 0;
};

#endif
