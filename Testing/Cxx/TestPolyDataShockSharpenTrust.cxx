// vtkPolyDataShockSharpenFilter as a new user runs it, on shapes with known answers:
// already sharp shapes stay where they are, rounded and blurred shapes move towards
// their sharp originals, a mesh given twice gives the result of the mesh given once,
// and the active normals of the output belong to the output's geometry.
#include "vtkPolyDataShockSharpenFilter.h"

#include "TestFilterHelpers.h"
#include "TestMeshesVTK.h"
#include "TestSharpShapes.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellLocator.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkDataArray.h"
#include "vtkFeatureEdges.h"
#include "vtkFloatArray.h"
#include "vtkGenericCell.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkSphereSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSmartPointer.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace
{
using shock_test::MessageLog;
using Filter = vtkPolyDataShockSharpenFilter;
using Mesh = vtkSmartPointer<vtkPolyData>;

Mesh Output(vtkAlgorithm* algorithm)
{
  algorithm->Update();
  Mesh copy = Mesh::New();
  copy->DeepCopy(vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(0)));
  return copy;
}

/// Triangulate and clean a source (what ParaView's Triangulate + Clean do), then subdivide linearly.
Mesh Prepared(vtkAlgorithm* source, int subdivisions)
{
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  if (subdivisions == 0)
  {
    return Output(clean);
  }
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(clean->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(subdivisions);
  return Output(subdivide);
}

double Diagonal(vtkPolyData* mesh)
{
  return mesh->GetLength(); // of the bounding box
}

double LargestMove(vtkPolyData* a, vtkPolyData* b)
{
  double worst = 0.0;
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    a->GetPoint(p, x);
    b->GetPoint(p, y);
    worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(x, y)));
  }
  return worst;
}

/// Mean angle (degrees, area-weighted) to the original's normal at the closest point,
/// and RMS distance of the points to the original surface.
std::pair<double, double> Errors(vtkPolyData* mesh, vtkPolyData* original)
{
  vtkNew<vtkCellLocator> locator;
  locator->SetDataSet(original);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  auto normal = [](vtkPolyData* m, vtkIdType c, double n[3], double centre[3]) {
    double a[3], b[3], d[3];
    vtkIdType count;
    const vtkIdType* ids;
    m->GetCellPoints(c, count, ids);
    m->GetPoint(ids[0], a);
    m->GetPoint(ids[1], b);
    m->GetPoint(ids[2], d);
    vtkTriangle::ComputeNormal(a, b, d, n);
    for (int k = 0; k < 3; ++k)
    {
      centre[k] = (a[k] + b[k] + d[k]) / 3.0;
    }
    return vtkTriangle::TriangleArea(a, b, d);
  };
  double angle = 0.0, area = 0.0, squares = 0.0;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    double n[3], centre[3], closest[3], reference[3], unused[3], d2;
    vtkIdType at;
    int sub;
    const double a = normal(mesh, c, n, centre);
    locator->FindClosestPoint(centre, closest, cell, at, sub, d2);
    normal(original, at, reference, unused);
    angle += a * std::acos(std::max(-1.0, std::min(1.0, vtkMath::Dot(n, reference)))) * 180.0 / vtkMath::Pi();
    area += a;
  }
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3], closest[3], d2;
    vtkIdType at;
    int sub;
    mesh->GetPoint(p, x);
    locator->FindClosestPoint(x, closest, cell, at, sub, d2);
    squares += d2;
  }
  return { angle / area, std::sqrt(squares / mesh->GetNumberOfPoints()) };
}

