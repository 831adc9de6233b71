// Counting the events an algorithm invokes (progress reports, runs), for tests that assert how
// often something happened.
#ifndef MeshLODEventCounter_h
#define MeshLODEventCounter_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"

namespace meshlod
{
namespace testing
{
/// Counts `event` on `object` from construction on. Not copyable: the observer points at it.
class EventCounter
{
public:
  EventCounter(vtkObject* object, unsigned long event)
  {
    this->Command->SetClientData(&this->Count);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    object->AddObserver(event, this->Command);
  }
  EventCounter(const EventCounter&) = delete;
  EventCounter& operator=(const EventCounter&) = delete;

  int Count = 0;

private:
  vtkNew<vtkCallbackCommand> Command;
};
} // namespace testing
} // namespace meshlod

#endif
