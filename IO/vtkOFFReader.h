/**
 * @class   vtkOFFReader
 * @brief   Reads an Object File Format (OFF or COFF, text) file as polygonal data.
 *
 * The format is described in ShockOffFormat.h: vertices with optional RGB(A)
 * colours, polygons of 3 or more vertices with optional colours, comments and
 * blank lines. Colours become the unsigned-char active scalars "Colors" (point
 * data) and "FaceColors" (cell data). A malformed file gives one error naming
 * the file and the line, and an empty output.
 *
 * @sa vtkOFFWriter vtkPLYReader
 */
#ifndef vtkOFFReader_h
#define vtkOFFReader_h

#include "vtkIOShockModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class VTKIOSHOCK_EXPORT vtkOFFReader : public vtkPolyDataAlgorithm
{
public:
  static vtkOFFReader* New();
  vtkTypeMacro(vtkOFFReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// Whether `fname` starts like an OFF file (an OFF or COFF header), for reader factories.
  static int CanReadFile(const char* fname);

protected:
  vtkOFFReader();
  ~vtkOFFReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

private:
  vtkOFFReader(const vtkOFFReader&) = delete;
  void operator=(const vtkOFFReader&) = delete;
};

#endif