TEST(SharpenTrust, AlreadySharpShapesStayWithinOnePercentAtDefaults)
{
  vtkNew<vtkCubeSource> box; // ParaView's Box()
  vtkNew<vtkCylinderSource> cylinder; // ParaView's Cylinder(): resolution 6, capped
  vtkNew<vtkCylinderSource> round;
  round->SetResolution(32);
  const std::vector<std::pair<std::string, Mesh>> shapes = { { "Box, triangulated, cleaned", Prepared(box, 0) },
    { "Box subdivided 3 times", Prepared(box, 3) }, { "Cylinder subdivided twice", Prepared(cylinder, 2) },
    { "Cylinder (resolution 32) subdivided twice", Prepared(round, 2) },
    { "slotted L block", shocktest::ToPolyData(shocktest::SlottedLBlock()) } };
  for (const auto& shape : shapes)
  {
    vtkNew<Filter> sharpen; // defaults left alone
    MessageLog log(sharpen);
    sharpen->SetInputData(shape.second);
    const Mesh out = Output(sharpen);
    EXPECT_TRUE(log.Errors.empty() && log.Warnings.empty()) << log.Errors << log.Warnings;
    EXPECT_LT(LargestMove(out, shape.second), 0.01 * Diagonal(shape.second)) << shape.first;
    EXPECT_GT(sharpen->GetLastFeatureEdges(), 0) << shape.first;
    // The paper's settings round them (what the defaults keep from happening).
    sharpen->SetFeatureAngle(180.0);
    sharpen->SetFitTargetToProjection();
    sharpen->SetAnchorWeight(0.0);
    sharpen->SetDriftRadius(0.0);
    sharpen->KeepUnmovedNormalsOff();
    sharpen->SetNormalSmoothingPasses(0);
    const Mesh paper = Output(sharpen);
    EXPECT_GT(LargestMove(paper, shape.second), 0.01 * Diagonal(shape.second)) << shape.first;
  }
}

TEST(SharpenTrust, RoundedAndBlurredShapesMoveTowardsTheirOriginals)
{
  const shocktest::MeshData cube = shocktest::BoxSurface(24, 2.0, 2.0, 2.0);
  const Mesh block = shocktest::ToPolyData(shocktest::SlottedLBlock());
  vtkNew<vtkWindowedSincPolyDataFilter> blur;
  blur->SetInputData(block);
  blur->SetNumberOfIterations(20);
  blur->SetPassBand(0.005);
  blur->NormalizeCoordinatesOn();
  // (input, sharp original, flow time): the windowed-sinc blur is narrower.
  const std::vector<std::tuple<Mesh, Mesh, double>> shapes = {
    { shocktest::ToPolyData(shocktest::RoundedBox(24, 2.0, 0.3)), shocktest::ToPolyData(cube), 1024.0 },
    { Output(blur), block, 256.0 } };
  for (const auto& [input, original, time] : shapes)
  {
    const auto before = Errors(input, original);
    for (int solver : { Filter::CONJUGATE_GRADIENT, Filter::EXACT })
    {
      vtkNew<Filter> sharpen;
      sharpen->SetInputData(input);
      sharpen->SetFlowTime(time);
      sharpen->SetSolver(solver);
      const Mesh out = Output(sharpen);
      const auto after = Errors(out, original);
      std::cout << "normal error " << before.first << " -> " << after.first << " degrees, RMS distance "
                << before.second << " -> " << after.second << " (solver " << solver << ")\n";
      EXPECT_LT(after.first, 0.5 * before.first) << "solver " << solver;
      EXPECT_LT(after.second, 0.8 * before.second) << "solver " << solver;
      EXPECT_EQ(sharpen->GetLastFlippedTriangles(), 0);
    }
  }
}

