#include "ShockFilterInternals.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributes.h"
#include "vtkShockAdvectionFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <type_traits>

namespace
{
struct CopyToDoubles
{
  template <typename ArrayT>
  void operator()(ArrayT* array, double* out, int threads) const
  {
    const auto values = vtk::DataArrayValueRange(array);
    shock::ParallelFor(values.size(), shock::ThreadsForWork(threads, values.size()), [&](std::int64_t begin, std::int64_t end) {
      std::copy(values.begin() + begin, values.begin() + end, out + begin);
    });
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
    if constexpr (sizeof(T) <= 4)
    {
      // Clamped first (rounding is monotone, and the limits are integers), then
      // rounded half away from zero as std::round does, without its library
      // call: the clamped value and its truncation fit an int64 exactly.
      const double clamped = std::min(std::max(v, low), high);
      const auto truncated = static_cast<std::int64_t>(clamped);
      const double rest = clamped - static_cast<double>(truncated);
      return static_cast<T>(truncated + (rest >= 0.5 ? 1 : 0) - (rest <= -0.5 ? 1 : 0));
    }
    else
    {
      const double rounded = std::round(v);
      return rounded <= low ? std::numeric_limits<T>::lowest()
                            : (rounded >= high ? std::numeric_limits<T>::max() : static_cast<T>(rounded));
    }
  }
  else
  {
    return static_cast<T>(v);
  }
}

/// RoundAndClamp to the value type `dataType`, as a double: for arrays seen
/// through the generic vtkDataArray interface, whose accessors take doubles.
double RoundAndClampTo(int dataType, double v)
{
  switch (dataType)
  {
    vtkTemplateMacro(return static_cast<double>(RoundAndClamp<VTK_TT>(v)));
    default:
      return v;
  }
}

/// RoundAndClamp for the values of ArrayT (by the array's real type for a
/// generic vtkDataArray).
template <typename ArrayT>
vtk::GetAPIType<ArrayT> RoundAndClampFor(ArrayT* array, double v)
{
  if constexpr (std::is_same<ArrayT, vtkDataArray>::value)
  {
    return RoundAndClampTo(array->GetDataType(), v);
  }
  else
  {
    return RoundAndClamp<vtk::GetAPIType<ArrayT>>(v);
  }
}

/// A new array of the prototype's type, name, components, component names and
/// number of tuples (values not set).
vtkSmartPointer<vtkDataArray> NewArrayLike(vtkDataArray* prototype, vtkIdType tuples = -1)
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
  out->SetNumberOfTuples(tuples >= 0 ? tuples : prototype->GetNumberOfTuples());
  return out;
}

/// Copies any array into float or double storage (the value types a kernel reads).
struct CopyTo
{
  template <typename ArrayT, typename OutT>
  void operator()(ArrayT* array, OutT* out, int threads) const
  {
    const auto values = vtk::DataArrayValueRange(array);
    shock::ParallelFor(values.size(), shock::ThreadsForWork(threads, values.size()),
      [&](std::int64_t begin, std::int64_t end) {
        for (std::int64_t i = begin; i < end; ++i)
        {
          out[i] = static_cast<OutT>(values[i]);
        }
      });
  }
};

/// Makes the writer of OutputForKernel for an array of a dispatchable type.
struct MakeWriter
{
  template <typename ArrayT>
  void operator()(ArrayT* array, shock::SampleWriter& writer) const
  {
    const int C = array->GetNumberOfComponents();
    if constexpr (std::is_same<ArrayT, vtkAOSDataArrayTemplate<unsigned char>>::value)
    {
      // Photographs: straight into the array's storage.
      unsigned char* values = array->GetPointer(0);
      writer = [values, C](std::int64_t first, std::int64_t count, const double* in) {
        shock::RoundAndClampBytes(in, count * C, values + first * C);
      };
      return;
    }
    writer = [array, C](std::int64_t first, std::int64_t count, const double* in) {
      auto values = vtk::DataArrayValueRange(array, first * C, (first + count) * C);
      std::int64_t i = 0;
      for (auto&& value : values)
      {
        value = RoundAndClampFor(array, in[i++]);
      }
    };
  }
};

