#include "vtkOFFReader.h"

#include "ShockOffFormat.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <fstream>
#include <string>

vtkStandardNewMacro(vtkOFFReader);

vtkOFFReader::vtkOFFReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkOFFReader::~vtkOFFReader()
{
  this->SetFileName(nullptr);
}

int vtkOFFReader::CanReadFile(const char* fname)
{
  std::ifstream file(fname ? fname : "", std::ios::binary);
  std::string word;
  // The header may follow comments.
  while (file >> word && word[0] == '#')
  {
    std::getline(file, word);
  }
  // OFF, COFF, and the variants (NOFF, 4OFF, ...) that the reader refuses with a message.
  return file && word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0 ? 1 : 0;
}

int vtkOFFReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "No file name: set FileName.");
    return 0;
  }
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = shockio::ReadOff(this->FileName, error);
  if (!mesh)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UpdateProgress(1.0);
  output->ShallowCopy(mesh);
  return 1;
}

void vtkOFFReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
