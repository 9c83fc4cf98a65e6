/**
 * @file GridChecks.h
 * @brief The checks every grid kernel's entry point makes first (the shape,
 * the buffers, the parameters), and the flow fields of a signal without flow.
 */
#ifndef GridChecks_h
#define GridChecks_h

#include "GridLayered.h"
#include "GridShape.h"
#include "ShockTypes.h"

#include <cmath>
#include <cstdint>
#include <string>

namespace shock
{
namespace grid
{

/// The checks of the grid shape and the number of components; an empty Status when valid.
inline Status CheckGridShape(const GridShape& shape, int components)
{
  for (int a = 0; a < 3; ++a)
  {
    if (shape.dimensions[a] < 1)
    {
      return { "grid dimensions must be >= 1" };
    }
    // A flat axis (one sample) has no edges: its spacing plays no part.
    if (shape.dimensions[a] > 1 && (!(shape.spacing[a] > 0.0) || !std::isfinite(shape.spacing[a])))
    {
      return { "the grid spacing along axis " + std::to_string(a) + " (" + std::to_string(shape.spacing[a]) +
        ") must be finite and > 0" };
    }
    if (shape.wholeDimensions[a] != 0 && shape.wholeDimensions[a] < shape.dimensions[a])
    {
      return { "the whole grid's samples along axis " + std::to_string(a) + " (" +
        std::to_string(shape.wholeDimensions[a]) + ") must be 0 or at least the grid's " +
        std::to_string(shape.dimensions[a]) };
    }
  }
  if (components < 1)
  {
    return { "the signal needs at least one component" };
  }
  return {};
}

/// The checks every grid run makes first: the shape, the buffers, the parameters.
template <typename T>
Status CheckGridRun(const GridShape& shape, int components, const T* input,
  const SampleWriter& output, const AdvectionParameters& parameters)
{
  const Status arguments = CheckGridShape(shape, components);
  if (!arguments.Ok())
  {
    return arguments;
  }
  if (!input || !output)
  {
    return { "input and output must be distinct, non-null buffers" };
  }
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t first = parameters.writtenSamples[2 * a];
    const std::int64_t last = parameters.writtenSamples[2 * a + 1];
    if (first <= last && (first < 0 || last >= shape.dimensions[a]))
    {
      return { "the written samples along axis " + std::to_string(a) + " (" + std::to_string(first) + " to " +
        std::to_string(last) + ") must lie in the grid's " + std::to_string(shape.dimensions[a]) + " samples" };
    }
  }
  return CheckAdvectionParameters(parameters);
}

/// CheckGridRun for a layered signal (its arrays are checked by AdvectLayered).
template <typename T>
Status CheckGridRun(const GridShape& shape, int components, const LayeredValues<T>& input,
  const SampleWriter& output, const AdvectionParameters& parameters)
{
  return CheckGridRun(shape, components, input.piece, output, parameters);
}

/// The argument checks shared by the grid kernels' entry points; an empty Status when valid.
inline Status CheckGridArguments(
  const GridShape& shape, int components, const double* input, const double* output)
{
  const Status checked = CheckGridShape(shape, components);
  if (!checked.Ok())
  {
    return checked;
  }
  if (!input || !output || input == output)
  {
    return { "input and output must be distinct, non-null buffers" };
  }
  return {};
}

/// Flow fields of a signal without flow (constant, or no faces): zero potential and flow.
inline void ZeroFlowFields(std::int64_t samples, std::int64_t faces, GridFlowFields& fields)
{
  fields.potential.assign(static_cast<size_t>(samples), 0.0);
  fields.flow.assign(static_cast<size_t>(faces * 3), 0.0);
}
} // namespace grid
} // namespace shock

#endif
