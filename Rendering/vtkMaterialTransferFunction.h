/**
 * @class   vtkMaterialTransferFunction
 * @brief   Maps a data value to the seven material parameters of Zhang & Ma eq. 4.
 *
 * Nodes are placed in data units (like vtkColorTransferFunction) and carry
 * (ambient, diffuse, specular, shininess, attenuation, scattering, reflection);
 * colour and opacity stay in the usual vtkVolumeProperty. Between nodes the
 * parameters are interpolated linearly; outside the nodes they are clamped to
 * the first/last node. With no nodes, Evaluate() returns the defaults of
 * mmv::MaterialParameterTable. The parameter layout, units and limits are in
 * vtkMultiMaterialParameters.h.
 *
 * Every edit bumps the MTime. Invalid input (a non-finite or negative value, a
 * value above the parameter's hard limit, malformed JSON, an unknown preset)
 * is reported with vtkErrorMacro and leaves the function unchanged.
 */
#ifndef vtkMaterialTransferFunction_h
#define vtkMaterialTransferFunction_h

#include "vtkMultiMaterialVolumeModule.h" // export macro
#include "vtkObject.h"

#include <string> // for JSON strings

class VTKMULTIMATERIALVOLUME_EXPORT vtkMaterialTransferFunction : public vtkObject
{
public:
  static vtkMaterialTransferFunction* New();
  vtkTypeMacro(vtkMaterialTransferFunction, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Number of numbers per node in flat arrays: value + 7 parameters.
  static constexpr int NodeStride = 8;

  /**
   * Adds a node; a node already at `value` is replaced. Returns the node's
   * index in value order, or -1 (with an error) if any argument is invalid.
   */
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection);
  int AddNode(double value, const double parameters[7]);

  /// Removes the node at exactly `value`; returns its former index or -1.
  int RemoveNode(double value);
  void RemoveAllNodes();
  int GetSize() const;

  /// Node i as value + 7 parameters (false if i is out of range).
  bool GetNode(int i, double node[8]) const;

  /**
   * Replaces all nodes from a flat array of `count` numbers, 8 per node
   * (value, ka, kd, ks, shininess, attenuation, scattering, reflection), the
   * layout of ParaView's MaterialNodes property. Rejects the whole array (and
   * keeps the current nodes) if `count` is not a multiple of 8 or any number
   * is invalid. Returns success.
   */
  bool SetNodes(int count, const double* nodes);
  /// Writes GetSize()*8 numbers in the SetNodes() layout.
  void GetNodes(double* nodes) const;

  /// The 7 parameters at `value` (interpolated, clamped outside the nodes).
  void Evaluate(double value, double parameters[7]) const;
  double EvaluateParameter(double value, int parameter) const;

  /**
   * Samples `size` values evenly from xStart to xEnd (inclusive) into
   * `table`, 7 floats per sample: table[i*7 + p]. Used for GPU textures.
   */
  void GetTable(double xStart, double xEnd, int size, float* table) const;

  /// Largest value of a parameter over all nodes (its default when empty).
  /// Lets callers skip work a scene does not need (e.g. no scattering).
  double GetMaximum(int parameter) const;

  /// Value range covered by the nodes (0,0 when empty).
  void GetRange(double range[2]) const;

  /**
   * Replaces the nodes with the named preset of vtkMaterialLibrary's
   * built-in presets, spread over [rangeMin, rangeMax] (two equal nodes).
   * Unknown names give an error and leave the function unchanged.
   */
  bool ApplyPreset(const char* name, double rangeMin, double rangeMax);

  ///@{
  /**
   * JSON form: {"nodes": [{"value": v, "ambient": .., "diffuse": .., ...}, ...]}
   * Missing parameter keys take their defaults; unknown keys are errors.
   * FromJSON/ReadJSONFile return false and change nothing on any error.
   */
  std::string ToJSON() const;
  bool FromJSON(const std::string& json);
  bool WriteJSONFile(const char* path) const;
  bool ReadJSONFile(const char* path);
  ///@}

  /// Copies the nodes of another function.
  void DeepCopy(vtkMaterialTransferFunction* other);

protected:
  vtkMaterialTransferFunction();
  ~vtkMaterialTransferFunction() override;

private:
  vtkMaterialTransferFunction(const vtkMaterialTransferFunction&) = delete;
  void operator=(const vtkMaterialTransferFunction&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
