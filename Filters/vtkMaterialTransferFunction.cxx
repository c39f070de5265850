#include "vtkMaterialTransferFunction.h"

#include "vtkMaterialJSON.h"
#include "vtkMaterialLibrary.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkMultiMaterialPhysicalMedium.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

static_assert(vtkMaterialTransferFunction::NodeStride == 1 + mmv::MaterialParameterCount,
  "a flat node is its value followed by every material parameter");
static_assert(vtkMaterialTransferFunction::EmissionNodeStride == 1 + mmv::TransmissionR,
  "the flat node before the transmission colour ends just before it");
static_assert(vtkMaterialTransferFunction::AnisotropyNodeStride == 1 + mmv::Emission,
  "the flat node before emission ends just before emission");
static_assert(vtkMaterialTransferFunction::LegacyNodeStride == 1 + mmv::Anisotropy,
  "the legacy flat node ends just before anisotropy");

namespace
{
struct Node
{
  double Value;
  std::array<double, mmv::MaterialParameterCount> Parameters;
};

/// Checks one node; fills `why` when it is rejected.
bool IsValidNode(const Node& node, std::string& why)
{
  if (!std::isfinite(node.Value))
  {
    why = "node value is not a finite number";
    return false;
  }
  for (int p = 0; p < mmv::MaterialParameterCount; ++p)
  {
    if (!mmv::IsValidMaterialValue(p, node.Parameters[p], &why))
    {
      why = "node at value " + std::to_string(node.Value) + ": " + why;
      return false;
    }
  }
  return true;
}

/// Reads `count` numbers, `stride` per node (NodeStride, or an older stride
/// whose nodes lack the trailing parameters: they take their defaults).
bool ReadFlatNodes(
  int count, const double* flat, int stride, std::vector<Node>& nodes, std::string& why)
{
  nodes.assign(count / stride, Node());
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    const double* node = flat + i * stride;
    nodes[i].Value = node[0];
    for (int p = 0; p < mmv::MaterialParameterCount; ++p)
    {
      nodes[i].Parameters[p] =
        p + 1 < stride ? node[p + 1] : mmv::MaterialParameterTable[p].Default;
    }
    if (!IsValidNode(nodes[i], why))
    {
      why = "node " + std::to_string(i) + ": " + why;
      return false;
    }
  }
  return true;
}

/// Sorts by value; of several nodes at one value the last one wins, as if
/// they had been added one by one with AddNode().
void SortAndMerge(std::vector<Node>& nodes)
{
  std::stable_sort(
    nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a.Value < b.Value; });
  std::vector<Node> merged;
  merged.reserve(nodes.size());
  for (const Node& node : nodes)
  {
    if (!merged.empty() && merged.back().Value == node.Value)
    {
      merged.back() = node;
    }
    else
    {
      merged.push_back(node);
    }
  }
  nodes.swap(merged);
}

/// Parses the JSON form into sorted, validated nodes.
bool ParseNodes(const std::string& text, std::vector<Node>& nodes, std::string& why)
{
  mmv::Json root;
  if (!mmv::ParseJSON(text, root, why))
  {
    return false;
  }
  if (!root.is_object())
  {
    why = "the top level must be an object with a \"nodes\" array";
    return false;
  }
  for (auto it = root.begin(); it != root.end(); ++it)
  {
    if (it.key() != "nodes")
    {
      why = "unknown top-level key \"" + it.key() + "\"";
      return false;
    }
  }
  const auto nodesIt = root.find("nodes");
  if (nodesIt == root.end() || !nodesIt->is_array())
  {
    why = "the top level must be an object with a \"nodes\" array";
    return false;
  }
  std::vector<Node> parsed;
  for (std::size_t i = 0; i < nodesIt->size(); ++i)
  {
    const mmv::Json& item = (*nodesIt)[i];
    const std::string where = "node " + std::to_string(i) + ": ";
    Node node;
    if (!mmv::ReadMaterialParameters(item, { "value" }, node.Parameters.data(), why))
    {
      why = where + why;
      return false;
    }
    const auto valueIt = item.find("value");
    if (valueIt == item.end())
    {
      why = where + "missing \"value\"";
      return false;
    }
    if (!mmv::ReadFiniteNumber(*valueIt, "\"value\"", node.Value, why))
    {
      why = where + why;
      return false;
    }
    parsed.push_back(node);
  }
  SortAndMerge(parsed);
  nodes.swap(parsed);
  return true;
}
}