TEST(SharpenTrust, CoarseSmoothShapesStayPutAtDefaults)
{
  // ParaView's Sphere() (resolution 8) and coarser or finer spheres and tori: a
  // smooth shape has nothing to sharpen, however coarse its tessellation.
  std::vector<std::pair<std::string, Mesh>> shapes;
  for (int resolution : { 8, 12, 16 })
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(resolution);
    sphere->SetPhiResolution(resolution);
    shapes.emplace_back("Sphere, resolution " + std::to_string(resolution), Output(sphere));
  }
  for (int resolution : { 16, 32 })
  {
    vtkNew<vtkParametricTorus> torus;
    vtkNew<vtkParametricFunctionSource> source;
    source->SetParametricFunction(torus);
    source->SetUResolution(resolution);
    source->SetVResolution(resolution);
    vtkNew<vtkCleanPolyData> clean; // close the seams (their points differ by rounding)
    clean->SetInputConnection(source->GetOutputPort());
    clean->SetTolerance(1e-10);
    shapes.emplace_back("Torus, resolution " + std::to_string(resolution), Output(clean));
  }
  for (const auto& [name, shape] : shapes)
  {
    for (double time : { 64.0, 2048.0 })
    {
      vtkNew<Filter> sharpen;
      MessageLog log(sharpen);
      sharpen->SetInputData(shape);
      sharpen->SetFlowTime(time);
      const Mesh out = Output(sharpen);
      EXPECT_TRUE(log.Errors.empty()) << log.Errors;
      EXPECT_LT(LargestMove(out, shape), 0.01 * Diagonal(shape)) << name << ", t = " << time;
    }
  }
  // The paper's potential (CurvatureContrast 0) sharpens the sphere's facets: its poles move out.
  vtkNew<Filter> paper;
  paper->SetInputData(shapes.front().second);
  paper->SetFlowTime(2048.0);
  paper->SetCurvatureContrast(0.0);
  EXPECT_GT(LargestMove(Output(paper), shapes.front().second), 0.02 * Diagonal(shapes.front().second));
}

/**
 * Whether the defaults bring `blurred` back towards `original` at some flow
 * time of 256, 1024, 4096: the mean face-normal error <= 0.7 x the blurred
 * input's, and the RMS point distance <= rmsLimit x the blurred input's.
 */
bool ComesBackAtSomeFlowTime(vtkPolyData* blurred, vtkPolyData* original, double rmsLimit)
{
  const auto before = Errors(blurred, original);
  bool met = false;
  for (double time : { 256.0, 1024.0, 4096.0 })
  {
    vtkNew<Filter> sharpen;
    sharpen->SetInputData(blurred);
    sharpen->SetFlowTime(time);
    const auto after = Errors(Output(sharpen), original);
    std::cout << "t = " << time << ": normal error " << before.first << " -> " << after.first
              << " degrees, RMS distance " << before.second << " -> " << after.second << "\n";
    met = met || (after.first <= 0.7 * before.first && after.second <= rmsLimit * before.second);
  }
  return met;
}

/**
 * A CAD-like part (a box, subdivided so that a blur of a few edges leaves its
 * faces flat) and the same blurred as the evaluation's sinc blurs do.
 */
std::pair<Mesh, Mesh> SincBlurredBox()
{
  vtkNew<vtkCubeSource> cube;
  const Mesh box = Prepared(cube, 4);
  vtkNew<vtkWindowedSincPolyDataFilter> blur;
  blur->SetInputData(box);
  blur->SetNumberOfIterations(20);
  blur->SetPassBand(0.05);
  blur->NormalizeCoordinatesOn();
  return { box, Output(blur) };
}

TEST(SharpenTrust, ABoxBlurredByWindowedSincComesBackAtDefaults)
{
  // The sinc-blurred box: at some flow time the
  // defaults bring the normals back (error <= 0.7 x the blurred input's)
  // without moving the points further from the original (RMS <= 1.0 x).
  const std::pair<Mesh, Mesh> boxes = SincBlurredBox();
  const Mesh& box = boxes.first;
  const Mesh& blurred = boxes.second;
  ASSERT_GT(Errors(blurred, box).first, 1.0); // degrees: the blur rounds the creases
  EXPECT_TRUE(ComesBackAtSomeFlowTime(blurred, box, 1.0));
}

/// RMS distance of the points of `result` to the same points of `original`.
double RmsDistance(vtkPolyData* original, vtkPolyData* result)
{
  double sum = 0.0;
  for (vtkIdType p = 0; p < original->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    original->GetPoint(p, x);
    result->GetPoint(p, y);
    sum += vtkMath::Distance2BetweenPoints(x, y);
  }
  return std::sqrt(sum / original->GetNumberOfPoints());
}

