#include "vtkOFFWriter.h"

#include "ShockOffFormat.h"

#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <string>

vtkStandardNewMacro(vtkOFFWriter);

vtkOFFWriter::vtkOFFWriter() = default;

vtkOFFWriter::~vtkOFFWriter()
{
  this->SetFileName(nullptr);
}

vtkPolyData* vtkOFFWriter::GetInput()
{
  return vtkPolyData::SafeDownCast(this->GetInputDataObject(0, 0));
}

int vtkOFFWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

void vtkOFFWriter::WriteData()
{
  vtkPolyData* input = this->GetInput();
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No file name: set FileName.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  std::string error;
  if (!input || !shockio::WriteOff(input, this->FileName, error))
  {
    vtkErrorMacro(<< (input ? error : std::string("No input polygonal data.")));
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkOFFWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
