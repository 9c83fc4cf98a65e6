// Helpers shared by the VTK filter tests (header-only, test code only).
#ifndef TestFilterHelpers_h
#define TestFilterHelpers_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <string>
#include <vector>

namespace shock_test
{

/// Records the error and warning messages an object emits.
class MessageLog
{
public:
  explicit MessageLog(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
      auto* self = static_cast<MessageLog*>(client);
      (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings) +=
        std::string(static_cast<const char*>(data)) + "\n";
    });
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
  std::string Errors, Warnings;

private:
  vtkNew<vtkCallbackCommand> Callback;
};

/// All values of a numeric array, interleaved, as doubles (none for a null array).
inline std::vector<double> Values(vtkDataArray* array)
{
  if (!array)
  {
    return {};
  }
  std::vector<double> v(static_cast<size_t>(array->GetNumberOfValues()));
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    v[static_cast<size_t>(i)] = array->GetComponent(i / array->GetNumberOfComponents(),
      static_cast<int>(i % array->GetNumberOfComponents()));
  }
  return v;
}

/// Runs the algorithm and returns whether the pipeline update succeeded.
inline bool UpdateSucceeds(vtkAlgorithm* algorithm)
{
  return algorithm->GetExecutive()->Update() != 0;
}

} // namespace shock_test

#endif
