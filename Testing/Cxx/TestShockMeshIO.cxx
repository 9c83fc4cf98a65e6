// Tests of the mesh file input and output of shockfilter (ShockMeshIO.h): round
// trips through every format, colours, and the converters of the test meshes
// (the OFF syntax: TestShockMeshIOOffSyntax.cxx; the errors of malformed, missing
// and unsupported files, never a crash or printed text: TestShockMeshIOErrors.cxx).
#include "TestShockMeshIO.h"

namespace
{

// --- Round trips -------------------------------------------------------------------

TEST(ShockMeshIO, TrianglesRoundTripThroughEveryFormat)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(2, 1.5));
  for (const char* format : Formats)
  {
    SCOPED_TRACE(format);
    const std::string extension = format;
    const vtkSmartPointer<vtkPolyData> read = RoundTrip(sphere, TempPath("sphere." + extension));
    ASSERT_TRUE(read);
    const bool floats = extension == "ply" || extension == "stl";
    ExpectSamePolygons(sphere, read, floats ? FloatTolerance : 0.0);
    EXPECT_EQ(
      read->GetNumberOfPoints(), sphere->GetNumberOfPoints()); // STL's points are merged again
    if (extension != "stl")
    {
      ExpectSamePoints(sphere, read, floats ? FloatTolerance : 0.0);
    }
  }
}

TEST(ShockMeshIO, ExtensionsAreCaseInsensitive)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  for (const char* name : { "a.PLY", "b.Obj", "c.STL", "d.VTP", "e.Vtk", "f.OFF" })
  {
    const vtkSmartPointer<vtkPolyData> read = RoundTrip(sphere, TempPath(name));
    ASSERT_TRUE(read) << name;
    ExpectSamePolygons(sphere, read, FloatTolerance);
  }
}

TEST(ShockMeshIO, PolygonsKeepTheirSizeWhereTheFormatAllows)
{
  const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
  const double area = shocktest::SurfaceArea(FromPolyData(mesh));
  for (const char* format : Formats)
  {
    SCOPED_TRACE(format);
    const std::string extension = format;
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("mixed.") + format));
    ASSERT_TRUE(read);
    if (extension == "stl")
    {
      // STL holds triangles: 2 per quad, 3 for the pentagon, same area.
      EXPECT_EQ(read->GetNumberOfPolys(), 2 * 2 + 2 + 3);
      EXPECT_NEAR(shocktest::SurfaceArea(FromPolyData(read)), area, 1e-12);
    }
    else
    {
      ExpectSamePolygons(mesh, read, FloatTolerance);
    }
  }
}

TEST(ShockMeshIO, PointColorsRoundTripThroughPlyOffAndVtp)
{
  for (int components : { 3, 4 })
  {
    const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
    const auto colors = Colors(shockio::PointColorsName, mesh->GetNumberOfPoints(), components, 5);
    mesh->GetPointData()->AddArray(colors); // found by name: not the active scalars
    for (const char* format : { "ply", "off", "vtp" })
    {
      SCOPED_TRACE(std::string(format) + " " + std::to_string(components));
      const vtkSmartPointer<vtkPolyData> read =
        RoundTrip(mesh, TempPath(std::to_string(components) + "." + format));
      ASSERT_TRUE(read);
      ExpectColors(read->GetPointData(), shockio::PointColorsName, colors);
    }
  }
}

TEST(ShockMeshIO, ReadColorsAreTheActiveScalars)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  mesh->GetPointData()->AddArray(Colors(shockio::PointColorsName, mesh->GetNumberOfPoints(), 3, 1));
  for (const char* format : { "ply", "off" })
  {
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("colors.") + format));
    ASSERT_TRUE(read);
    ASSERT_NE(read->GetPointData()->GetScalars(), nullptr) << format;
    EXPECT_STREQ(read->GetPointData()->GetScalars()->GetName(), shockio::PointColorsName);
  }
}

