// Sharpens a blurred step with vtkImageShockAdvectionFilter from an
// installed ShockFilters; prints the steepest jump before and after.
#include <vtkImageData.h>
#include <vtkImageShockAdvectionFilter.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <cmath>
#include <cstdio>

namespace
{
double SteepestJump(vtkImageData* image, int width)
{
  auto* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  double steepest = 0.0;
  for (int i = 0; i + 1 < width; ++i)
  {
    steepest = std::fmax(steepest, std::fabs(values->GetValue(i + 1) - values->GetValue(i)));
  }
  return steepest;
}
}

int main()
{
  const int width = 64;
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, 4, 1);
  vtkNew<vtkFloatArray> ramp;
  ramp->SetName("Step");
  ramp->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    const int x = static_cast<int>(id % width);
    ramp->SetValue(id, static_cast<float>(std::tanh((x - 31.5) / 3.0)));
  }
  image->GetPointData()->SetScalars(ramp);

  vtkNew<vtkImageShockAdvectionFilter> shock;
  shock->SetInputData(image);
  shock->SetFlowTime(1024.0);
  shock->Update();
  vtkImageData* sharp = shock->GetOutput();
  if (sharp->GetNumberOfPoints() != image->GetNumberOfPoints())
  {
    std::printf("no output\n");
    return 1;
  }
  const double before = SteepestJump(image, width);
  const double after = SteepestJump(sharp, width);
  std::printf("steepest jump %.3f before, %.3f after\n", before, after);
  return after > 1.5 * before ? 0 : 1;
}
