// Tests of the mesh file input and output of shockfilter (ShockMeshIO.h): the
// errors of malformed files of the VTK formats, of truncated and corrupt binary
// files, of what VTK's readers would drop or change, of legacy files of other
// datasets, of unsupported or missing files and of writes; one line each, never
// a crash or printed text (the other tests of ShockMeshIO.h: TestShockMeshIO.cxx,
// TestShockMeshIOOffSyntax.cxx).
#include "TestShockMeshIO.h"

namespace
{

// --- Errors of the VTK formats ----------------------------------------------------------

TEST(ShockMeshIO, MalformedFilesOfTheVtkFormatsGiveErrorsWithoutPrinting)
{
  const std::string plyHeader = "ply\nformat ascii 1.0\n"
                                "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n";
  const std::string plyVertices = "0 0 0\n1 0 0\n0 1 0\n";
  struct Case
  {
    const char* extension;
    std::string text;
    const char* expected;
  };
  const Case cases[] = {
    { "ply", "garbage\n", "not a PLY file" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "no end_header line" },
    { "ply", "ply\nelement vertex 1\nproperty float x\nend_header\n", "no format line" },
    { "ply", "ply\nformat nonsense 1.0\nend_header\n", "line 2: unknown PLY format" },
    { "ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
      "line 3: expected 'property" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n",
      "line 4: expected 'property" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
      "line 3: expected 'element" },
    { "ply", "ply\nformat ascii 1.0\n\nelement vertex 1\nend_header\n",
      "line 3: a blank line in the header" },
    { "ply",
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n3 0 1 2\n",
      "has no 'vertex' element" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 "
      "0\n",
      "no x, y and z values" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\nelement extra 2\nend_header\n0 0 0\n1 0 0\n0 1 0\n\n\n",
      "the PLY element 'extra' has no properties" }, // vtkPLY crashed on it (fuzzing)
    { "ply",
      "ply\nformat ascii 1.0\nelement edge 0\nproperty int a\nelement vertex 0\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n",
      "needs the 'vertex' element first" },
    { "ply",
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 0\nproperty list uchar float vertex_indices\nend_header\n",
      "no 'vertex_indices' list of integers" },
    { "ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
      "property list uchar uchar red\nend_header\n",
      "the PLY property 'red' is declared a list" },
    { "ply", plyHeader.substr(0, plyHeader.size() - 11) + "property float texcoord\nend_header\n" + plyVertices +
      "3 0 1 2 5\n",
      "the PLY property 'texcoord' is declared a single value" },
    { "ply", plyHeader + "0 0 0\n1 0 0\n", "vertex 2: the file ends before the data" },
    { "ply", plyHeader + plyVertices + "3 0 1 2", "line 13: face 0: the last line has no line break" },
    { "ply", plyHeader + "0 0 0\n1\v0 0\n0 1 0\n3 0 1 2\n", "vertex 1: '1?0' is not a finite number" },
    { "ply", plyHeader + plyVertices, "face 0: the file ends before the data" },
    { "ply", plyHeader + "0 0 0\n\n1 0 0\n0 1 0\n3 0 1 2\n",
      "line 11: vertex 1: a blank line in the data" },
    { "ply", plyHeader + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
      "line 11: vertex 1: 'zero' is not a finite number" },
    { "ply", plyHeader + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
      "vertex 1: fewer values than the header announces" },
    { "ply", plyHeader + "0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
      "vertex 0: more values than the header announces" },
    { "ply", plyHeader + plyVertices + "3 0 1 3\n", "line 13: face 0: vertex id 3 is not in 0..2" },
    { "ply", plyHeader + plyVertices + "3 0 1.5 2\n", "'1.5' is not an integer" },
    { "ply", plyHeader + plyVertices + "3 0 1\n", "fewer values" },
    { "stl", "solid broken\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n",
      "Parse error reading STL vertex" },
    { "stl", "not an stl file at all\n", "Expecting 'solid'" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4: vertex id '9' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: vertex id '0' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "vertex id '-4' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n",
      "texture coordinate id '1' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/ 3/1\n",
      "texture coordinate id '' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n",
      "normal id '2' refers to nothing" },
    { "obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 \\\n 4\n", "line 4: vertex id '4' refers to nothing" },
    { "obj", "v 0 0 0\nusemtl " + std::string(100, 'm') + "\n",
      "a material name of 100 characters or more" },
    { "obj", "just some words\n", "no points could be read" },
    { "vtp", "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"><PolyData><Piece",
      "Error parsing XML" },
    { "vtp", "this is not XML\n", "Error parsing XML" },
    { "vtk", "# vtk DataFile Version 3.0\nbroken\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0\n",
      "Error reading ascii data" }, // a generic VTK warning, caught through the output window
    { "vtk", "not a vtk file\n", "Unrecognized file type" },
    { "vtk",
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
      "POLYGONS 1 4\n3 0 1 5\n",
      "a cell refers to a point the file does not have" },
  };
  OutputWindowScope output;
  for (size_t i = 0; i < std::size(cases); ++i)
  {
    SCOPED_TRACE(cases[i].text);
    ExpectReadError(
      TextFile("malformed" + std::to_string(i) + "." + cases[i].extension, cases[i].text),
      cases[i].expected);
  }
  EXPECT_EQ(output.Text(), "");
}

TEST(ShockMeshIO, TruncatedAndCorruptBinaryFilesGiveErrors)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  OutputWindowScope output;
  const std::pair<const char*, const char*> formats[] = { { "ply",
                                                            "the file ends before the data" },
    { "stl", "announces 80 triangles, but the file holds 78" }, { "vtp", "Cannot read" },
    { "vtk", "Error reading binary data" } };
  for (const auto& [format, expected] : formats)
  {
    SCOPED_TRACE(format);
    const std::string path = TempPath(std::string("whole.") + format);
    std::string error;
    ASSERT_TRUE(shockio::WriteMesh(sphere, path, error)) << error;
    std::ifstream file(path, std::ios::binary);
    const std::string bytes(
      (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    // The last 100 bytes cut off.
    const std::string truncated =
      TextFile(std::string("truncated.") + format, bytes.substr(0, bytes.size() - 100));
    ExpectReadError(truncated, expected);
  }
  // A binary PLY file whose face refers to a vertex it does not have.
  {
    const std::string path = TempPath("badindex.ply");
    std::string error;
    ASSERT_TRUE(shockio::WriteMesh(sphere, path, error)) << error;
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    const std::string bytes(
      (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const size_t faces =
      bytes.find("end_header\n") + 11 + 12 * static_cast<size_t>(sphere->GetNumberOfPoints());
    const char wrong[4] = { '\xE8', '\x03', 0,
      0 }; // 1000 as a little-endian int32: the second id of face 0
    file.seekp(static_cast<std::streamoff>(faces + 1 + 4));
    file.write(wrong, sizeof(wrong));
    file.close();
    ExpectReadError(path, "face 0: vertex id 1000 is not in 0..41");
  }
  // A binary STL file announcing more triangles than it holds.
  {
    std::string bytes(84 + 50, '\0');
    bytes[80] = 2;
    ExpectReadError(TextFile("short.stl", bytes), "announces 2 triangles, but the file holds 1");
  }
  EXPECT_EQ(output.Text(), "");
}

// What VTK's mesh readers would silently change or drop is refused, naming it:
// a face vtkOBJReader skips (vertex references in another form than the faces
// before it), PLY colours that are not 8-bit (vtkPLYReader stores them as
// 8-bit: 0..1 floats would turn black, 60000 would become 96), triangle strips
// vtkPLYReader skips. The same faces in one form are read whole.
// A truncated ASCII PLY says so; a complete one whose last line lacks its line
// break is told that.
TEST(ShockMeshIO, ATruncatedPlySaysTruncated)
{
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n";
  std::string error;
  const std::string cut = TextFile("cut.ply", header + "3 0 1");
  EXPECT_FALSE(shockio::ReadMesh(cut, error));
  EXPECT_EQ(error, cut + ": line 13: face 0: the file ends inside the data (truncated?)");
  const std::string open = TextFile("open.ply", header + "3 0 1 2");
  EXPECT_FALSE(shockio::ReadMesh(open, error));
  EXPECT_EQ(error, open + ": line 13: face 0: the last line has no line break, which VTK's PLY reader needs");
}

TEST(ShockMeshIO, WhatTheReadersWouldDropOrChangeIsRefused)
{
  std::string error;
  const std::string mixed = TextFile(
    "skipped.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n");
  EXPECT_FALSE(shockio::ReadMesh(mixed, error));
  EXPECT_EQ(error, mixed + ": face 2 (counting from 1) writes its vertex references in another form (v, v/vt, "
                           "v//vn or v/vt/vn) than the faces before it, and VTK's OBJ reader drops such faces; "
                           "write every face in one form");
  const std::string oneForm = TextFile(
    "one_form.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2//1 4//1 3//1\n");
  const vtkSmartPointer<vtkPolyData> mesh = shockio::ReadMesh(oneForm, error);
  ASSERT_TRUE(mesh) << error;
  EXPECT_EQ(mesh->GetNumberOfPolys(), 2);

  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (const std::string type : { "float", "ushort", "double" })
  {
    const std::string path = TextFile("colours_" + type + ".ply",
      header + "property " + type + " red\nproperty " + type + " green\nproperty " + type + " blue\n" + faces +
        "0 0 0 0 0 1\n1 0 0 1 0 0\n0 1 0 0 1 0\n3 0 1 2\n");
    EXPECT_FALSE(shockio::ReadMesh(path, error)) << type;
    EXPECT_NE(error.find("the PLY colour 'red' of the vertex element is"), std::string::npos) << error;
    EXPECT_NE(error.find("store them as uchar"), std::string::npos) << error;
  }
  const std::string bytes = TextFile("colours_uchar.ply",
    header + "property uchar red\nproperty uchar green\nproperty uchar blue\n" + faces +
      "0 0 0 0 0 255\n1 0 0 255 0 0\n0 1 0 0 255 0\n3 0 1 2\n");
  EXPECT_TRUE(shockio::ReadMesh(bytes, error)) << error;

  const std::string strips = TextFile("strips.ply",
    header + "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
             "3 0 1 2\n");
  EXPECT_FALSE(shockio::ReadMesh(strips, error));
  EXPECT_NE(error.find("'tristrips', which VTK's PLY reader skips"), std::string::npos) << error;
}

TEST(ShockMeshIO, LegacyUnstructuredGridIsReadAsItsSurface)
{
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  points->InsertNextPoint(0, 0, 1);
  grid->SetPoints(points);
  const vtkIdType tetra[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, tetra);
  const std::string path = TempPath("tetra.vtk");
  vtkNew<vtkUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  std::string error;
  const vtkSmartPointer<vtkPolyData> surface = shockio::ReadMesh(path, error);
  ASSERT_TRUE(surface) << error;
  EXPECT_EQ(surface->GetNumberOfPolys(), 4);
  EXPECT_NEAR(shocktest::SurfaceArea(FromPolyData(surface)), 1.5 + std::sqrt(3.0) / 2, 1e-12);
}

TEST(ShockMeshIO, LegacyFilesOfOtherDatasetsGiveErrors)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 2);
  const std::string path = TempPath("image.vtk");
  vtkNew<vtkStructuredPointsWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  OutputWindowScope output;
  ExpectReadError(path, "holds neither polydata nor an unstructured grid");
  EXPECT_EQ(output.Text(), "");
}

// --- File and argument errors ------------------------------------------------------------

TEST(ShockMeshIO, UnsupportedOrMissingFilesGiveErrors)
{
  const std::string mesh = TextFile("mesh.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string renamed = TextFile("mesh.xyz", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string folder = TempPath("folder");
  std::filesystem::create_directories(folder);
  const std::string bare = folder + "/mesh";
  std::ofstream(bare) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  ExpectReadError(renamed, "unknown extension '.xyz'");
  ExpectReadError(bare, "no file extension");
  ExpectReadError(TempPath("missing.ply"), "no such file");
  ExpectReadError(TextFile("empty.stl", ""), "the file is empty");
  const std::string directory = TempPath("folder.obj");
  std::filesystem::create_directories(directory);
  ExpectReadError(directory, "is a directory");
  std::string error;
  EXPECT_TRUE(shockio::ReadMesh(mesh, error)) << error;
}

TEST(ShockMeshIO, WritingErrors)
{
  const vtkSmartPointer<vtkPolyData> sphere = ToPolyData(Icosphere(1));
  OutputWindowScope output;
  std::string error;
  EXPECT_FALSE(shockio::WriteMesh(sphere, TempPath("mesh.xyz"), error));
  EXPECT_NE(error.find("unknown extension '.xyz'"), std::string::npos) << error;
  EXPECT_FALSE(shockio::WriteMesh(nullptr, TempPath("null.ply"), error));
  EXPECT_NE(error.find("no points"), std::string::npos) << error;
  vtkNew<vtkPolyData> empty;
  EXPECT_FALSE(shockio::WriteMesh(empty, TempPath("empty.vtp"), error));
  EXPECT_NE(error.find("no points"), std::string::npos) << error;

  // A point cloud has no triangles for STL.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(sphere->GetPoints());
  EXPECT_FALSE(shockio::WriteMesh(cloud, TempPath("cloud.stl"), error));
  EXPECT_NE(error.find("no polygons"), std::string::npos) << error;

  // PLY stores at most 255 corners per polygon.
  vtkNew<vtkPolyData> disk;
  vtkNew<vtkPoints> points;
  std::vector<vtkIdType> ring;
  for (int k = 0; k < 300; ++k)
  {
    ring.push_back(points->InsertNextPoint(std::cos(k / 47.0), std::sin(k / 47.0), 0.0));
  }
  vtkNew<vtkCellArray> polys;
  polys->InsertNextCell(static_cast<vtkIdType>(ring.size()), ring.data());
  disk->SetPoints(points);
  disk->SetPolys(polys);
  EXPECT_FALSE(shockio::WriteMesh(disk, TempPath("disk.ply"), error));
  EXPECT_NE(error.find("at most 255"), std::string::npos) << error;
  EXPECT_TRUE(RoundTrip(disk, TempPath("disk.off"))); // OFF has no limit

  // Every format reports a directory that does not exist.
  for (const char* format : Formats)
  {
    const std::string path = TempPath("no-such-directory") + "/mesh." + format;
    EXPECT_FALSE(shockio::WriteMesh(sphere, path, error)) << format;
    EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
  EXPECT_EQ(output.Text(), "");
}

} // namespace
