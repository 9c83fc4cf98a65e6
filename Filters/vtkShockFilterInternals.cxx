#include "vtkShockFilterInternals.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributes.h"
#include "vtkShockAdvectionFilter.h"

#include <cmath>
#include <limits>
#include <type_traits>

namespace
{
struct CopyToDoubles
{
  template <typename ArrayT>
  void operator()(ArrayT* array, std::vector<double>& out) const
  {
    const auto values = vtk::DataArrayValueRange(array);
    out.assign(values.begin(), values.end());
  }
};

template <typename T>
T RoundAndClamp(double v)
{
  if constexpr (std::is_integral<T>::value)
  {
    if (std::isnan(v))
    {
      return T(0);
    }
    const double low = static_cast<double>(std::numeric_limits<T>::lowest());
    const double high = static_cast<double>(std::numeric_limits<T>::max());
    const double rounded = std::round(v);
    return rounded <= low ? std::numeric_limits<T>::lowest()
                          : (rounded >= high ? std::numeric_limits<T>::max() : static_cast<T>(rounded));
  }
  else
  {
    return static_cast<T>(v);
  }
}

struct CopyFromDoubles
{
  template <typename ArrayT>
  void operator()(ArrayT* array, const std::vector<double>& in) const
  {
    using ValueT = vtk::GetAPIType<ArrayT>;
    auto values = vtk::DataArrayValueRange(array);
    auto source = in.begin();
    for (auto&& v : values)
    {
      v = RoundAndClamp<ValueT>(*source++);
    }
  }
};
}

namespace vtkShockFilterInternals
{
shock::AdvectionParameters MakeParameters(vtkShockAdvectionFilter* filter)
{
  shock::AdvectionParameters p;
  p.time = filter->GetTimeStep();
  p.smoothingPasses = filter->GetSmoothingPasses();
  p.stepFraction = filter->GetStepFraction();
  p.flowMode = static_cast<shock::FlowMode>(filter->GetFlowMode());
  p.flowUpdates = filter->GetNumberOfFlowUpdates();
  p.sampling = static_cast<shock::Sampling>(filter->GetSampling());
  p.tracing = static_cast<shock::Tracing>(filter->GetTracingMode());
  p.numberOfThreads = filter->GetNumberOfThreads();
  p.valueScale = filter->GetParallelValueScale();
  return p;
}

std::vector<double> ToDoubles(vtkDataArray* array)
{
  std::vector<double> values;
  CopyToDoubles worker;
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker, values))
  {
    worker(array, values); // vtkDataArray fallback for unusual storage
  }
  return values;
}

vtkSmartPointer<vtkDataArray> FromDoubles(vtkDataArray* prototype, const std::vector<double>& values)
{
  vtkSmartPointer<vtkDataArray> out = vtk::TakeSmartPointer(prototype->NewInstance());
  out->SetName(prototype->GetName());
  out->SetNumberOfComponents(prototype->GetNumberOfComponents());
  for (int c = 0; c < prototype->GetNumberOfComponents(); ++c)
  {
    if (const char* name = prototype->GetComponentName(c))
    {
      out->SetComponentName(c, name);
    }
  }
  out->SetNumberOfTuples(prototype->GetNumberOfTuples());
  CopyFromDoubles worker;
  if (!vtkArrayDispatch::Dispatch::Execute(out.Get(), worker, values))
  {
    worker(out.Get(), values);
  }
  return out;
}

void ReplaceArray(vtkDataSetAttributes* attributes, vtkDataArray* original, vtkDataArray* replacement)
{
  int index = -1;
  for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
  {
    if (attributes->GetAbstractArray(i) == original)
    {
      index = i;
    }
  }
  if (index >= 0 && original->GetName())
  {
    attributes->AddArray(replacement); // same name: replaced in place, roles kept
    return;
  }
  const int role = index >= 0 ? attributes->IsArrayAnAttribute(index) : -1;
  if (index >= 0)
  {
    attributes->RemoveArray(index);
  }
  const int added = attributes->AddArray(replacement);
  if (role >= 0)
  {
    attributes->SetActiveAttribute(added, role);
  }
}
}