struct CopyFromDoubles
{
  template <typename ArrayT>
  void operator()(ArrayT* array, const double* in, int threads) const
  {
    auto values = vtk::DataArrayValueRange(array);
    shock::ParallelFor(values.size(), shock::ThreadsForWork(threads, values.size()), [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t i = begin; i < end; ++i)
      {
        values[i] = RoundAndClampFor(array, in[i]);
      }
    });
  }
};

/// `out` holding `values` (CopyFromDoubles on `threads` threads; serial for arrays with unusual storage).
vtkSmartPointer<vtkDataArray> Convert(vtkSmartPointer<vtkDataArray> out, const double* values, int threads)
{
  CopyFromDoubles worker;
  if (!vtkArrayDispatch::Dispatch::Execute(out.Get(), worker, values, threads))
  {
    worker(out.Get(), values, 1); // see ToDoubles
  }
  return out;
}
}

namespace ShockFilterInternals
{
shock::AdvectionParameters MakeParameters(vtkShockAdvectionFilter* filter)
{
  shock::AdvectionParameters p;
  p.time = filter->GetFlowTime();
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
  std::vector<double> values(static_cast<size_t>(array->GetNumberOfValues()));
  ToDoubles(array, values.data(), 1);
  return values;
}

void ToDoubles(vtkDataArray* array, double* out, int threads)
{
  CopyToDoubles worker;
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker, out, threads))
  {
    // vtkDataArray fallback for unusual storage, whose generic accessors need not
    // be safe to call concurrently.
    worker(array, out, 1);
  }
}

vtkSmartPointer<vtkDataArray> FromDoubles(vtkDataArray* prototype, const std::vector<double>& values)
{
  return FromDoubles(prototype, values.data(), 1);
}

vtkSmartPointer<vtkDataArray> FromDoubles(
  vtkDataArray* prototype, const double* values, int threads)
{
  return Convert(NewArrayLike(prototype), values, threads);
}

vtkSmartPointer<vtkDataArray> FromDoubles(
  int dataType, int components, vtkIdType tuples, const double* values, int threads)
{
  auto out = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(dataType));
  out->SetNumberOfComponents(components);
  out->SetNumberOfTuples(tuples);
  return Convert(out, values, threads);
}

KernelSignal SignalForKernel(vtkDataArray* array, int threads)
{
  KernelSignal signal;
  if (auto* floats = vtkAOSDataArrayTemplate<float>::FastDownCast(array))
  {
    signal.floats = floats->GetPointer(0);
    return signal;
  }
  if (auto* doubles = vtkAOSDataArrayTemplate<double>::FastDownCast(array))
  {
    signal.doubles = doubles->GetPointer(0);
    return signal;
  }
  if (auto* bytes = vtkAOSDataArrayTemplate<unsigned char>::FastDownCast(array))
  {
    signal.bytes = bytes->GetPointer(0);
    return signal;
  }
  const vtkIdType count = array->GetNumberOfValues();
  CopyTo worker;
  switch (array->GetDataType())
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_FLOAT:
      signal.floatCopy = shock::AllocateLargeArray<float>(count);
      if (!vtkArrayDispatch::Dispatch::Execute(array, worker, signal.floatCopy.get(), threads))
      {
        worker(array, signal.floatCopy.get(), 1); // unusual storage: serial, as in ToDoubles
      }
      signal.floats = signal.floatCopy.get();
      break;
    default:
      signal.doubleCopy = shock::AllocateLargeArray<double>(count);
      ToDoubles(array, signal.doubleCopy.get(), threads);
      signal.doubles = signal.doubleCopy.get();
  }
  return signal;
}

KernelOutput OutputForKernel(vtkDataArray* prototype, vtkIdType tuples)
{
  KernelOutput output;
  output.array = NewArrayLike(prototype, tuples);
  MakeWriter maker;
  if (!vtkArrayDispatch::Dispatch::Execute(output.array.Get(), maker, output.writer))
  {
    // Unusual storage, whose generic accessors need not be safe to call
    // concurrently: one writer at a time.
    vtkDataArray* array = output.array;
    auto lock = std::make_shared<std::mutex>();
    shock::SampleWriter generic;
    maker(array, generic);
    output.writer = [lock, generic](std::int64_t first, std::int64_t count, const double* in) {
      const std::lock_guard<std::mutex> hold(*lock);
      generic(first, count, in);
    };
  }
  return output;
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
