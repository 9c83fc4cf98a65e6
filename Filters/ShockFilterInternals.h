/**
 * @file ShockFilterInternals.h
 * @brief Private glue between the vtkShock* filters and the VTK-free kernels.
 *
 * Not installed: the kernels' types stay out of the module's public headers.
 */
#ifndef ShockFilterInternals_h
#define ShockFilterInternals_h

#include "GridShockAdvection.h"
#include "ShockTypes.h"
#include "vtkSmartPointer.h"

#include <vector>

class vtkDataArray;
class vtkDataSetAttributes;
class vtkShockAdvectionFilter;

namespace ShockFilterInternals
{
/// The filter's parameters in the kernels' form.
shock::AdvectionParameters MakeParameters(vtkShockAdvectionFilter* filter);

/// All tuples of a numeric array as interleaved doubles (any value type, any storage).
std::vector<double> ToDoubles(vtkDataArray* array);

/**
 * ToDoubles into `out`, which has room for array->GetNumberOfValues() doubles,
 * converted on `threads` OpenMP threads (<= 0: all cores); serial for arrays
 * with unusual storage.
 */
void ToDoubles(vtkDataArray* array, double* out, int threads);

/**
 * A new array like `prototype` (same value type, name, components and
 * component names) holding `values`. Integer types are rounded and clamped to
 * the type's range; NaN becomes 0 for integer types (it cannot occur there).
 */
vtkSmartPointer<vtkDataArray> FromDoubles(vtkDataArray* prototype, const std::vector<double>& values);

/**
 * FromDoubles reading prototype->GetNumberOfValues() doubles from `values`,
 * converted on `threads` OpenMP threads (<= 0: all cores); serial for arrays
 * with unusual storage.
 */
vtkSmartPointer<vtkDataArray> FromDoubles(
  vtkDataArray* prototype, const double* values, int threads);

/// FromDoubles into a new unnamed array of VTK type `dataType` with `tuples` tuples of `components`.
vtkSmartPointer<vtkDataArray> FromDoubles(
  int dataType, int components, vtkIdType tuples, const double* values, int threads);

/**
 * The values a grid kernel reads, as float, double or unsigned 8-bit (exactly
 * one pointer is set): the array's own storage when it is a contiguous array of
 * one of these types (no copy), else a copy converted on `threads` threads:
 * float for the other 8- and 16-bit integer types (exact), double for the others.
 */
struct KernelSignal
{
  const float* floats = nullptr;
  const double* doubles = nullptr;
  const unsigned char* bytes = nullptr;
  shock::LargeArray<float> floatCopy;
  shock::LargeArray<double> doubleCopy;
};
KernelSignal SignalForKernel(vtkDataArray* array, int threads);

/**
 * A new array like `prototype` (as FromDoubles makes it), and a writer of a
 * grid kernel's results into it with FromDoubles' rounding and clamping, safe
 * to call from several threads for disjoint runs of tuples.
 */
struct KernelOutput
{
  vtkSmartPointer<vtkDataArray> array;
  shock::SampleWriter writer;
};
/// `tuples`: the new array's tuple count (-1: the prototype's).
KernelOutput OutputForKernel(vtkDataArray* prototype, vtkIdType tuples = -1);

/**
 * Replace `original` by `replacement` in `attributes`, keeping its attribute
 * role (active scalars, ...) and, for named arrays, its position.
 */
void ReplaceArray(vtkDataSetAttributes* attributes, vtkDataArray* original, vtkDataArray* replacement);
}

#endif
