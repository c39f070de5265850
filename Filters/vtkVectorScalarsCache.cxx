#include "vtkVectorScalarsCache.h"

#include "vtkDataArray.h"
#include "vtkVolumeInputScalars.h"

vtkDataArray* vtkVectorScalarsCache::Get(
  vtkDataArray* vectors, int mode, int component, std::string* error)
{
  if (!vectors)
  {
    if (error)
    {
      *error = "no array";
    }
    return nullptr;
  }
  const vtkMTimeType time = vectors->GetMTime();
  // Arrays of deleted or modified vectors can never be asked for again
  // (modification times only grow; a new array at a freed address has a
  // newer time, and the weak pointer is null meanwhile).
  this->Entries.remove_if([](const Entry& e) { return !e.From; });
  for (auto entry = this->Entries.begin(); entry != this->Entries.end();)
  {
    if (entry->From == vectors && entry->FromTime != time)
    {
      entry = this->Entries.erase(entry);
    }
    else
    {
      ++entry;
    }
  }
  auto found = this->Entries.begin();
  for (; found != this->Entries.end(); ++found)
  {
    if (found->From == vectors && found->Mode == mode && found->Component == component)
    {
      break;
    }
  }
  if (found == this->Entries.end())
  {
    vtkSmartPointer<vtkDataArray> reduced = mmv::MakeVectorScalars(vectors, mode, component, error);
    if (!reduced)
    {
      return nullptr;
    }
    ++this->Reductions;
    Entry entry;
    entry.From = vectors;
    entry.FromTime = time;
    entry.Mode = mode;
    entry.Component = component;
    entry.Reduced = reduced;
    this->Entries.push_front(entry);
  }
  else if (found != this->Entries.begin())
  {
    this->Entries.splice(this->Entries.begin(), this->Entries, found);
  }
  if (!this->KeepAll)
  {
    this->Entries.resize(1);
  }
  return this->Entries.front().Reduced;
}

size_t vtkVectorScalarsCache::GetBytes() const
{
  size_t bytes = 0;
  for (const Entry& e : this->Entries)
  {
    bytes += static_cast<size_t>(e.Reduced->GetActualMemorySize()) * 1024u;
  }
  return bytes;
}