class vtkMaterialTransferFunction::vtkInternals
{
public:
  std::vector<Node> Nodes; // sorted by Value, no two at the same value
};

vtkStandardNewMacro(vtkMaterialTransferFunction);

vtkMaterialTransferFunction::vtkMaterialTransferFunction()
  : Internals(new vtkInternals)
{
}

vtkMaterialTransferFunction::~vtkMaterialTransferFunction()
{
  delete this->Internals;
}

int vtkMaterialTransferFunction::AddNode(double value, double ambient, double diffuse,
  double specular, double shininess, double attenuation, double scattering, double reflection)
{
  return this->AddNode(value, ambient, diffuse, specular, shininess, attenuation, scattering,
    reflection, mmv::MaterialParameterTable[mmv::Anisotropy].Default);
}

int vtkMaterialTransferFunction::AddNode(double value, double ambient, double diffuse,
  double specular, double shininess, double attenuation, double scattering, double reflection,
  double anisotropy)
{
  return this->AddNode(value, ambient, diffuse, specular, shininess, attenuation, scattering,
    reflection, anisotropy, mmv::MaterialParameterTable[mmv::Emission].Default);
}

int vtkMaterialTransferFunction::AddNode(double value, double ambient, double diffuse,
  double specular, double shininess, double attenuation, double scattering, double reflection,
  double anisotropy, double emission)
{
  const double white = mmv::MaterialParameterTable[mmv::TransmissionR].Default;
  return this->AddNode(value, ambient, diffuse, specular, shininess, attenuation, scattering,
    reflection, anisotropy, emission, white, white, white);
}

int vtkMaterialTransferFunction::AddNode(double value, double ambient, double diffuse,
  double specular, double shininess, double attenuation, double scattering, double reflection,
  double anisotropy, double emission, double transmissionR, double transmissionG,
  double transmissionB)
{
  const double parameters[mmv::MaterialParameterCount] = { ambient, diffuse, specular, shininess,
    attenuation, scattering, reflection, anisotropy, emission, transmissionR, transmissionG,
    transmissionB };
  return this->AddNode(value, parameters);
}

int vtkMaterialTransferFunction::AddNode(double value, const double parameters[NumberOfParameters])
{
  if (!parameters)
  {
    vtkErrorMacro("AddNode: no parameters given.");
    return -1;
  }
  Node node;
  node.Value = value;
  std::copy(parameters, parameters + mmv::MaterialParameterCount, node.Parameters.begin());
  std::string why;
  if (!IsValidNode(node, why))
  {
    vtkErrorMacro("AddNode: " << why << "; the function is unchanged.");
    return -1;
  }
  std::vector<Node>& nodes = this->Internals->Nodes;
  auto it = std::lower_bound(
    nodes.begin(), nodes.end(), value, [](const Node& n, double v) { return n.Value < v; });
  if (it != nodes.end() && it->Value == value)
  {
    *it = node;
  }
  else
  {
    it = nodes.insert(it, node);
  }
  this->Modified();
  return static_cast<int>(it - nodes.begin());
}

int vtkMaterialTransferFunction::AddPhysicalMediumNode(
  double value, double albedo, double anisotropy, double extinctionPerVoxel)
{
  double parameters[NumberOfParameters];
  std::string why;
  if (!mmv::PhysicalMediumToMaterial(albedo, anisotropy, extinctionPerVoxel, parameters, &why))
  {
    vtkErrorMacro("AddPhysicalMediumNode: " << why);
    return -1;
  }
  return this->AddNode(value, parameters);
}

std::string vtkMaterialTransferFunction::PhysicalMediumDomainError(
  double albedo, double anisotropy, double extinctionPerVoxel)
{
  double parameters[NumberOfParameters];
  std::string why;
  return mmv::PhysicalMediumToMaterial(albedo, anisotropy, extinctionPerVoxel, parameters, &why)
    ? std::string()
    : why;
}

int vtkMaterialTransferFunction::RemoveNode(double value)
{
  std::vector<Node>& nodes = this->Internals->Nodes;
  auto it = std::lower_bound(
    nodes.begin(), nodes.end(), value, [](const Node& n, double v) { return n.Value < v; });
  if (it == nodes.end() || it->Value != value)
  {
    return -1;
  }
  const int index = static_cast<int>(it - nodes.begin());
  nodes.erase(it);
  this->Modified();
  return index;
}

