/**
 * @class   vtkOFFWriter
 * @brief   Writes polygonal data as an Object File Format (OFF or COFF, text) file.
 *
 * Writes the polygons of its input (triangle strips as triangles; vertex and
 * line cells are dropped), with COFF vertex colours when the active point
 * scalars (else the point array "Colors") are unsigned-char RGB or RGBA, and
 * face colours likewise from the cell data ("FaceColors"). Coordinates are
 * written in the shortest text that reads back exactly. The file is written
 * to a temporary file beside it and renamed over it only when complete: a
 * failed write (a full disk) leaves an existing file untouched.
 *
 * @sa vtkOFFReader vtkPLYWriter
 */
#ifndef vtkOFFWriter_h
#define vtkOFFWriter_h

#include "vtkIOShockModule.h" // For export macro
#include "vtkWriter.h"

class vtkPolyData;

class VTKIOSHOCK_EXPORT vtkOFFWriter : public vtkWriter
{
public:
  static vtkOFFWriter* New();
  vtkTypeMacro(vtkOFFWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to write.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// The input polygonal data.
  vtkPolyData* GetInput();

protected:
  vtkOFFWriter();
  ~vtkOFFWriter() override;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  char* FileName = nullptr;

private:
  vtkOFFWriter(const vtkOFFWriter&) = delete;
  void operator=(const vtkOFFWriter&) = delete;
};

#endif
