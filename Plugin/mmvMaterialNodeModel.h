/**
 * @file   mmvMaterialNodeModel.h
 * @brief  The Multi-Material Editor's nodes, without Qt: what
 *         pqMaterialNodesPropertyWidget edits and pqMaterialNodesTrack draws.
 *
 * The MaterialNodes property is a flat list, vtkMaterialTransferFunction's
 * SetNodes() layout (13 numbers a node: the data value, then the 12 material
 * parameters of mmv::MaterialParameterTable; 10, 9 or 8 in older states). The
 * model holds it as sorted nodes with distinct values and one selection, and
 * does every edit the editor offers: add (parameters interpolated as the
 * renderer does), remove, move (kept between its neighbours), set one
 * parameter, apply a preset. Numbers the renderer rejects are replaced by
 * stand-ins when loaded and reported (LoadProblems), so the editor never
 * shows a NaN or writes one back. Unit-tested by Testing/Cxx/TestMaterialNodeModel.
 */
#ifndef mmvMaterialNodeModel_h
#define mmvMaterialNodeModel_h

#include "vtkMaterialLibrary.h"
#include "vtkMaterialTransferFunction.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"

#include <array>
#include <string>
#include <vector>

namespace mmv
{
class MaterialNodeModel
{
public:
  static constexpr int Stride = vtkMaterialTransferFunction::NodeStride; // value + 12 parameters
  static constexpr int ParameterCount = MaterialParameterCount;
  static_assert(Stride == ParameterCount + 1, "MaterialNodes layout: value + parameters");
  using Node = std::array<double, Stride>;

  /// A number of the loaded list the renderer rejects. Parameter -1: the
  /// node's value is not finite and the node is left out (Node is its index
  /// in the list as given); otherwise Node is its index once sorted and the
  /// parameter shows `Shown` instead of `Value` (NaN: the default; out of
  /// limits: the nearest limit).
  struct LoadProblem
  {
    int Node = -1;
    int Parameter = -1;
    double Value = 0.0;
    double Shown = 0.0;
    std::string Why;
  };

  ///@{
  /// The property's flat list. SetFlat() reads any SetNodes() layout, sorts
  /// the nodes and sanitises them (see LoadProblem); the selection is kept
  /// when the node count is unchanged (undo of a drag) and cleared otherwise.
  void SetFlat(const std::vector<double>& flat);
  std::vector<double> GetFlat() const;
  ///@}

  const std::vector<Node>& GetNodes() const { return this->Nodes; }
  int GetNumberOfNodes() const { return static_cast<int>(this->Nodes.size()); }

  ///@{
  /// The selected node, -1 for none (an index out of range selects none).
  int GetCurrent() const { return this->Current; }
  void SetCurrent(int index);
  bool HasCurrent() const { return this->Current >= 0; }
  ///@}

  ///@{
  /// What the last SetFlat() replaced; cleared by ClearLoadProblems() (the
  /// editor does when it writes the nodes back: they hold only stand-ins).
  const std::vector<LoadProblem>& GetLoadProblems() const { return this->LoadProblems; }
  void ClearLoadProblems() { this->LoadProblems.clear(); }
  /// Whether parameter `parameter` of node `node` shows a stand-in.
  bool IsStandIn(int node, int parameter) const;
  ///@}

  /**
   * Adds a node at `value` with the parameters the renderer interpolates
   * there (the table defaults with no nodes) and selects it; returns its
   * index. A node already at `value` is selected instead (`inserted` false).
   * A non-finite value adds nothing and returns -1.
   */
  int Insert(double value, bool* inserted = nullptr);

  /// Removes the selected node and selects its successor (or the new last
  /// node), so repeated removal clears nodes one after another.
  bool RemoveCurrent();

  /**
   * Moves node `index` to `value`, kept strictly between its neighbours
   * (equal values would merge in vtkMaterialTransferFunction): it stops
   * 1e-4 of `range` short of them. False (nothing moved) for a bad index or
   * a non-finite value.
   */
  bool Move(int index, double value, const double range[2]);

  /// Sets one parameter of node `index`; false for a bad index or parameter.
  bool SetParameter(int index, int parameter, double value);

  ///@{
  /**
   * Typed text for the value of node `index` or for one of its parameters.
   * Text that is not a finite number, or a parameter outside its limits, is
   * refused (nothing changes); a value past a neighbour is moved next to it
   * (Move). Either way GetNotice() says what happened to the text, so the
   * editor can show it; an edit that went through as typed clears it.
   */
  bool SetValueText(int index, const std::string& text, const double range[2]);
  bool SetParameterText(int index, int parameter, const std::string& text);
  ///@}

  /// Why `text` cannot be parameter `parameter` ("" when it can), keeping
  /// `kept`: the notice SetParameterText gives, for editors that refuse
  /// text as it is typed.
  static std::string ParameterTextNotice(int parameter, const std::string& text, double kept);

  ///@{
  /// What the last typed edit was refused for or changed to ("" for none).
  const std::string& GetNotice() const { return this->Notice; }
  void ClearNotice() { this->Notice.clear(); }
  ///@}

  /// Gives the selected node `parameters` (a preset's); false without one.
  bool SetCurrentParameters(const double parameters[ParameterCount]);

  /// Two nodes at the ends of `range` with `parameters`, none selected: what
  /// vtkMaterialTransferFunction::ApplyPreset() makes of a preset.
  void SetUniform(const double parameters[ParameterCount], const double range[2]);

  /// Replaces the nodes by preset `name` spread over [lo, hi], as the
  /// representation applies it; false (nodes unchanged) for an unknown preset
  /// or a bad range.
  bool TakePreset(const char* name, double lo, double hi);

  /**
   * The range a track showing the nodes spans: `dataRange` (null: none),
   * widened to include every node; [0, 1] with neither, and a window around
   * a single node without data.
   */
  void TrackRange(const double* dataRange, double range[2]) const;

  ///@{
  /// The nodes interpolated as the renderer interpolates them.
  void Evaluate(double value, double parameters[ParameterCount]) const;
  double EvaluateParameter(double value, int parameter) const;
  ///@}

  /// The preset whose parameters `node` carries (to 1e-9), or null.
  const char* PresetOf(const Node& node) const;

  /// The built-in and loaded material presets.
  vtkMaterialLibrary* GetLibrary() const { return this->Library; }

private:
  void Sanitize(std::vector<Node>& nodes);
  void Sync();

  std::vector<Node> Nodes; // sorted by value, values distinct
  int Current = -1;
  std::vector<LoadProblem> LoadProblems;
  std::string Notice;
  vtkNew<vtkMaterialLibrary> Library;
  // Mirror of the nodes, so interpolation matches the renderer's exactly.
  vtkNew<vtkMaterialTransferFunction> Function;
};
}

#endif