TEST(ShockMeshIO, ActiveColorScalarsAreWrittenUnderAnyName)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  const auto colors = Colors("paint", mesh->GetNumberOfPoints(), 3, 9);
  mesh->GetPointData()->SetScalars(colors);
  for (const char* format : { "ply", "off" })
  {
    SCOPED_TRACE(format);
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("paint.") + format));
    ASSERT_TRUE(read);
    ExpectColors(read->GetPointData(), shockio::PointColorsName, colors);
  }
  // The caller's arrays keep their names.
  EXPECT_STREQ(mesh->GetPointData()->GetScalars()->GetName(), "paint");
}

TEST(ShockMeshIO, NonColorArraysAreNotColors)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkFloatArray> scalars; // not unsigned char
  scalars->SetName(shockio::PointColorsName);
  scalars->SetNumberOfComponents(3);
  scalars->SetNumberOfTuples(mesh->GetNumberOfPoints());
  scalars->Fill(0.5);
  mesh->GetPointData()->SetScalars(scalars);
  const std::string path = TempPath("plain.off");
  std::string error;
  ASSERT_TRUE(shockio::WriteMesh(mesh, path, error)) << error;
  std::ifstream file(path);
  std::string header;
  file >> header;
  EXPECT_EQ(header, "OFF");
  const vtkSmartPointer<vtkPolyData> read = shockio::ReadMesh(path, error);
  ASSERT_TRUE(read) << error;
  EXPECT_EQ(read->GetPointData()->GetNumberOfArrays(), 0);
}

TEST(ShockMeshIO, FaceColorsRoundTripThroughPlyAndOff)
{
  for (int components : { 3, 4 })
  {
    const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
    const auto colors = Colors(shockio::FaceColorsName, mesh->GetNumberOfPolys(), components, 77);
    mesh->GetCellData()->AddArray(colors);
    for (const char* format : { "ply", "off" })
    {
      SCOPED_TRACE(std::string(format) + " " + std::to_string(components));
      const vtkSmartPointer<vtkPolyData> read =
        RoundTrip(mesh, TempPath(std::to_string(components) + "." + format));
      ASSERT_TRUE(read);
      ExpectColors(read->GetCellData(), shockio::FaceColorsName, colors);
    }
  }
}

TEST(ShockMeshIO, PlyKeepsNormals)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkDoubleArray> normals; // the PLY writer takes floats only: converted
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    normals->InsertNextTuple(mesh->GetPoint(p));
  }
  mesh->GetPointData()->SetNormals(normals);
  const vtkSmartPointer<vtkPolyData> read = RoundTrip(mesh, TempPath("normals.ply"));
  ASSERT_TRUE(read);
  vtkDataArray* readNormals = read->GetPointData()->GetNormals();
  ASSERT_NE(readNormals, nullptr);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(readNormals->GetComponent(p, c), normals->GetComponent(p, c), FloatTolerance);
    }
  }
}

TEST(ShockMeshIO, VtkFormatsKeepEveryArray)
{
  const vtkSmartPointer<vtkPolyData> mesh = ToPolyData(Icosphere(1));
  vtkNew<vtkDoubleArray> height;
  height->SetName("height");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    height->InsertNextValue(mesh->GetPoint(p)[2]);
  }
  mesh->GetPointData()->AddArray(height);
  mesh->GetCellData()->AddArray(Colors("labels", mesh->GetNumberOfPolys(), 1, 3));
  for (const char* format : { "vtp", "vtk" })
  {
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("arrays.") + format));
    ASSERT_TRUE(read);
    vtkDataArray* readHeight = read->GetPointData()->GetArray("height");
    ASSERT_NE(readHeight, nullptr) << format;
    EXPECT_EQ(readHeight->GetTuple1(7), height->GetValue(7));
    EXPECT_NE(read->GetCellData()->GetArray("labels"), nullptr) << format;
  }
}

