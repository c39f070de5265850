#include "vtkMultiMaterialLiveObjects.h"

#include "vtkObjectFactory.h"

#include <map>
#include <mutex>
#include <string>

vtkStandardNewMacro(vtkMultiMaterialLiveObjects);

namespace
{
struct Registry
{
  std::mutex Mutex;
  std::map<std::string, int> Counts;
};

Registry& TheRegistry()
{
  // Never destroyed: objects held by statics may die after it would.
  static Registry* registry = new Registry;
  return *registry;
}
}

void vtkMultiMaterialLiveObjects::Constructed(const char* className)
{
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.Mutex);
  ++r.Counts[className ? className : ""];
}

void vtkMultiMaterialLiveObjects::Destroyed(const char* className)
{
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.Mutex);
  --r.Counts[className ? className : ""];
}

int vtkMultiMaterialLiveObjects::GetCount()
{
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.Mutex);
  int total = 0;
  for (const auto& entry : r.Counts)
  {
    total += entry.second;
  }
  return total;
}

int vtkMultiMaterialLiveObjects::GetCount(const char* className)
{
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.Mutex);
  const auto found = r.Counts.find(className ? className : "");
  return found == r.Counts.end() ? 0 : found->second;
}

void vtkMultiMaterialLiveObjects::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.Mutex);
  for (const auto& entry : r.Counts)
  {
    os << indent << entry.first << ": " << entry.second << "\n";
  }
}