void vtkMaterialTransferFunction::RemoveAllNodes()
{
  this->Internals->Nodes.clear();
  this->Modified();
}

int vtkMaterialTransferFunction::GetSize() const
{
  return static_cast<int>(this->Internals->Nodes.size());
}

bool vtkMaterialTransferFunction::GetNode(int i, double node[NodeStride]) const
{
  if (i < 0 || i >= this->GetSize() || !node)
  {
    return false;
  }
  const Node& n = this->Internals->Nodes[i];
  node[0] = n.Value;
  std::copy(n.Parameters.begin(), n.Parameters.end(), node + 1);
  return true;
}

int vtkMaterialTransferFunction::DetectNodeStride(int count, const double* nodes)
{
  // Newest first: of several layouts that fit, the newest one that reads as
  // valid, sorted nodes wins, else the oldest that fits.
  constexpr int Strides[4] = { NodeStride, EmissionNodeStride, AnisotropyNodeStride,
    LegacyNodeStride };
  std::vector<int> fitting;
  for (int stride : Strides)
  {
    if (count >= 0 && count % stride == 0)
    {
      fitting.push_back(stride);
    }
  }
  if (fitting.size() <= 1 || !nodes)
  {
    return fitting.empty() ? 0 : fitting.front();
  }
  for (std::size_t i = 0; i + 1 < fitting.size(); ++i)
  {
    std::vector<Node> parsed;
    std::string why;
    if (ReadFlatNodes(count, nodes, fitting[i], parsed, why) &&
      std::is_sorted(parsed.begin(), parsed.end(),
        [](const Node& a, const Node& b) { return a.Value < b.Value; }))
    {
      return fitting[i];
    }
  }
  return fitting.back();
}

bool vtkMaterialTransferFunction::SetNodes(int count, const double* nodes)
{
  const int stride = DetectNodeStride(count, nodes);
  if (stride == 0)
  {
    vtkErrorMacro("SetNodes: " << count << " numbers do not make whole nodes of " << NodeStride
                               << " (value + " << mmv::MaterialParameterCount
                               << " parameters) nor of the older " << EmissionNodeStride << ", "
                               << AnisotropyNodeStride << " or " << LegacyNodeStride
                               << "; the function is unchanged.");
    return false;
  }
  if (count > 0 && !nodes)
  {
    vtkErrorMacro("SetNodes: no array given for " << count << " numbers.");
    return false;
  }
  std::vector<Node> parsed;
  std::string why;
  if (!ReadFlatNodes(count, nodes, stride, parsed, why))
  {
    vtkErrorMacro("SetNodes: " << why << "; the function is unchanged.");
    return false;
  }
  SortAndMerge(parsed);
  this->Internals->Nodes.swap(parsed);
  this->Modified();
  return true;
}

void vtkMaterialTransferFunction::GetNodes(double* nodes) const
{
  if (!nodes)
  {
    return;
  }
  for (const Node& n : this->Internals->Nodes)
  {
    *nodes++ = n.Value;
    nodes = std::copy(n.Parameters.begin(), n.Parameters.end(), nodes);
  }
}

void vtkMaterialTransferFunction::Evaluate(
  double value, double parameters[NumberOfParameters]) const
{
  const std::vector<Node>& nodes = this->Internals->Nodes;
  if (nodes.empty())
  {
    for (int p = 0; p < mmv::MaterialParameterCount; ++p)
    {
      parameters[p] = mmv::MaterialParameterTable[p].Default;
    }
    return;
  }
  // Written so a NaN value takes the first node rather than garbage.
  if (!(value > nodes.front().Value))
  {
    std::copy(nodes.front().Parameters.begin(), nodes.front().Parameters.end(), parameters);
    return;
  }
  if (value >= nodes.back().Value)
  {
    std::copy(nodes.back().Parameters.begin(), nodes.back().Parameters.end(), parameters);
    return;
  }
  // First node above value; front < value < back, so both neighbours exist.
  const auto upper = std::upper_bound(
    nodes.begin(), nodes.end(), value, [](double v, const Node& n) { return v < n.Value; });
  const Node& n1 = *upper;
  const Node& n0 = *(upper - 1);
  const double t = (value - n0.Value) / (n1.Value - n0.Value);
  for (int p = 0; p < mmv::MaterialParameterCount; ++p)
  {
    parameters[p] = n0.Parameters[p] + t * (n1.Parameters[p] - n0.Parameters[p]);
  }
}

