#include "ShockTypes.h"

#include <cmath>

namespace shock
{

Status CheckAdvectionParameters(const AdvectionParameters& parameters)
{
  if (!(parameters.time >= 0.0) || !std::isfinite(parameters.time))
  {
    return { "the flow time must be finite and >= 0" };
  }
  if (parameters.smoothingPasses < 0)
  {
    return { "the number of smoothing passes must be >= 0" };
  }
  if (!(parameters.stepFraction > 0.0) || parameters.stepFraction > 1.0)
  {
    return { "the step fraction must be in (0, 1]" };
  }
  if (parameters.flowUpdates < 1)
  {
    return { "the number of flow updates must be >= 1" };
  }
  if (parameters.hierarchyLevels < 1)
  {
    return { "the number of hierarchy levels must be >= 1" };
  }
  if (!(parameters.valueScale >= 0.0) || !std::isfinite(parameters.valueScale))
  {
    return { "the value scale must be finite and >= 0" };
  }
  return {};
}

} // namespace shock
