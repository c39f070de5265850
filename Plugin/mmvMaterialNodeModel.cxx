#include "mmvMaterialNodeModel.h"

#include "mmvNumberText.h"
#include "vtkLogger.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>

namespace mmv
{
//-----------------------------------------------------------------------------
void MaterialNodeModel::SetFlat(const std::vector<double>& flat)
{
  // States written before emission have 9 numbers a node (e = 0), before
  // anisotropy 8 (g = 0, e = 0); the missing fields come from the table.
  int stride =
    vtkMaterialTransferFunction::DetectNodeStride(static_cast<int>(flat.size()), flat.data());
  stride = stride > 0 ? stride : Stride;
  std::vector<Node> nodes;
  for (size_t i = 0; i + stride <= flat.size(); i += stride)
  {
    Node n;
    for (int k = 0; k < Stride; ++k)
    {
      n[k] = k < stride ? flat[i + k] : MaterialParameterTable[k - 1].Default;
    }
    nodes.push_back(n);
  }
  this->Sanitize(nodes);
  const bool sameCount = nodes.size() == this->Nodes.size();
  this->Nodes = std::move(nodes);
  // Keep the selection across value edits (undo of a drag); a different
  // node count means nodes came or went, so the index means nothing.
  if (!sameCount)
  {
    this->Current = -1;
  }
  this->Sync();
}

//-----------------------------------------------------------------------------
std::vector<double> MaterialNodeModel::GetFlat() const
{
  std::vector<double> flat;
  flat.reserve(this->Nodes.size() * Stride);
  for (const Node& n : this->Nodes)
  {
    flat.insert(flat.end(), n.begin(), n.end());
  }
  return flat;
}

//-----------------------------------------------------------------------------
void MaterialNodeModel::SetCurrent(int index)
{
  this->Current = (index >= 0 && index < this->GetNumberOfNodes()) ? index : -1;
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::IsStandIn(int node, int parameter) const
{
  return std::any_of(this->LoadProblems.begin(), this->LoadProblems.end(),
    [&](const LoadProblem& p)
    { return p.Parameter >= 0 && p.Node == node && p.Parameter == parameter; });
}

//-----------------------------------------------------------------------------
// Leaves out nodes at a non-finite value and replaces parameters the
// renderer rejects (NaN: the default; out of limits: the nearest limit),
// noting each in LoadProblems. `nodes` is sorted after.
void MaterialNodeModel::Sanitize(std::vector<Node>& nodes)
{
  this->LoadProblems.clear();
  std::vector<Node> kept;
  kept.reserve(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i)
  {
    if (std::isfinite(nodes[i][0]))
    {
      kept.push_back(nodes[i]);
      continue;
    }
    LoadProblem problem;
    problem.Node = static_cast<int>(i);
    problem.Value = problem.Shown = nodes[i][0];
    problem.Why = "the node's value is not a finite number";
    this->LoadProblems.push_back(problem);
  }
  nodes = std::move(kept);
  std::stable_sort(
    nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a[0] < b[0]; });
  for (size_t i = 0; i < nodes.size(); ++i)
  {
    for (int p = 0; p < ParameterCount; ++p)
    {
      double& v = nodes[i][p + 1];
      std::string why;
      if (IsValidMaterialValue(p, v, &why))
      {
        continue;
      }
      const MaterialParameterInfo& info = MaterialParameterTable[p];
      LoadProblem problem;
      problem.Node = static_cast<int>(i);
      problem.Parameter = p;
      problem.Value = v;
      problem.Shown =
        std::isfinite(v) ? std::min(info.HardMax, std::max(info.HardMin, v)) : info.Default;
      problem.Why = why;
      this->LoadProblems.push_back(problem);
      v = problem.Shown;
    }
  }
}

//-----------------------------------------------------------------------------
void MaterialNodeModel::Sync()
{
  const std::vector<double> flat = this->GetFlat();
  if (!this->Function->SetNodes(static_cast<int>(flat.size()), flat.data()))
  {
    // Sanitised nodes always pass; this would be a bug in Sanitize().
    vtkLogF(WARNING, "MaterialNodes holds invalid values; the curve may be stale");
  }
}

//-----------------------------------------------------------------------------
int MaterialNodeModel::Insert(double value, bool* inserted)
{
  if (inserted)
  {
    *inserted = false;
  }
  if (!std::isfinite(value))
  {
    return -1;
  }
  auto it = std::lower_bound(this->Nodes.begin(), this->Nodes.end(), value,
    [](const Node& n, double v) { return n[0] < v; });
  // The offset first: insert() may reallocate, invalidating `it`.
  const int index = static_cast<int>(it - this->Nodes.begin());
  if (it != this->Nodes.end() && (*it)[0] == value)
  {
    this->Current = index;
    return index;
  }
  Node node;
  node[0] = value;
  // Interpolating keeps the rendering unchanged until the user edits the
  // new node; with no nodes this yields the table defaults.
  this->Function->Evaluate(value, node.data() + 1);
  this->Nodes.insert(it, node);
  if (inserted)
  {
    *inserted = true;
  }
  this->Current = index;
  this->Sync();
  return index;
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::RemoveCurrent()
{
  if (this->Current < 0 || this->Current >= this->GetNumberOfNodes())
  {
    return false;
  }
  this->Nodes.erase(this->Nodes.begin() + this->Current);
  this->Current = std::min(this->Current, this->GetNumberOfNodes() - 1);
  this->Sync();
  return true;
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::Move(int index, double value, const double range[2])
{
  if (index < 0 || index >= this->GetNumberOfNodes() || !std::isfinite(value))
  {
    return false;
  }
  const double gap = (range[1] - range[0]) * 1e-4;
  if (index > 0)
  {
    value = std::max(value, this->Nodes[index - 1][0] + gap);
  }
  if (index + 1 < this->GetNumberOfNodes())
  {
    value = std::min(value, this->Nodes[index + 1][0] - gap);
  }
  this->Nodes[index][0] = value;
  this->Sync();
  return true;
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::SetParameter(int index, int parameter, double value)
{
  if (index < 0 || index >= this->GetNumberOfNodes() || parameter < 0 ||
    parameter >= ParameterCount)
  {
    return false;
  }
  this->Nodes[index][parameter + 1] = value;
  this->Sync();
  return true;
}

//-----------------------------------------------------------------------------
std::string MaterialNodeModel::ParameterTextNotice(
  int parameter, const std::string& text, double kept)
{
  if (parameter < 0 || parameter >= ParameterCount)
  {
    return "no such parameter";
  }
  const MaterialParameterInfo& info = MaterialParameterTable[parameter];
  const NumberText parsed = ParseNumberText(text, info.HardMin, info.HardMax);
  if (parsed.State == NumberTextState::Acceptable)
  {
    return std::string();
  }
  std::ostringstream notice;
  notice << "\"" << text << "\" refused: " << info.Key << " takes a number from " << info.HardMin
         << " to " << info.HardMax << " (such as 0.25 or 2.5e-1); kept " << kept;
  return notice.str();
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::SetParameterText(int index, int parameter, const std::string& text)
{
  if (index < 0 || index >= this->GetNumberOfNodes() || parameter < 0 ||
    parameter >= ParameterCount)
  {
    return false;
  }
  this->Notice = ParameterTextNotice(parameter, text, this->Nodes[index][parameter + 1]);
  if (!this->Notice.empty())
  {
    return false;
  }
  const MaterialParameterInfo& info = MaterialParameterTable[parameter];
  return this->SetParameter(
    index, parameter, ParseNumberText(text, info.HardMin, info.HardMax).Value);
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::SetValueText(int index, const std::string& text, const double range[2])
{
  if (index < 0 || index >= this->GetNumberOfNodes())
  {
    return false;
  }
  const NumberText parsed = ParseNumberText(text, -DBL_MAX, DBL_MAX);
  std::ostringstream notice;
  if (parsed.State != NumberTextState::Acceptable)
  {
    notice << "\"" << text << "\" refused: a node's value must be a finite number; kept "
           << this->Nodes[index][0];
    this->Notice = notice.str();
    return false;
  }
  this->Notice.clear();
  if (!this->Move(index, parsed.Value, range))
  {
    return false;
  }
  const double placed = this->Nodes[index][0];
  if (placed != parsed.Value)
  {
    notice << text << " moved to " << placed << ": node " << index + 1
           << " stays between its neighbours";
    if (index > 0)
    {
      notice << " (" << this->Nodes[index - 1][0];
      notice << (index + 1 < this->GetNumberOfNodes() ? " and " : ")");
    }
    else
    {
      notice << " (";
    }
    if (index + 1 < this->GetNumberOfNodes())
    {
      notice << this->Nodes[index + 1][0] << ")";
    }
    this->Notice = notice.str();
  }
  return true;
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::SetCurrentParameters(const double parameters[ParameterCount])
{
  if (this->Current < 0)
  {
    return false;
  }
  std::copy(parameters, parameters + ParameterCount, this->Nodes[this->Current].begin() + 1);
  this->Sync();
  return true;
}

//-----------------------------------------------------------------------------
void MaterialNodeModel::SetUniform(const double parameters[ParameterCount], const double range[2])
{
  Node lo, hi;
  lo[0] = range[0];
  hi[0] = range[1];
  std::copy(parameters, parameters + ParameterCount, lo.begin() + 1);
  std::copy(parameters, parameters + ParameterCount, hi.begin() + 1);
  this->Nodes = { lo, hi };
  this->Current = -1;
  this->Sync();
}

//-----------------------------------------------------------------------------
bool MaterialNodeModel::TakePreset(const char* name, double lo, double hi)
{
  vtkNew<vtkMaterialTransferFunction> preset;
  if (!name || !this->Library->HasPreset(name) || !preset->ApplyPreset(name, lo, hi))
  {
    return false;
  }
  std::vector<double> flat(static_cast<size_t>(preset->GetSize()) * Stride);
  preset->GetNodes(flat.data());
  this->Nodes.clear();
  for (size_t i = 0; i + Stride <= flat.size(); i += Stride)
  {
    Node n;
    std::copy(flat.begin() + i, flat.begin() + i + Stride, n.begin());
    this->Nodes.push_back(n);
  }
  this->Current = -1;
  this->Sync();
  return true;
}

//-----------------------------------------------------------------------------
void MaterialNodeModel::TrackRange(const double* dataRange, double range[2]) const
{
  double lo = dataRange ? dataRange[0] : VTK_DOUBLE_MAX;
  double hi = dataRange ? dataRange[1] : VTK_DOUBLE_MIN;
  // Nodes outside the data stay reachable.
  for (const Node& n : this->Nodes)
  {
    lo = std::min(lo, n[0]);
    hi = std::max(hi, n[0]);
  }
  if (!(lo <= hi))
  {
    lo = 0.0;
    hi = 1.0;
  }
  else if (!(hi > lo))
  {
    // One node and no data: centre it in a unit-ish window.
    const double half = std::max(0.5, std::abs(lo) * 0.5);
    lo -= half;
    hi += half;
  }
  range[0] = lo;
  range[1] = hi;
}

//-----------------------------------------------------------------------------
void MaterialNodeModel::Evaluate(double value, double parameters[ParameterCount]) const
{
  this->Function->Evaluate(value, parameters);
}

//-----------------------------------------------------------------------------
double MaterialNodeModel::EvaluateParameter(double value, int parameter) const
{
  return this->Function->EvaluateParameter(value, parameter);
}

//-----------------------------------------------------------------------------
const char* MaterialNodeModel::PresetOf(const Node& node) const
{
  for (int i = 0; i < this->Library->GetNumberOfPresets(); ++i)
  {
    const char* name = this->Library->GetPresetName(i);
    double p[ParameterCount];
    if (name && this->Library->GetPreset(name, p) &&
      std::equal(p, p + ParameterCount, node.begin() + 1,
        [](double a, double b) { return std::abs(a - b) <= 1e-9 * (1.0 + std::abs(a)); }))
    {
      return name;
    }
  }
  return nullptr;
}
}
