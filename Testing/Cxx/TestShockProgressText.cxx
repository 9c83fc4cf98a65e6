// The progress text each filter gives ParaView's progress bar: the phase it is in.
#include "vtkImageShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace
{

/// The distinct progress texts of one Update of `algorithm`, in the order they came.
std::vector<std::string> ProgressTexts(vtkAlgorithm* algorithm)
{
  std::vector<std::string> texts;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&texts);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void*) {
    auto* seen = static_cast<std::vector<std::string>*>(client);
    const char* text = static_cast<vtkAlgorithm*>(caller)->GetProgressText();
    if (text && (seen->empty() || seen->back() != text))
    {
      seen->push_back(text);
    }
  });
  // Removed after the update: the algorithm keeps the command, whose client data is `texts`.
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ProgressEvent, onProgress);
  algorithm->Update();
  algorithm->RemoveObserver(tag);
  return texts;
}

TEST(ShockProgressText, EachFilterNamesItsPhases)
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 127, 0, 127, 0, 0);
  vtkNew<vtkImageShockAdvectionFilter> image;
  image->SetInputConnection(wavelet->GetOutputPort());
  image->SetFlowTime(256.0);
  EXPECT_EQ(ProgressTexts(image), std::vector<std::string>{ "tracing the flow lines" });

  image->SetDomainToGradients();
  EXPECT_EQ(ProgressTexts(image),
    (std::vector<std::string>{ "tracing the flow lines", "integrating the advected gradients" }));

  image->SetDomainToValues();
  image->SetMethodToPDE();
  image->SetFlowTime(4.0);
  EXPECT_EQ(ProgressTexts(image), std::vector<std::string>{ "integrating the shock PDE" });

  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(64);
  vtkNew<vtkPolyDataShockSharpenFilter> sharpen;
  sharpen->SetInputConnection(sphere->GetOutputPort());
  sharpen->SetFlowTime(256.0);
  EXPECT_EQ(ProgressTexts(sharpen),
    (std::vector<std::string>{ "advecting the face normals", "fitting the positions to the normals" }));
}

} // namespace