/// The volume a closed triangle mesh encloses (positive when its triangles face outwards).
double EnclosedVolume(vtkPolyData* mesh)
{
  double sum = 0.0;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    double a[3], b[3], c[3], bc[3];
    mesh->GetPoint(ids[0], a);
    mesh->GetPoint(ids[1], b);
    mesh->GetPoint(ids[2], c);
    vtkMath::Cross(b, c, bc);
    sum += vtkMath::Dot(a, bc) / 6.0;
  }
  return sum;
}

/**
 * An L-shaped block, as a scan samples a machined part: the union of four
 * unit cubes (at x = 0, 1, 2 in the row y = 0, and at x = 0, y = 1), each
 * square face of the surface split into `cells` x `cells` squares of two
 * triangles, the points shared. It has convex creases and a concave one (inside the L), and corners
 * where three creases meet.
 */
Mesh LBlock(int cells)
{
  auto filled = [](int x, int y, int z) { return z == 0 && ((y == 0 && x >= 0 && x < 3) || (x == 0 && y == 1)); };
  const int n = cells;
  auto key = [n](const int g[3]) { return (static_cast<long long>(g[0] + n) * (6 * n) + g[1] + n) * (6 * n) + g[2] + n; };
  std::map<long long, vtkIdType> ids;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  auto point = [&](const int g[3]) {
    const auto found = ids.find(key(g));
    if (found != ids.end())
    {
      return found->second;
    }
    const vtkIdType id = points->InsertNextPoint(
      static_cast<double>(g[0]) / n, static_cast<double>(g[1]) / n, static_cast<double>(g[2]) / n);
    ids.emplace(key(g), id);
    return id;
  };
  for (int x = 0; x < 3; ++x)
  {
    for (int y = 0; y < 2; ++y)
    {
      if (!filled(x, y, 0))
      {
        continue;
      }
      for (int axis = 0; axis < 3; ++axis)
      {
        for (int side : { -1, 1 })
        {
          int neighbour[3] = { x, y, 0 };
          neighbour[axis] += side;
          if (filled(neighbour[0], neighbour[1], neighbour[2]))
          {
            continue;
          }
          // The face's plane and two in-plane axes (u, v) with u x v along side * axis.
          const int u = (axis + 1) % 3;
          const int v = (axis + 2) % 3;
          for (int i = 0; i < n; ++i)
          {
            for (int j = 0; j < n; ++j)
            {
              int corner[4][3];
              const int du[4] = { 0, 1, 1, 0 };
              const int dv[4] = { 0, 0, 1, 1 };
              for (int k = 0; k < 4; ++k)
              {
                const int cell[3] = { x, y, 0 };
                for (int c = 0; c < 3; ++c)
                {
                  corner[k][c] = cell[c] * n;
                }
                corner[k][axis] += side > 0 ? n : 0;
                corner[k][u] += i + du[k];
                corner[k][v] += j + dv[k];
              }
              vtkIdType q[4];
              for (int k = 0; k < 4; ++k)
              {
                q[k] = point(corner[k]);
              }
              // Counter-clockwise seen from outside.
              const vtkIdType a[3] = { q[0], side > 0 ? q[1] : q[2], side > 0 ? q[2] : q[1] };
              const vtkIdType b[3] = { q[0], side > 0 ? q[2] : q[3], side > 0 ? q[3] : q[2] };
              triangles->InsertNextCell(3, a);
              triangles->InsertNextCell(3, b);
            }
          }
        }
      }
    }
  }
  Mesh block = Mesh::New();
  block->SetPoints(points);
  block->SetPolys(triangles);
  return block;
}

/**
 * Laplacian smoothing of the kind of ParaView's Smooth (written here: VTK
 * 9.2's vtkSmoothPolyDataFilter frees with the wrong delete under
 * AddressSanitizer): `iterations` times, every point moves `relaxation` of
 * the way to the mean of its edge neighbours, all from the previous
 * iteration's positions.
 */
