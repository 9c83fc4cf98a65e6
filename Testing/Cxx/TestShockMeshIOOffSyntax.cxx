// Tests of the OFF reader of shockfilter (ShockMeshIO.h): comments, blank lines,
// polygons of any size, counts on their own line, COFF colours as integers or
// reals, and the one-line errors of malformed OFF files (the other tests of
// ShockMeshIO.h: TestShockMeshIO.cxx, TestShockMeshIOErrors.cxx).
#include "TestShockMeshIO.h"

namespace
{

// --- The OFF syntax -------------------------------------------------------------------

TEST(ShockMeshIO, OffReadsCommentsBlankLinesAndPolygonsOfAnySize)
{
  const std::string path = TextFile("syntax.off",
    "# a comment before the header\n"
    "\n"
    "OFF 5 3 0   # counts on the header line\r\n"
    "0 0 0\n"
    "\t1 0 0\n"
    "# a comment between the vertices\n"
    "1 1 0\n"
    "0 1 0\n"
    "+0.5 1.5e0 -0\n"
    "\n"
    "4 0 1 2 3\n"
    "3 3 2 4 # a comment after a face\n"
    "5  0 1 2 4 3\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPoints(), 5);
  EXPECT_EQ(mesh->GetPoint(4)[1], 1.5);
  const auto polygons = PolygonCorners(mesh);
  ASSERT_EQ(polygons.size(), 3u);
  EXPECT_EQ(polygons[0].size(), 4u);
  EXPECT_EQ(polygons[1].size(), 3u);
  EXPECT_EQ(polygons[2].size(), 5u);
  EXPECT_EQ(
    mesh->GetPointData()->GetNumberOfArrays() + mesh->GetCellData()->GetNumberOfArrays(), 0);
}

TEST(ShockMeshIO, OffReadsCountsOnTheirOwnLineWithoutEdgeCount)
{
  const std::string path =
    TextFile("counts.off", "OFF\n# comment\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(path, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPolys(), 1);
}

TEST(ShockMeshIO, CoffReadsIntegerAndRealColors)
{
  const std::string integers = TextFile("integers.off",
    "COFF\n3 1 3\n0 0 0 255 0 0\n1 0 0 0 128 0\n0 1 0 0 0 1\n3 0 1 2 10 20 30 40\n");
  const std::string reals = TextFile("reals.off",
    "COFF\n3 1 3\n0 0 0 1.0 0 0 1\n1 0 0 0 0.5 0 1\n0 1 0 0 0 1 0.0\n3 0 1 2 1 0.2e0 0\n");
  std::string error;
  const vtkSmartPointer<vtkPolyData> a = shockio::ReadMesh(integers, error);
  ASSERT_TRUE(a) << error;
  const auto* pointColors = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  ASSERT_NE(pointColors, nullptr);
  EXPECT_EQ(pointColors->GetNumberOfComponents(), 3);
  EXPECT_EQ(pointColors->GetValue(0), 255);
  EXPECT_EQ(pointColors->GetValue(4), 128);
  EXPECT_EQ(pointColors->GetValue(8), 1); // integers are 0..255 values
  const auto* faceColors =
    vtkUnsignedCharArray::SafeDownCast(a->GetCellData()->GetArray(shockio::FaceColorsName));
  ASSERT_NE(faceColors, nullptr);
  EXPECT_EQ(faceColors->GetNumberOfComponents(), 4);
  EXPECT_EQ(faceColors->GetValue(3), 40);

  // One real makes every colour value of the file a 0..1 real.
  const vtkSmartPointer<vtkPolyData> b = shockio::ReadMesh(reals, error);
  ASSERT_TRUE(b) << error;
  const auto* realColors =
    vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetArray(shockio::PointColorsName));
  ASSERT_NE(realColors, nullptr);
  EXPECT_EQ(realColors->GetNumberOfComponents(), 4);
  EXPECT_EQ(realColors->GetValue(0), 255);
  EXPECT_EQ(realColors->GetValue(5), 128); // 0.5 * 255 rounded
  EXPECT_EQ(realColors->GetValue(10), 255);
  EXPECT_EQ(realColors->GetValue(11), 0);
  const auto* realFaces =
    vtkUnsignedCharArray::SafeDownCast(b->GetCellData()->GetArray(shockio::FaceColorsName));
  ASSERT_NE(realFaces, nullptr);
  EXPECT_EQ(realFaces->GetValue(0), 255);
  EXPECT_EQ(realFaces->GetValue(1), 51);
}

TEST(ShockMeshIO, MalformedOffFilesGiveErrors)
{
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
    { "# only a comment\n\n", "no OFF header" },
    { "PLY\n3 1 0\n" + triangle + "3 0 1 2\n", "not an OFF file" },
    { "NOFF\n3 1 0\n", "unsupported OFF variant 'NOFF'" },
    { "OFF BINARY\n", "binary OFF files are not supported" },
    { "OFF\n", "the file ends before the counts" },
    { "OFF\n3\n" + triangle, "line 2: expected the counts" },
    { "OFF\n3 1 0 7\n" + triangle, "line 2: expected the counts" },
    { "OFF\n-3 1 0\n", "expected the counts" }, { "OFF\nthree 1 0\n", "expected the counts" },
    { "OFF\n4 1 0\n" + triangle, "ends after 3 of its 4 vertices" },
    { "OFF\n3 2 0\n" + triangle + "3 0 1 2\n", "ends after 1 of its 2 faces" },
    { "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 3: vertex 0: 2 values" },
    { "OFF\n3 1 0\n0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "vertex 0: 4 values" },
    { "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",
      "line 4: vertex 1: coordinate 'x' is not a finite number" },
    { "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "coordinate 'nan' is not a finite number" },
    { "OFF\n3 1 0\n0 0 0\n1 1e999 0\n0 1 0\n3 0 1 2\n",
      "coordinate '1e999' is not a finite number" },
    { "OFF\n3 1 0\n" + triangle + "2 0 1\n", "face 0: 2 vertices; a face has at least 3" },
    { "OFF\n3 1 0\n" + triangle + "4 0 1 2\n", "face 0: announces 4 vertex ids but lists 3" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 3\n", "vertex id '3' is not an integer in 0..2" },
    { "OFF\n3 1 0\n" + triangle + "3 0 -1 2\n", "vertex id '-1' is not an integer in 0..2" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1.0 2\n", "vertex id '1.0' is not an integer" },
    { "OFF\n3 1 0\n" + triangle + "x 0 1 2\n",
      "the vertex count 'x' is not a non-negative integer" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 5\n", "colour-map indices are not supported" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 5 5\n", "2 colour values" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 1 2 3 4 5\n", "5 colour values" },
    { "OFF\n3 2 0\n" + triangle + "3 0 1 2 1 2 3\n3 0 1 2\n",
      "face 1: 0 colour values, but the first one has 3" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2 1 2 red\n", "colour value 'red' is not a number" },
    { "OFF\n3 1 0\n" + triangle + "3 0 1 2\n3 0 1 2\n",
      "line 7: more data after the last of the 1 faces" },
    { "COFF\n3 1 0\n" + triangle + "3 0 1 2\n",
      "line 3: vertex 0: no colour, but the file is COFF" },
    { "COFF\n3 1 0\n0 0 0 1 2 3\n1 0 0 1 2 3 4\n0 1 0 1 2 3\n3 0 1 2\n",
      "vertex 1: 4 colour values, but the first one has 3" },
    { "COFF\n3 1 0\n0 0 0 1 2 3\n1 0 0 1 2 300\n0 1 0 1 2 3\n3 0 1 2\n",
      "line 4: colour value 300 is not an integer in 0..255" },
    { "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1.5\n3 0 1 2\n",
      "line 5: colour value 1.5 is not in 0..1" },
    { "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 0.5\n3 0 1 2 2 0 0\n",
      "line 6: colour value 2 is not in 0..1" },
    { "OFF\n0 0 0\n", "no points could be read" },
    { "OFF\n1000000000000 1 0\n0 0 0\n", "ends after 1 of its 1000000000000 vertices" },
    { "OFF\n3 1 0\n0 0 0\n1 " + std::string(1, '\0') + "\x01 0\n0 1 0\n3 0 1 2\n",
      "coordinate '?"
      "?' is not a finite number" }, // two unprintable bytes
  };
  OutputWindowScope output;
  int index = 0;
  for (const auto& [text, expected] : cases)
  {
    SCOPED_TRACE(text);
    ExpectReadError(TextFile("malformed" + std::to_string(index++) + ".off", text), expected);
  }
  EXPECT_EQ(output.Text(), "");
}

} // namespace
