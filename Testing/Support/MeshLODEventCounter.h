// Counting the events an algorithm invokes (progress reports, runs), for tests that assert how
// often something happened.
#ifndef MeshLODEventCounter_h
#define MeshLODEventCounter_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkWeakPointer.h"

namespace meshlod
{
namespace testing
{
/// Counts `event` on `object` from construction to destruction. Not copyable: the observer
/// points at it (and is removed with it, should the object outlive the counter).
class EventCounter
{
public:
  EventCounter(vtkObject* object, unsigned long event)
    : Object(object)
  {
    this->Command->SetClientData(&this->Count);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    this->Tag = object->AddObserver(event, this->Command);
  }
  ~EventCounter()
  {
    if (this->Object)
    {
      this->Object->RemoveObserver(this->Tag);
    }
  }
  EventCounter(const EventCounter&) = delete;
  EventCounter& operator=(const EventCounter&) = delete;

  int Count = 0;

private:
  vtkWeakPointer<vtkObject> Object;
  unsigned long Tag = 0;
  vtkNew<vtkCallbackCommand> Command;
};
} // namespace testing
} // namespace meshlod

#endif