Mesh LaplacianSmoothed(vtkPolyData* mesh, int iterations, double relaxation)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<std::set<vtkIdType>> neighbours(static_cast<size_t>(n));
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    for (vtkIdType k = 0; k < size; ++k)
    {
      neighbours[static_cast<size_t>(ids[k])].insert(ids[(k + 1) % size]);
      neighbours[static_cast<size_t>(ids[(k + 1) % size])].insert(ids[k]);
    }
  }
  std::vector<double> x(static_cast<size_t>(3 * n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    mesh->GetPoint(p, &x[static_cast<size_t>(3 * p)]);
  }
  for (int iteration = 0; iteration < iterations; ++iteration)
  {
    std::vector<double> next(x);
    for (vtkIdType p = 0; p < n; ++p)
    {
      const auto& around = neighbours[static_cast<size_t>(p)];
      for (int k = 0; k < 3; ++k)
      {
        double mean = 0.0;
        for (const vtkIdType q : around)
        {
          mean += x[static_cast<size_t>(3 * q + k)];
        }
        mean /= static_cast<double>(around.size());
        next[static_cast<size_t>(3 * p + k)] += relaxation * (mean - x[static_cast<size_t>(3 * p + k)]);
      }
    }
    x.swap(next);
  }
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    points->SetPoint(p, &x[static_cast<size_t>(3 * p)]);
  }
  Mesh smoothed = Mesh::New();
  smoothed->DeepCopy(mesh);
  smoothed->SetPoints(points);
  return smoothed;
}

TEST(SharpenTrust, AnLShapedBlockBlurredTwoWaysComesBackAtDefaults)
{
  // A part with a concave crease, sampled evenly, blurred as the evaluation's
  // sinc1 and laplace1 (docs/sharpening.md, "The scan set"): at some flow
  // time the defaults bring the normals back (error <= 0.7 x the blurred
  // input's) without moving the points further from the original (RMS <= 1.0 x).
  const Mesh block = LBlock(12);
  // Closed and outward: every edge shared by two triangles, a positive volume.
  vtkNew<vtkFeatureEdges> open;
  open->SetInputData(block);
  open->BoundaryEdgesOn();
  open->NonManifoldEdgesOn();
  open->FeatureEdgesOff();
  open->ManifoldEdgesOff();
  open->Update();
  ASSERT_EQ(open->GetOutput()->GetNumberOfCells(), 0);
  ASSERT_NEAR(EnclosedVolume(block), 4.0, 1e-9);

  vtkNew<vtkWindowedSincPolyDataFilter> sinc;
  sinc->SetInputData(block);
  sinc->SetNumberOfIterations(20);
  sinc->SetPassBand(0.05);
  sinc->NormalizeCoordinatesOn();
  const std::pair<const char*, Mesh> blurs[] = { { "windowed sinc", Output(sinc) },
    { "Laplacian", LaplacianSmoothed(block, 40, 0.1) } };
  for (const auto& [name, blurred] : blurs)
  {
    ASSERT_GT(Errors(blurred, block).first, 1.0) << name; // degrees: the creases are rounded
    EXPECT_TRUE(ComesBackAtSomeFlowTime(blurred, block, 1.0)) << name;
  }
}

