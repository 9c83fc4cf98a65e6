// The shock filter on plain arrays, without VTK: a blurred edge in a 2D image
// becomes a sharp one. Link the kernels (ShockKernels); see Examples/CMakeLists.txt.
//
// Run: build/bin/ShockKernelExample   (prints the steepest step before and after)
#include "GridShockAdvection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

int main()
{
  // A 64 x 48 image whose left half is dark and right half bright, blurred
  // across about 6 pixels (a smooth ramp from x = 26 to x = 38).
  shock::GridShape shape;
  shape.dimensions = { 64, 48, 1 };
  const int width = shape.dimensions[0];
  std::vector<double> image(static_cast<size_t>(shape.NumberOfSamples()));
  for (int y = 0; y < shape.dimensions[1]; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      image[static_cast<size_t>(y * width + x)] = 0.5 + 0.5 * std::tanh((x - 31.5) / 3.0);
    }
  }

  // The paper's fixed flow for a flow time of 4096 (normalised units).
  shock::AdvectionParameters parameters;
  parameters.time = 4096;
  std::vector<double> sharpened(image.size());
  const shock::Status status =
    shock::AdvectGridSignal(shape, 1, image.data(), sharpened.data(), parameters);
  if (!status.Ok())
  {
    std::fprintf(stderr, "shock filter failed: %s\n", status.error.c_str());
    return 1;
  }

  // The steepest step between neighbours along one row, before and after.
  auto steepest = [width](const std::vector<double>& v)
  {
    double step = 0;
    for (int x = 0; x + 1 < width; ++x)
    {
      step = std::max(step, std::fabs(v[static_cast<size_t>(x + 1)] - v[static_cast<size_t>(x)]));
    }
    return step;
  };
  const auto [low, high] = std::minmax_element(sharpened.begin(), sharpened.end());
  std::printf("steepest step before %.3f, after %.3f; values in [%.3f, %.3f]\n", steepest(image),
    steepest(sharpened), *low, *high);
  // A shock filter sharpens without overshoot: the step is steeper, the range kept.
  const bool sharper = steepest(sharpened) > 2 * steepest(image);
  const bool inRange = *low >= 0.0 && *high <= 1.0;
  return sharper && inRange ? 0 : 1;
}