TEST(ShockMeshIO, FaceFormatsWriteStripsAsTrianglesAndDropOtherCells)
{
  // A vertex cell, a line, a triangle and a 5-point strip (3 triangles), each with a face colour.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 6; ++k)
  {
    points->InsertNextPoint(k / 2, k % 2, 0.0);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  verts->InsertNextCell({ 0 });
  lines->InsertNextCell({ 0, 5 });
  polys->InsertNextCell({ 0, 2, 1 });
  strips->InsertNextCell({ 1, 2, 3, 4, 5 });
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  mesh->SetStrips(strips);
  const auto colors = Colors(shockio::FaceColorsName, 4, 3, 0); // vertex, line, triangle, strip
  mesh->GetCellData()->AddArray(colors);
  for (const char* format : { "ply", "off", "stl" })
  {
    SCOPED_TRACE(format);
    const vtkSmartPointer<vtkPolyData> read =
      RoundTrip(mesh, TempPath(std::string("strip.") + format));
    ASSERT_TRUE(read);
    EXPECT_EQ(read->GetNumberOfVerts() + read->GetNumberOfLines() + read->GetNumberOfStrips(), 0);
    ASSERT_EQ(read->GetNumberOfPolys(), 4);
    // The strip's triangles alternate in orientation to face the same way.
    const shocktest::MeshData triangles = FromPolyData(read);
    for (std::int64_t t = 0; t < 4; ++t)
    {
      EXPECT_GT(shocktest::TriangleNormal(triangles, t)[2], 0.0) << "triangle " << t;
    }
    if (std::string(format) != "stl")
    {
      auto* readColors =
        vtkUnsignedCharArray::SafeDownCast(read->GetCellData()->GetArray(shockio::FaceColorsName));
      ASSERT_NE(readColors, nullptr);
      for (vtkIdType t = 0; t < 4; ++t)
      {
        EXPECT_EQ(readColors->GetValue(3 * t), colors->GetValue(3 * (t == 0 ? 2 : 3)))
          << "triangle " << t;
      }
    }
  }
}

TEST(ShockMeshIO, OffCoordinatesRoundTripExactly)
{
  auto mesh = ToPolyData(shocktest::Noisy(Icosphere(2), 1e-3, 11));
  mesh->GetPoints()->SetPoint(0, 0.1, -1e-300, 12345678.901234567);
  const vtkSmartPointer<vtkPolyData> read = RoundTrip(mesh, TempPath("exact.off"));
  ASSERT_TRUE(read);
  ExpectSamePoints(mesh, read, 0.0);
}

// --- The converters of the test meshes -----------------------------------------------------

TEST(TestMeshesVTK, ConvertersRoundTrip)
{
  const shocktest::MeshData sphere = Icosphere(2);
  const vtkSmartPointer<vtkPolyData> polyData = ToPolyData(sphere);
  EXPECT_EQ(polyData->GetNumberOfPoints(), sphere.NumberOfPoints());
  EXPECT_EQ(polyData->GetNumberOfPolys(), sphere.NumberOfTriangles());
  const shocktest::MeshData back = FromPolyData(polyData);
  EXPECT_EQ(back.points, sphere.points);
  EXPECT_EQ(back.triangles, sphere.triangles);
}

TEST(TestMeshesVTK, FromPolyDataFansPolygonsAndSkipsOtherCells)
{
  const vtkSmartPointer<vtkPolyData> mesh = MixedPolygons();
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 9 });
  mesh->SetLines(lines);
  const shocktest::MeshData triangles = FromPolyData(mesh);
  EXPECT_EQ(triangles.NumberOfPoints(), 11);
  const std::vector<std::int64_t> expected = { 0, 1, 6, 0, 6, 5, 1, 2, 7, 1, 7, 6, 2, 3, 8, 2, 8, 7,
    3, 4, 9, 3, 9, 10, 3, 10, 8 };
  EXPECT_EQ(triangles.triangles, expected);
}

} // namespace