TEST(SharpenTrust, TheFitHoldsWhatTheSharpeningDidNotTurn)
{
  // The windowed-sinc box of the previous test at the default flow time. Its
  // faces' middles are flat and the sharpening leaves their normals as they
  // are; the paper's fit (AnchorWeight 0) still moves those points, drifting
  // with the creases it sharpens. The defaults hold them where the blur left
  // them, end closer to the original point for point, and sharpen as much.
  const std::pair<Mesh, Mesh> boxes = SincBlurredBox();
  const Mesh& box = boxes.first;
  const Mesh& blurred = boxes.second;
  vtkNew<Filter> defaults;
  defaults->SetInputData(blurred);
  const Mesh anchored = Output(defaults);
  vtkNew<Filter> paper;
  paper->SetInputData(blurred);
  paper->SetAnchorWeight(0.0);
  const Mesh unanchored = Output(paper);
  // The middles: farther than 0.25 from every edge of the unit cube's faces.
  auto middleMove = [&](vtkPolyData* result) {
    double worst = 0.0;
    for (vtkIdType p = 0; p < box->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3], z[3];
      box->GetPoint(p, x);
      int inside = 0;
      for (int k = 0; k < 3; ++k)
      {
        inside += std::abs(x[k]) < 0.25 ? 1 : 0;
      }
      if (inside == 2) // on a face (one coordinate at +-0.5), away from its edges
      {
        blurred->GetPoint(p, y);
        result->GetPoint(p, z);
        worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(y, z)));
      }
    }
    return worst;
  };
  auto rms = [&](vtkPolyData* result) { return RmsDistance(box, result); };
  std::cout << "middle of the faces moved: paper's fit " << middleMove(unanchored) << ", defaults "
            << middleMove(anchored) << "; RMS to the original: blurred " << rms(blurred) << ", paper's fit "
            << rms(unanchored) << ", defaults " << rms(anchored) << "\n";
  EXPECT_GT(middleMove(unanchored), 1e-4 * Diagonal(box));
  EXPECT_LT(middleMove(anchored), 0.5 * middleMove(unanchored));
  EXPECT_LT(rms(anchored), rms(unanchored));
  const double input = Errors(blurred, box).first;
  EXPECT_LT(Errors(anchored, box).first, 0.8 * input);
  EXPECT_LT(Errors(anchored, box).first, 1.05 * Errors(unanchored, box).first);
}

TEST(SharpenTrust, TheDefaultDriftRemovalKeepsTheLocalMeanOfTheSincBlurredBox)
{
  // The windowed-sinc box again: the blur keeps the volume, pushing the faces
  // out beside the creases it rounds, so the fit without step 5 (DriftRadius
  // 0) rebuilds the creases on faces that stand a little out. The default
  // DriftRadius (8) removes the smooth part of the displacement: the
  // area-weighted mean position stays the blurred box's (exactly with the
  // exact solver) and the points end closer to the original box, while the
  // normals still sharpen.
  const std::pair<Mesh, Mesh> boxes = SincBlurredBox();
  const Mesh& box = boxes.first;
  const Mesh& blurred = boxes.second;
  vtkNew<Filter> withoutStep5;
  withoutStep5->SetInputData(blurred);
  withoutStep5->SetSolver(Filter::EXACT);
  withoutStep5->SetDriftRadius(0.0);
  const Mesh plain = Output(withoutStep5);
  vtkNew<Filter> defaults;
  defaults->SetInputData(blurred);
  defaults->SetSolver(Filter::EXACT);
  EXPECT_EQ(defaults->GetDriftRadius(), 8.0);
  const Mesh local = Output(defaults);
  // The mean displacement from the blurred box, each point weighted by a third
  // of the area of its triangles (0 without step 5 too, by symmetry), and the
  // volume (the sinc blur kept the box's; the fit without step 5 adds some at the creases).
  auto volume = [](vtkPolyData* result) { return EnclosedVolume(result); };
  auto meanShift = [&](vtkPolyData* result) {
    double shift[3] = { 0.0, 0.0, 0.0 };
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    vtkCellArray* polys = blurred->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    {
      double a[3], b[3], c[3];
      blurred->GetPoint(ids[0], a);
      blurred->GetPoint(ids[1], b);
      blurred->GetPoint(ids[2], c);
      const double area = vtkTriangle::TriangleArea(a, b, c);
      for (int corner = 0; corner < 3; ++corner)
      {
        double x[3], y[3];
        blurred->GetPoint(ids[corner], x);
        result->GetPoint(ids[corner], y);
        for (int k = 0; k < 3; ++k)
        {
          shift[k] += area / 3.0 * (y[k] - x[k]);
        }
      }
    }
    return vtkMath::Norm(shift);
  };
  auto rms = [&](vtkPolyData* result) { return RmsDistance(box, result); };
  std::cout << "mean shift: DriftRadius 0 " << meanShift(plain) << ", defaults " << meanShift(local)
            << "; volume: box " << volume(box) << ", blurred " << volume(blurred) << ", DriftRadius 0 "
            << volume(plain) << ", defaults " << volume(local) << "; RMS to the original: blurred " << rms(blurred) << ", DriftRadius 0 " << rms(plain)
            << ", defaults " << rms(local) << "\n";
  EXPECT_LT(meanShift(local), 1e-9);
  // Part of the volume the rebuilt creases add comes off again.
  EXPECT_LT(std::abs(volume(local) - volume(blurred)), 0.75 * std::abs(volume(plain) - volume(blurred)));
  EXPECT_LT(rms(local), rms(plain));
  EXPECT_LT(rms(local), rms(blurred));
  EXPECT_LT(Errors(local, box).first, 0.8 * Errors(blurred, box).first);
}