double vtkMaterialTransferFunction::EvaluateParameter(double value, int parameter) const
{
  if (parameter < 0 || parameter >= mmv::MaterialParameterCount)
  {
    vtkErrorMacro("EvaluateParameter: unknown material parameter index " << parameter << ".");
    return 0.0;
  }
  double parameters[mmv::MaterialParameterCount];
  this->Evaluate(value, parameters);
  return parameters[parameter];
}

void vtkMaterialTransferFunction::GetTable(double xStart, double xEnd, int size, float* table) const
{
  if (size <= 0 || !table)
  {
    vtkErrorMacro("GetTable: needs a positive size and a table (size = " << size << ").");
    return;
  }
  if (!std::isfinite(xStart) || !std::isfinite(xEnd))
  {
    vtkErrorMacro("GetTable: the range [" << xStart << ", " << xEnd << "] is not finite.");
    return;
  }
  double parameters[mmv::MaterialParameterCount];
  for (int i = 0; i < size; ++i)
  {
    double x = xStart;
    if (size > 1)
    {
      // The last sample is exactly xEnd: the formula could round past it.
      x = i == size - 1 ? xEnd : xStart + (xEnd - xStart) * i / (size - 1);
    }
    this->Evaluate(x, parameters);
    for (int p = 0; p < mmv::MaterialParameterCount; ++p)
    {
      table[i * mmv::MaterialParameterCount + p] = static_cast<float>(parameters[p]);
    }
  }
}

double vtkMaterialTransferFunction::GetMaximum(int parameter) const
{
  if (parameter < 0 || parameter >= mmv::MaterialParameterCount)
  {
    vtkErrorMacro("GetMaximum: unknown material parameter index " << parameter << ".");
    return 0.0;
  }
  const std::vector<Node>& nodes = this->Internals->Nodes;
  if (nodes.empty())
  {
    return mmv::MaterialParameterTable[parameter].Default;
  }
  double maximum = nodes.front().Parameters[parameter];
  for (const Node& n : nodes)
  {
    maximum = std::max(maximum, n.Parameters[parameter]);
  }
  return maximum;
}

bool vtkMaterialTransferFunction::HasNonZero(int parameter) const
{
  if (parameter < 0 || parameter >= mmv::MaterialParameterCount)
  {
    vtkErrorMacro("HasNonZero: unknown material parameter index " << parameter << ".");
    return false;
  }
  const std::vector<Node>& nodes = this->Internals->Nodes;
  return std::any_of(nodes.begin(), nodes.end(),
    [parameter](const Node& n) { return n.Parameters[parameter] != 0.0; });
}

bool vtkMaterialTransferFunction::HasChromaticTransmission() const
{
  const std::vector<Node>& nodes = this->Internals->Nodes;
  return std::any_of(nodes.begin(), nodes.end(),
    [](const Node& n)
    {
      return mmv::IsChromaticTransmission(n.Parameters[mmv::TransmissionR],
        n.Parameters[mmv::TransmissionG], n.Parameters[mmv::TransmissionB]);
    });
}

bool vtkMaterialTransferFunction::GetNonZeroRange(int parameter, double range[2]) const
{
  if (parameter < 0 || parameter >= mmv::MaterialParameterCount)
  {
    vtkErrorMacro("GetNonZeroRange: unknown material parameter index " << parameter << ".");
    return false;
  }
  const double infinity = std::numeric_limits<double>::infinity();
  const std::vector<Node>& nodes = this->Internals->Nodes;
  if (nodes.empty())
  {
    if (mmv::MaterialParameterTable[parameter].Default == 0.0)
    {
      return false;
    }
    range[0] = -infinity; // the default everywhere
    range[1] = infinity;
    return true;
  }
  auto nonZero = [parameter](const Node& n) { return n.Parameters[parameter] != 0.0; };
  const auto first = std::find_if(nodes.begin(), nodes.end(), nonZero);
  if (first == nodes.end())
  {
    return false;
  }
  const auto last = std::find_if(nodes.rbegin(), nodes.rend(), nonZero);
  range[0] = first == nodes.begin() ? -infinity : std::prev(first)->Value;
  range[1] = last == nodes.rbegin() ? infinity : std::prev(last)->Value;
  return true;
}

