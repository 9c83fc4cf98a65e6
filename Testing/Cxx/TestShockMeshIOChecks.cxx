// The IO library's defences on mesh files: the OFF reader and writer as VTK
// algorithms, the same rules in every format (faces of 3 or more vertices,
// finite coordinates), declared counts checked before VTK allocates them, and
// outputs that replace their target only when complete.
#include "IOTestSupport.h"
#include "ShockMeshIO.h"
#include "TestMeshesVTK.h"
#include "vtkOFFReader.h"
#include "vtkOFFWriter.h"

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <string>
#include <vector>

namespace
{
using shocktest::FileBytes;
using shocktest::TempPath;
using shocktest::TextFile;

/// Counts the error events of an object and keeps the first message.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Count++ == 0)
    {
      this->First = static_cast<const char*>(data);
    }
  }
  int Count = 0;
  std::string First;
};

/// Expects ReadMesh(path) to fail with one line naming the file and containing `expected`.
void ExpectRefused(const std::string& path, const std::string& expected)
{
  std::string error;
  EXPECT_EQ(shockio::ReadMesh(path, error), nullptr) << path;
  EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
  EXPECT_NE(error.find(expected), std::string::npos) << "error: " << error << "\nexpected: " << expected;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

/// A sphere with RGB point colours made from the positions.
vtkSmartPointer<vtkPolyData> ColouredSphere()
{
  vtkSmartPointer<vtkPolyData> sphere = shocktest::ToPolyData(shocktest::Icosphere(2));
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName(shockio::PointColorsName);
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(sphere->GetNumberOfPoints());
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      colours->SetTypedComponent(p, c, static_cast<unsigned char>(128 + 120 * sphere->GetPoint(p)[c]));
    }
  }
  sphere->GetPointData()->SetScalars(colours);
  return sphere;
}

TEST(ShockMeshIOChecks, OffReaderAndWriterArePipelineAlgorithms)
{
  const vtkSmartPointer<vtkPolyData> sphere = ColouredSphere();
  const std::string path = TempPath("sphere.off");
  vtkNew<vtkOFFWriter> writer;
  writer->SetInputData(sphere);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_EQ(FileBytes(path).rfind("COFF\n", 0), 0u);
  EXPECT_EQ(vtkOFFReader::CanReadFile(path.c_str()), 1);
  EXPECT_EQ(vtkOFFReader::CanReadFile(TextFile("not.off", "ply\n").c_str()), 0);

  vtkNew<vtkOFFReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* read = reader->GetOutput();
  ASSERT_EQ(read->GetNumberOfPoints(), sphere->GetNumberOfPoints());
  ASSERT_EQ(read->GetNumberOfPolys(), sphere->GetNumberOfPolys());
  for (vtkIdType p = 0; p < sphere->GetNumberOfPoints(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(read->GetPoint(p)[c], sphere->GetPoint(p)[c]); // the shortest exact text
    }
  }
  auto* colours = vtkUnsignedCharArray::SafeDownCast(read->GetPointData()->GetScalars());
  ASSERT_NE(colours, nullptr);
  auto* expected = vtkUnsignedCharArray::SafeDownCast(sphere->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < expected->GetNumberOfValues(); ++i)
  {
    ASSERT_EQ(colours->GetValue(i), expected->GetValue(i));
  }
}