TEST(SharpenTrust, ABoxBlurredByAGaussianOfItsPositionsComesBackAtDefaults)
{
  // The same box blurred by a Gaussian of its point positions (sigma 1.5 mean
  // edge lengths, as the evaluation's gauss1): its creases turn over two or
  // three edges, each still sharper than the default feature angle, with the
  // faces beside them bent. The defaults bring the normals back at some flow
  // time (error <= 0.7 x the blurred input's) without moving the points
  // materially further from the original (RMS <= 1.05 x: the Gaussian also
  // slid the points along the faces, which no normal brings back; the
  // evaluation's parts in docs/sharpening.md end at 0.96-0.97 x).
  vtkNew<vtkCubeSource> cube;
  const Mesh box = Prepared(cube, 4);
  vtkPoints* points = box->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  double edge = 0.0;
  vtkIdType edges = 0;
  for (vtkIdType c = 0; c < box->GetNumberOfCells(); ++c)
  {
    vtkIdType size;
    const vtkIdType* ids;
    box->GetCellPoints(c, size, ids);
    for (vtkIdType k = 0; k < size; ++k, ++edges)
    {
      double a[3], b[3];
      points->GetPoint(ids[k], a);
      points->GetPoint(ids[(k + 1) % size], b);
      edge += std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
    }
  }
  const double sigma = 1.5 * edge / static_cast<double>(edges);
  vtkNew<vtkPoints> moved;
  moved->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3], sum[3] = { 0.0, 0.0, 0.0 }, weights = 0.0;
    points->GetPoint(i, p);
    for (vtkIdType j = 0; j < n; ++j)
    {
      double q[3];
      points->GetPoint(j, q);
      const double d2 = vtkMath::Distance2BetweenPoints(p, q);
      if (d2 <= 9.0 * sigma * sigma)
      {
        const double w = std::exp(-0.5 * d2 / (sigma * sigma));
        for (int k = 0; k < 3; ++k)
        {
          sum[k] += w * q[k];
        }
        weights += w;
      }
    }
    moved->SetPoint(i, sum[0] / weights, sum[1] / weights, sum[2] / weights);
  }
  vtkNew<vtkPolyData> blurred;
  blurred->CopyStructure(box);
  blurred->SetPoints(moved);
  // The blurred creases still have edges sharper than the default feature angle.
  vtkNew<vtkFeatureEdges> sharp;
  sharp->SetInputData(blurred);
  sharp->BoundaryEdgesOff();
  sharp->NonManifoldEdgesOff();
  sharp->ManifoldEdgesOff();
  sharp->FeatureEdgesOn();
  sharp->SetFeatureAngle(30.0);
  sharp->Update();
  ASSERT_GT(sharp->GetOutput()->GetNumberOfLines(), 0);
  ASSERT_GT(Errors(blurred, box).first, 1.0); // degrees: the blur rounds the creases
  EXPECT_TRUE(ComesBackAtSomeFlowTime(blurred, box, 1.05));
}