void vtkMaterialTransferFunction::GetRange(double range[2]) const
{
  const std::vector<Node>& nodes = this->Internals->Nodes;
  range[0] = nodes.empty() ? 0.0 : nodes.front().Value;
  range[1] = nodes.empty() ? 0.0 : nodes.back().Value;
}

bool vtkMaterialTransferFunction::ApplyPreset(const char* name, double rangeMin, double rangeMax)
{
  if (!name)
  {
    vtkErrorMacro("ApplyPreset: no preset name given.");
    return false;
  }
  if (!std::isfinite(rangeMin) || !std::isfinite(rangeMax) || rangeMin > rangeMax)
  {
    vtkErrorMacro("ApplyPreset: invalid range [" << rangeMin << ", " << rangeMax
                                                 << "]; the function is unchanged.");
    return false;
  }
  vtkNew<vtkMaterialLibrary> library;
  // Checked here so the error is reported by this object, not the library.
  if (!library->HasPreset(name))
  {
    vtkErrorMacro(
      "ApplyPreset: unknown material preset \"" << name << "\"; the function is unchanged.");
    return false;
  }
  Node node;
  library->GetPreset(name, node.Parameters.data());
  std::vector<Node> nodes;
  node.Value = rangeMin;
  nodes.push_back(node);
  if (rangeMax != rangeMin)
  {
    node.Value = rangeMax;
    nodes.push_back(node);
  }
  this->Internals->Nodes.swap(nodes);
  this->Modified();
  return true;
}

std::string vtkMaterialTransferFunction::ToJSON() const
{
  mmv::Json nodes = mmv::Json::array();
  for (const Node& n : this->Internals->Nodes)
  {
    mmv::Json node = mmv::Json::object();
    node["value"] = n.Value;
    mmv::WriteMaterialParameters(n.Parameters.data(), node);
    nodes.push_back(node);
  }
  mmv::Json root = mmv::Json::object();
  root["nodes"] = nodes;
  return root.dump(2);
}

bool vtkMaterialTransferFunction::FromJSON(const std::string& json)
{
  std::vector<Node> nodes;
  std::string why;
  if (!ParseNodes(json, nodes, why))
  {
    vtkErrorMacro("FromJSON: " << why << "; the function is unchanged.");
    return false;
  }
  this->Internals->Nodes.swap(nodes);
  this->Modified();
  return true;
}

bool vtkMaterialTransferFunction::WriteJSONFile(const char* path) const
{
  std::string why;
  if (!mmv::WriteTextFile(path, this->ToJSON(), why))
  {
    vtkErrorMacro("WriteJSONFile: " << why << ".");
    return false;
  }
  return true;
}

bool vtkMaterialTransferFunction::ReadJSONFile(const char* path)
{
  std::string text;
  std::vector<Node> nodes;
  std::string why;
  if (!mmv::ReadTextFile(path, text, why))
  {
    vtkErrorMacro("ReadJSONFile: " << why << "; the function is unchanged.");
    return false;
  }
  if (!ParseNodes(text, nodes, why))
  {
    vtkErrorMacro("ReadJSONFile: \"" << path << "\": " << why << "; the function is unchanged.");
    return false;
  }
  this->Internals->Nodes.swap(nodes);
  this->Modified();
  return true;
}

void vtkMaterialTransferFunction::DeepCopy(vtkMaterialTransferFunction* other)
{
  if (!other)
  {
    vtkErrorMacro("DeepCopy: no function to copy from.");
    return;
  }
  if (other == this)
  {
    return;
  }
  this->Internals->Nodes = other->Internals->Nodes;
  this->Modified();
}

void vtkMaterialTransferFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const std::vector<Node>& nodes = this->Internals->Nodes;
  os << indent << "Nodes: " << nodes.size() << "\n";
  for (const Node& n : nodes)
  {
    os << indent.GetNextIndent() << "value " << n.Value << ":";
    for (int p = 0; p < mmv::MaterialParameterCount; ++p)
    {
      os << " " << mmv::MaterialParameterTable[p].Key << "=" << n.Parameters[p];
    }
    os << "\n";
  }
}
