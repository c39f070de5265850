/**
 * @file   mmvTestUtilities.h
 * @brief  Helpers shared by the unit tests (header-only).
 */
#ifndef mmvTestUtilities_h
#define mmvTestUtilities_h

#include "vtkCommand.h"
#include "vtkObject.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <string>
#include <utility>
#include <vector>

namespace mmvtest
{

/**
 * Counts the ErrorEvents and WarningEvents of the objects it watches, and
 * keeps the last message. While an object is observed, VTK does not print
 * its errors and warnings, so expected failures keep the test log clean.
 * The observers are removed when the counter goes out of scope (objects that
 * died first are skipped).
 *
 *   mmvtest::ErrorCounter errors(filter);
 *   errors.Watch(filter->GetExecutive()); // pipeline errors too
 *   EXPECT_EQ(errors.Errors(), 1) << errors.LastMessage();
 */
class ErrorCounter
{
public:
  explicit ErrorCounter(vtkObject* object = nullptr)
  {
    if (object)
    {
      this->Watch(object);
    }
  }
  ~ErrorCounter()
  {
    for (auto& watched : this->Watched)
    {
      if (vtkObject* object = watched.first)
      {
        object->RemoveObserver(watched.second[0]);
        object->RemoveObserver(watched.second[1]);
      }
    }
  }
  ErrorCounter(const ErrorCounter&) = delete;
  ErrorCounter& operator=(const ErrorCounter&) = delete;

  /// Also counts `object`'s events.
  void Watch(vtkObject* object)
  {
    this->Watched.emplace_back(object,
      std::vector<unsigned long>{ object->AddObserver(vtkCommand::ErrorEvent, this->Callback),
        object->AddObserver(vtkCommand::WarningEvent, this->Callback) });
  }

  int Errors() const { return this->Callback->Errors; }
  int Warnings() const { return this->Callback->Warnings; }
  /// The text of the last error or warning ("" if none).
  const std::string& LastMessage() const { return this->Callback->Last; }
  /// Back to no events (between the cases of one test).
  void Reset()
  {
    this->Callback->Errors = 0;
    this->Callback->Warnings = 0;
    this->Callback->Last.clear();
  }

private:
  class Command : public vtkCommand
  {
  public:
    static Command* New() { return new Command; }
    void Execute(vtkObject*, unsigned long event, void* callData) override
    {
      ++(event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings);
      this->Last = callData ? static_cast<const char*>(callData) : "";
    }
    int Errors = 0;
    int Warnings = 0;
    std::string Last;
  };

  vtkSmartPointer<Command> Callback = vtkSmartPointer<Command>::New();
  std::vector<std::pair<vtkWeakPointer<vtkObject>, std::vector<unsigned long>>> Watched;
};

} // namespace mmvtest

#endif
