/**
 * @class   vtkMaterialTransferFunction
 * @brief   Maps a data value to the material parameters: the seven of Zhang &
 *          Ma eq. 4 plus the phase-function anisotropy and the emission.
 *
 * Nodes are placed in data units (like vtkColorTransferFunction) and carry
 * (ambient, diffuse, specular, shininess, attenuation, scattering, reflection,
 * anisotropy, emission);
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

#include "vtkMultiMaterialVolumeFiltersModule.h" // export macro
#include "vtkObject.h"

#include <string> // for JSON strings

class VTKMULTIMATERIALVOLUMEFILTERS_EXPORT vtkMaterialTransferFunction : public vtkObject
{
public:
  static vtkMaterialTransferFunction* New();
  vtkTypeMacro(vtkMaterialTransferFunction, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Number of numbers per node in flat arrays: value + 12 parameters.
  static constexpr int NodeStride = 13;
  /// The flat layout before the transmission colour: value + 9 parameters
  /// (T = (1, 1, 1), grey).
  static constexpr int EmissionNodeStride = 10;
  /// The flat layout before emission: value + 8 parameters (e = 0).
  static constexpr int AnisotropyNodeStride = 9;
  /// The flat layout before anisotropy: value + 7 parameters (g = 0, e = 0).
  static constexpr int LegacyNodeStride = 8;
  /// Parameters per node (mmv::MaterialParameterCount): size arrays with it.
  static constexpr int NumberOfParameters = NodeStride - 1;

  /**
   * Adds a node; a node already at `value` is replaced. Returns the node's
   * index in value order, or -1 (with an error) if any argument is invalid.
   * Without `anisotropy` the node scatters isotropically (g = 0); without
   * `emission` it does not glow (e = 0); without a transmission colour its
   * shadows are grey (T = (1, 1, 1)).
   */
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection);
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection, double anisotropy);
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection, double anisotropy, double emission);
  int AddNode(double value, double ambient, double diffuse, double specular, double shininess,
    double attenuation, double scattering, double reflection, double anisotropy, double emission,
    double transmissionR, double transmissionG, double transmissionB);
  int AddNode(double value, const double parameters[NumberOfParameters]);

  /**
   * Adds a node (as AddNode) whose parameters model a participating medium
   * of known physics: single-scattering albedo in [0, 0.999],
   * Henyey-Greenstein anisotropy in [0, 0.9] and extinction per voxel > 0
   * (sigma_t times the voxel size: -ln(1 - alpha) for opacity alpha per
   * voxel). The mapping is mmv::PhysicalMediumToMaterial, fitted to the
   * Monte Carlo truth (docs/how-it-works.md, "Physical media"). Returns the
   * node's index, or -1 with an error saying why
   * (PhysicalMediumDomainError) outside that domain; nothing is added then.
   */
  int AddPhysicalMediumNode(
    double value, double albedo, double anisotropy, double extinctionPerVoxel);
  /// Why AddPhysicalMediumNode would refuse these values; empty when valid.
  static std::string PhysicalMediumDomainError(
    double albedo, double anisotropy, double extinctionPerVoxel);

  /// Removes the node at exactly `value`; returns its former index or -1.
  int RemoveNode(double value);
  void RemoveAllNodes();
  int GetSize() const;

  /// Node i as value + 12 parameters (false if i is out of range).
  bool GetNode(int i, double node[NodeStride]) const;

  /**
   * Replaces all nodes from a flat array of `count` numbers, 13 per node
   * (value, ka, kd, ks, shininess, attenuation, scattering, reflection,
   * anisotropy, emission, transmission r, g, b), the layout of ParaView's
   * MaterialNodes property. The older layouts still load: 10 per node before
   * the transmission colour (T = (1, 1, 1), grey), 9 before emission (e = 0)
   * and 8 before anisotropy (g = 0, e = 0); see DetectNodeStride(). Rejects the
   * whole array (and keeps the current nodes)
   * if `count` makes no whole nodes or any number is invalid. Returns success.
   */
  bool SetNodes(int count, const double* nodes);
  /// Writes GetSize()*13 numbers in the SetNodes() layout.
  void GetNodes(double* nodes) const;

  /**
   * The layout of a flat node list: NodeStride, EmissionNodeStride,
   * AnisotropyNodeStride, LegacyNodeStride, or 0 when `count` is a multiple
   * of none. A count that is a multiple of several (40, 72, 90, 130, ...) is
   * read with the newest of
   * them that makes valid nodes with non-decreasing values (what GetNodes()
   * writes), else with the oldest.
   */
  static int DetectNodeStride(int count, const double* nodes);

  /// The 12 parameters at `value` (interpolated, clamped outside the nodes).
  void Evaluate(double value, double parameters[NumberOfParameters]) const;
  double EvaluateParameter(double value, int parameter) const;

  /**
   * Samples `size` values evenly from xStart to xEnd (inclusive) into
   * `table`, 12 floats per sample: table[i*12 + p]. Used for GPU textures.
   */
  void GetTable(double xStart, double xEnd, int size, float* table) const;

  /// Largest value of a parameter over all nodes (its default when empty).
  /// Lets callers skip work a scene does not need (e.g. no scattering).
  double GetMaximum(int parameter) const;

  /// True when some node's value of the parameter is not 0 (false when
  /// empty: every default the shader can leave out is 0). Chooses the shader
  /// variant: no Henyey-Greenstein code for g = 0, no emission for e = 0.
  bool HasNonZero(int parameter) const;

  /// True when some node's transmission colour is not white (a channel
  /// below 1): shadows are tinted and the shaders need the RGB irradiance
  /// (MMV_USE_RGB_IRRADIANCE); false when empty (grey).
  bool HasChromaticTransmission() const;

  /**
   * The smallest value interval outside which `parameter` is 0 (linear
   * between nodes, clamped outside them): from the node before the first
   * non-zero one (-infinity when that is the first node) to the node after
   * the last non-zero one (+infinity when that is the last). False, range
   * untouched, when the parameter is 0 at every value. Lets a pass skip
   * what cannot reflect (vtkReflectionVisibilityPass).
   */
  bool GetNonZeroRange(int parameter, double range[2]) const;

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
