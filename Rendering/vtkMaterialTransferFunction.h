/**
 * @class   vtkMaterialTransferFunction
 * @brief   Maps a data value to the material parameters: the seven of Zhang &
 *          Ma eq. 4 plus the phase-function anisotropy of the path tracer.
 *
 * Nodes are placed in data units (like vtkColorTransferFunction) and carry
 * (ambient, diffuse, specular, shininess, attenuation, scattering, reflection,
 * anisotropy);
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

  /// Number of numbers per node in flat arrays: value + 8 parameters.
  static constexpr int NodeStride = 9;
  /// The flat layout before anisotropy: value + 7 parameters (g = 0).
  static constexpr int LegacyNodeStride = 8;
  /// Parameters per node (mmv::MaterialParameterCount): size arrays with it.
  static constexpr int NumberOfParameters = NodeStride - 1;

  /**
   * Adds a node; a node already at `value` is replaced. Returns the node's
   * index in value order, or -1 (with an error) if any argument is invalid.
   * Without `anisotropy` the node scatters isotropically (g = 0).
   */
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection);
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection, double anisotropy);
  int AddNode(double value, const double parameters[NumberOfParameters]);

  /// Removes the node at exactly `value`; returns its former index or -1.
  int RemoveNode(double value);
  void RemoveAllNodes();
  int GetSize() const;

  /// Node i as value + 8 parameters (false if i is out of range).
  bool GetNode(int i, double node[NodeStride]) const;

  /**
   * Replaces all nodes from a flat array of `count` numbers, 9 per node
   * (value, ka, kd, ks, shininess, attenuation, scattering, reflection,
   * anisotropy), the layout of ParaView's MaterialNodes property. The layout
   * before anisotropy, 8 per node (g = 0), still loads: see
   * DetectNodeStride(). Rejects the whole array (and keeps the current nodes)
   * if `count` makes no whole nodes or any number is invalid. Returns success.
   */
  bool SetNodes(int count, const double* nodes);
  /// Writes GetSize()*9 numbers in the SetNodes() layout.
  void GetNodes(double* nodes) const;

  /**
   * The layout of a flat node list: NodeStride, LegacyNodeStride, or 0 when
   * `count` is a multiple of neither. A count that is a multiple of both
   * (72, 144, ...) is read as NodeStride only if it makes valid nodes with
   * non-decreasing values (what GetNodes() writes), else as the legacy layout.
   */
  static int DetectNodeStride(int count, const double* nodes);

  /// The 8 parameters at `value` (interpolated, clamped outside the nodes).
  void Evaluate(double value, double parameters[NumberOfParameters]) const;
  double EvaluateParameter(double value, int parameter) const;

  /**
   * Samples `size` values evenly from xStart to xEnd (inclusive) into
   * `table`, 8 floats per sample: table[i*8 + p]. Used for GPU textures.
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