TEST(SharpenTrust, AMeshGivenTwiceGivesTheResultOfTheMeshGivenOnce)
{
  const Mesh mesh = shocktest::ToPolyData(shocktest::RoundedBox(10, 2.0, 0.4));
  vtkNew<vtkCleanPolyData> cleanOnce; // Clean numbers the points as the cells use them
  cleanOnce->SetInputData(mesh);
  const Mesh once = Output(cleanOnce);
  vtkNew<vtkAppendPolyData> append; // AppendDatasets(m, m) + Clean
  append->AddInputData(mesh);
  append->AddInputData(mesh);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(append->GetOutputPort());
  const Mesh twice = Output(clean);
  ASSERT_EQ(twice->GetNumberOfPoints(), once->GetNumberOfPoints());
  ASSERT_EQ(twice->GetNumberOfCells(), 2 * once->GetNumberOfCells());

  vtkNew<Filter> sharpen;
  sharpen->SetFlowTime(512);
  sharpen->SetInputData(once);
  const Mesh expected = Output(sharpen);
  ASSERT_GT(LargestMove(expected, once), 1e-3);
  MessageLog log(sharpen);
  sharpen->SetInputData(twice);
  const Mesh doubled = Output(sharpen);
  EXPECT_EQ(LargestMove(doubled, expected), 0.0);
  EXPECT_EQ(sharpen->GetLastRepeatedTriangles(), once->GetNumberOfCells());
  EXPECT_NE(log.Warnings.find(std::to_string(once->GetNumberOfCells()) + " triangles repeat"), std::string::npos)
    << log.Warnings;
  EXPECT_TRUE(log.Errors.empty()) << log.Errors;
}

TEST(SharpenTrust, OutputNormalsBelongToTheOutputGeometry)
{
  vtkNew<vtkPolyDataNormals> normals; // Generate Surface Normals before sharpening
  normals->SetInputData(shocktest::ToPolyData(shocktest::RoundedBox(16, 2.0, 0.4)));
  normals->SplittingOff();
  normals->ComputeCellNormalsOn();
  Mesh input = Output(normals);
  vtkNew<vtkFloatArray> other;
  other->SetName("Other");
  other->SetNumberOfTuples(input->GetNumberOfPoints());
  for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
  {
    other->SetValue(p, static_cast<float>(p) * 0.5f);
  }
  input->GetPointData()->AddArray(other);

  vtkNew<Filter> sharpen;
  sharpen->SetInputData(input);
  sharpen->SetFlowTime(1024);
  const Mesh out = Output(sharpen);
  ASSERT_GT(LargestMove(out, input), 1e-2);
  vtkNew<vtkPolyDataNormals> reference; // the normals of the output's geometry
  reference->SetInputData(out);
  reference->SplittingOff();
  reference->ConsistencyOff();
  reference->ComputeCellNormalsOn();
  const Mesh expected = Output(reference);
  for (const bool cells : { false, true })
  {
    vtkDataArray* got = cells ? out->GetCellData()->GetNormals() : out->GetPointData()->GetNormals();
    vtkDataArray* want = cells ? expected->GetCellData()->GetNormals() : expected->GetPointData()->GetNormals();
    vtkDataArray* old = cells ? input->GetCellData()->GetNormals() : input->GetPointData()->GetNormals();
    ASSERT_NE(got, nullptr);
    EXPECT_STREQ(got->GetName(), old->GetName());
    EXPECT_EQ(got->GetDataType(), old->GetDataType());
    double worst = 0.0, changed = 0.0;
    for (vtkIdType i = 0; i < got->GetNumberOfTuples(); ++i)
    {
      double a[3], b[3], c[3];
      got->GetTuple(i, a);
      want->GetTuple(i, b);
      old->GetTuple(i, c);
      worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(a, b)));
      changed = std::max(changed, std::sqrt(vtkMath::Distance2BetweenPoints(a, c)));
    }
    EXPECT_LT(worst, 1e-5) << (cells ? "cell" : "point") << " normals";
    EXPECT_GT(changed, 0.05) << (cells ? "cell" : "point") << " normals must have changed";
  }
  EXPECT_EQ(shock_test::Values(out->GetPointData()->GetArray("Other")), shock_test::Values(other))
    << "other arrays pass through";
}

} // namespace