TEST(ShockMeshIOChecks, OffReaderReportsMalformedFilesAsOneVtkError)
{
  const std::string path = TextFile("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  vtkNew<vtkOFFReader> reader;
  vtkNew<ErrorCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->First.find("line 6: face 0: vertex id '9' is not an integer in 0..2"), std::string::npos)
    << errors->First;
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(ShockMeshIOChecks, FacesOfFewerThanThreeVerticesAreRefusedInEveryFaceFormat)
{
  const std::string points = "0 0 0\n1 0 0\n0 1 0\n";
  const std::string plyHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  for (const std::string face : { "0", "1 0", "2 0 1" })
  {
    const std::string off = TextFile("face.off", "OFF\n3 2 0\n" + points + "3 0 1 2\n" + face + "\n");
    ExpectRefused(off, "vertices; a face has at least 3");
    const std::string ply = TextFile("face.ply", plyHeader + points + "3 0 1 2\n" + face + "\n");
    ExpectRefused(ply, "vertices; a face has at least 3");
  }
}

TEST(ShockMeshIOChecks, NonFiniteCoordinatesAreRefusedInEveryTextFormat)
{
  for (const std::string value : { "nan", "inf", "-inf", "1e999" })
  {
    ExpectRefused(TextFile("v.off", "OFF\n3 1 0\n" + value + " 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
      "is not a finite number");
    ExpectRefused(TextFile("v.obj", "v " + value + " 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "is not a finite number");
    ExpectRefused(TextFile("v.ply",
                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                      value + " 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
      "is not a finite number");
  }
  // A valid OBJ file reads: the check refuses only what VTK would misread.
  std::string error;
  EXPECT_TRUE(shockio::ReadMesh(TextFile("ok.obj", "v 1e-3 +2 -3.5E2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), error)) << error;
}

TEST(ShockMeshIOChecks, DeclaredCountsBeyondTheLimitOrTheFileAreRefusedBeforeReading)
{
  const std::string vtp = TextFile("huge.vtp",
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">\n<PolyData>\n"
    "<Piece NumberOfPoints=\"2000000000\" NumberOfPolys=\"0\">\n<Points><DataArray type=\"Float64\" "
    "NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray></Points>\n</Piece>\n</PolyData>\n</VTKFile>\n");
  ExpectRefused(vtp, "more than the limit of 100000000 samples");
  const std::string legacy = TextFile("huge.vtk",
    "# vtk DataFile Version 3.0\nm\nASCII\nDATASET POLYDATA\nPOINTS 2000000 double\n0 0 0\n");
  ExpectRefused(legacy, "declares 2000000 points in a file of");
  // Within the limit and the file, the same files are read.
  const std::string small = TextFile("small.vtk",
    "# vtk DataFile Version 3.0\nm\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n0 0 0 1 0 0 0 1 0\n"
    "POLYGONS 1 4\n3 0 1 2\n");
  std::string error;
  EXPECT_TRUE(shockio::ReadMesh(small, error)) << error;
  EXPECT_EQ(shockio::ReadMesh(small, error, 2), nullptr);
  EXPECT_NE(error.find("declares 3 points, more than the limit of 2 samples"), std::string::npos) << error;
}

TEST(ShockMeshIOChecks, AFailedWriteLeavesTheTargetUntouched)
{
  const vtkSmartPointer<vtkPolyData> sphere = ColouredSphere();
  const char* const formats[] = { "ply", "obj", "stl", "vtp", "vtk", "off" };
  for (const char* format : formats)
  {
    const std::string path = TempPath(std::string("target.") + format);
    const std::string before = "the existing file, which must survive\n";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << before;
    std::string error;
    bool written = true;
    {
      shocktest::FileSizeLimit fullDisk(256);
      written = shockio::WriteMesh(sphere, path, error);
    }
    EXPECT_FALSE(written) << format;
    EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(FileBytes(path), before) << format;
    EXPECT_TRUE(shocktest::PartialFiles(path).empty()) << format;
    // Without the limit the same write replaces the file.
    EXPECT_TRUE(shockio::WriteMesh(sphere, path, error)) << error;
    EXPECT_NE(FileBytes(path), before) << format;
  }
}

TEST(ShockMeshIOChecks, OutputsReplaceRegularFilesOnly)
{
  // A named pipe (like a device such as /dev/full) cannot be replaced by a complete file.
  const std::string fifo = TempPath("pipe.off");
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string error;
  EXPECT_FALSE(shockio::WriteMesh(ColouredSphere(), fifo, error));
  EXPECT_NE(error.find("it is not a regular file"), std::string::npos) << error;
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  std::filesystem::remove(fifo);
}

} // namespace
