// Images and measurements shared by the tests of vtkImageShockAdvectionFilter
// (TestImageShockAdvectionFilter.cxx, TestImageShockAdvectionErrors.cxx,
// TestImageShockAdvectionPDE.cxx). Each test file gets its own copy (an unnamed
// namespace).
#ifndef TestImageShockAdvection_h
#define TestImageShockAdvection_h

#include "vtkImageShockAdvectionFilter.h"

#include "vtkExtractVOI.h"
#include "vtkRTAnalyticSource.h"

#include "GridShockAdvection.h"
#include "GridShockPDE.h"
#include "TestFilterHelpers.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageEllipsoidSource.h"
#include "vtkImageGaussianSmooth.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using shock_test::MessageLog;
using shock_test::UpdateSucceeds;
using shock_test::Values;

/// A blurred multi-feature image: a bright disc, a dark square and a ramp.
double Feature(double x, double y)
{
  const double disc = std::hypot(x - 20.0, y - 18.0) < 9.0 ? 1.0 : 0.0;
  const double square = (x > 32 && x < 46 && y > 8 && y < 30) ? -0.25 : 0.0;
  return 0.3 + 0.5 * disc + square + 0.004 * x;
}

/// An image of nx x ny (x nz) samples with a blurred feature pattern in `array`.
vtkSmartPointer<vtkImageData> MakeImage(vtkDataArray* array, int nx = 56, int ny = 40, int nz = 1,
  int components = 1, double scale = 1.0, double offset = 0.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(0.5, 0.5, 0.5);
  image->SetOrigin(-3.0, 2.0, 1.0);
  array->SetName("Intensity");
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        // Box-blur the pattern so edges are ramps a few samples wide.
        double v = 0.0;
        for (int dj = -2; dj <= 2; ++dj)
        {
          for (int di = -2; di <= 2; ++di)
          {
            v += Feature(i + di, j + dj + 0.5 * k) / 25.0;
          }
        }
        for (int c = 0; c < components; ++c)
        {
          array->SetComponent((k * ny + j) * nx + i, c, offset + scale * (c == 1 ? 1.0 - v : v));
        }
      }
    }
  }
  image->GetPointData()->SetScalars(array);
  return image;
}

/// Mean squared forward difference along x: a sharpness measure.
double GradientEnergy(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  int dims[3];
  image->GetDimensions(dims);
  double sum = 0.0;
  for (vtkIdType s = 0; s + 1 < a->GetNumberOfTuples(); ++s)
  {
    if ((s + 1) % dims[0] != 0)
    {
      const double d = a->GetComponent(s + 1, 0) - a->GetComponent(s, 0);
      sum += d * d;
    }
  }
  return sum / static_cast<double>(a->GetNumberOfTuples());
}

vtkSmartPointer<vtkImageData> FilterImage(vtkImageData* input, double time, int threads = 0)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  filter->SetNumberOfThreads(threads);
  filter->Update();
  return filter->GetOutput();
}

} // namespace

#endif
