/**
 * sharpenbench: how well geometry sharpening (vtkPolyDataShockSharpenFilter)
 * recovers shapes whose sharp original is known, for the four fit targets
 * (Projection, the paper's; Rotation; Shear; CentralProjection), flow times,
 * screening weights and both solvers; and how far already sharp shapes move at default settings
 * with and without the feature angle. Markdown tables on stdout
 * (docs/sharpening.md records them):
 *
 *   build/bin/sharpenbench recovery   # rounded and blurred shapes against their originals
 *   build/bin/sharpenbench summary    # the same at t = 1024, eps = 1 only
 *   build/bin/sharpenbench features   # the rounded and blurred shapes at FeatureAngle 30 and 180
 *   build/bin/sharpenbench sharp      # already sharp shapes at default settings
 *
 * Shapes are unions of grid cells (closed, uniformly triangulated, with convex
 * and concave creases); "rounded" ones are moved onto the original grown
 * around its inner box by a ball (Minkowski rounding), "blurred" ones are
 * windowed-sinc smoothed (vtkWindowedSincPolyDataFilter). Measures, all
 * against the sharp original: area-weighted mean angle between each
 * triangle's normal and the original's normal at the closest point of its
 * centroid; RMS distance of the points to the original surface and the
 * symmetric Hausdorff distance, in % of the original's bounding-box diagonal;
 * volume change in %; triangles whose orientation flipped.
 */
#include "vtkPolyDataShockSharpenFilter.h"

#include "vtkCellArray.h"
#include "vtkCellLocator.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkGenericCell.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkLogger.h"
#include "vtkMassProperties.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmoothPolyDataFilter.h"
#include "vtkSmartPointer.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace
{
using Mesh = vtkSmartPointer<vtkPolyData>;
using Occupied = std::function<bool(int, int, int)>;

/// Closed surface of the occupied cells of an nx x ny x nz grid of cell size h, centred at 0.
Mesh BlockSurface(int nx, int ny, int nz, double h, const Occupied& occupied)
{
  auto inside = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && occupied(i, j, k);
  };
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  std::map<std::array<int, 3>, vtkIdType> ids;
  auto id = [&](int i, int j, int k) {
    const std::array<int, 3> key{ i, j, k };
    auto found = ids.find(key);
    if (found != ids.end())
    {
      return found->second;
    }
    const vtkIdType n = points->InsertNextPoint((i - 0.5 * nx) * h, (j - 0.5 * ny) * h, (k - 0.5 * nz) * h);
    ids.emplace(key, n);
    return n;
  };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
      {
        if (!inside(i, j, k))
        {
          continue;
        }
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side)
          {
            int d[3] = { 0, 0, 0 };
            d[axis] = side ? 1 : -1;
            if (inside(i + d[0], j + d[1], k + d[2]))
            {
              continue;
            }
            // The face's corners, counter-clockwise seen from outside.
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            int corner[4][3];
            const int order[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
            for (int c = 0; c < 4; ++c)
            {
              int g[3] = { i, j, k };
              g[axis] += side;
              g[u] += order[side ? c : 3 - c][0];
              g[v] += order[side ? c : 3 - c][1];
              std::copy(g, g + 3, corner[c]);
            }
            vtkIdType q[4];
            for (int c = 0; c < 4; ++c)
            {
              q[c] = id(corner[c][0], corner[c][1], corner[c][2]);
            }
            const vtkIdType t0[3] = { q[0], q[1], q[2] }, t1[3] = { q[0], q[2], q[3] };
            triangles->InsertNextCell(3, t0);
            triangles->InsertNextCell(3, t1);
          }
      }
  auto mesh = Mesh::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

/// A copy of `mesh` on the box [-a, a] grown by a ball of radius r (a = half size - r).
Mesh Rounded(vtkPolyData* mesh, const double half[3], double r)
{
  auto out = Mesh::New();
  out->DeepCopy(mesh);
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    double x[3], nearest[3], away[3];
    out->GetPoint(p, x);
    for (int k = 0; k < 3; ++k)
    {
      nearest[k] = std::clamp(x[k], -(half[k] - r), half[k] - r);
      away[k] = x[k] - nearest[k];
    }
    const double d = std::sqrt(away[0] * away[0] + away[1] * away[1] + away[2] * away[2]);
    for (int k = 0; k < 3 && d > 0.0; ++k)
    {
      x[k] = nearest[k] + r / d * away[k];
    }
    out->GetPoints()->SetPoint(p, x);
  }
  return out;
}

/// Windowed-sinc smoothing (features not preserved): blurs every crease.
Mesh Blurred(vtkPolyData* mesh, int iterations, double passBand)
{
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputData(mesh);
  smooth->SetNumberOfIterations(iterations);
  smooth->SetPassBand(passBand);
  smooth->NormalizeCoordinatesOn();
  smooth->FeatureEdgeSmoothingOff();
  smooth->BoundarySmoothingOff();
  smooth->Update();
  return smooth->GetOutput();
}

double Diagonal(vtkPolyData* mesh)
{
  double b[6];
  mesh->GetBounds(b);
  return std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
}

double Volume(vtkPolyData* mesh)
{
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  return mass->GetVolume();
}

void TriangleNormal(vtkPolyData* mesh, vtkIdType c, double n[3], double* centroid = nullptr)
{
  const vtkIdType* ids;
  vtkIdType count;
  mesh->GetCellPoints(c, count, ids);
  double a[3], b[3], d[3];
  mesh->GetPoint(ids[0], a);
  mesh->GetPoint(ids[1], b);
  mesh->GetPoint(ids[2], d);
  vtkTriangle::ComputeNormal(a, b, d, n);
  if (centroid)
  {
    for (int k = 0; k < 3; ++k)
    {
      centroid[k] = (a[k] + b[k] + d[k]) / 3.0;
    }
  }
}

struct Measures
{
  double normalError = 0.0; ///< degrees
  double rms = 0.0;         ///< % of the diagonal
  double hausdorff = 0.0;   ///< % of the diagonal
  double volume = 0.0;      ///< % change
  long long flipped = 0;
};

/// Largest and RMS distance from the points of `from` to the surface of `to`.
void Distances(vtkPolyData* from, vtkPolyData* to, double& largest, double& rms)
{
  vtkNew<vtkCellLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  largest = 0.0;
  double sum = 0.0;
  for (vtkIdType p = 0; p < from->GetNumberOfPoints(); ++p)
  {
    double x[3], closest[3], d2;
    vtkIdType c;
    int sub;
    from->GetPoint(p, x);
    locator->FindClosestPoint(x, closest, cell, c, sub, d2);
    largest = std::max(largest, std::sqrt(d2));
    sum += d2;
  }
  rms = std::sqrt(sum / std::max<vtkIdType>(1, from->GetNumberOfPoints()));
}

Measures Measure(vtkPolyData* result, vtkPolyData* original)
{
  Measures m;
  const double diagonal = Diagonal(original);
  vtkNew<vtkCellLocator> locator;
  locator->SetDataSet(original);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  double angleSum = 0.0, areaSum = 0.0;
  for (vtkIdType c = 0; c < result->GetNumberOfCells(); ++c)
  {
    double n[3], centroid[3], closest[3], d2, reference[3];
    TriangleNormal(result, c, n, centroid);
    vtkIdType at;
    int sub;
    locator->FindClosestPoint(centroid, closest, cell, at, sub, d2);
    TriangleNormal(original, at, reference);
    const double area = vtkTriangle::SafeDownCast(result->GetCell(c))->ComputeArea();
    const double cosine = std::clamp(n[0] * reference[0] + n[1] * reference[1] + n[2] * reference[2], -1.0, 1.0);
    angleSum += area * std::acos(cosine) * 180.0 / 3.14159265358979323846;
    areaSum += area;
  }
  m.normalError = angleSum / areaSum;
  double there, back, rms, unused;
  Distances(result, original, there, rms);
  Distances(original, result, back, unused);
  m.rms = 100.0 * rms / diagonal;
  m.hausdorff = 100.0 * std::max(there, back) / diagonal;
  m.volume = 100.0 * (Volume(result) / Volume(original) - 1.0);
  return m;
}

struct Shape
{
  std::string name;
  Mesh input;
  Mesh original;
};

std::vector<Shape> RecoveryShapes()
{
  const double h = 1.0 / 24.0;
  auto all = [](int, int, int) { return true; };
  // CAD-like: an L-shaped block with a slot through its long leg (convex and concave creases).
  auto block = [](int i, int j, int k) {
    const bool l = i < 12 || j < 10;
    const bool slot = i >= 20 && i < 26 && k >= 6;
    return l && !slot;
  };
  const Mesh cube = BlockSurface(24, 24, 24, h, all);
  const Mesh box = BlockSurface(38, 24, 19, h, all);
  const Mesh cad = BlockSurface(32, 24, 14, h, block);
  const double cubeHalf[3] = { 0.5, 0.5, 0.5 };
  const double boxHalf[3] = { 19 * h, 12 * h, 9.5 * h };
  return { { "rounded cube (r = 0.15)", Rounded(cube, cubeHalf, 0.15), cube },
    { "rounded box (r = 0.12)", Rounded(box, boxHalf, 0.12), box },
    { "blurred box (windowed sinc)", Blurred(box, 20, 0.005), box },
    { "blurred CAD block (windowed sinc)", Blurred(cad, 20, 0.005), cad } };
}

Mesh Sharpen(vtkPolyData* input, double time, double weight, bool exact, int target, double featureAngle,
  long long* flipped = nullptr)
{
  vtkNew<vtkPolyDataShockSharpenFilter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(time);
  filter->SetScreeningWeight(weight);
  if (exact)
  {
    filter->SetSolverToExact();
  }
  filter->SetFitTarget(target);
  filter->SetFeatureAngle(featureAngle);
  filter->Update();
  if (flipped)
  {
    *flipped = filter->GetLastFlippedTriangles();
  }
  return filter->GetOutput();
}

void PrintMeasures(const Measures& m)
{
  std::printf(" %.2f | %.3f | %.2f | %+.2f | %lld |", m.normalError, m.rms, m.hausdorff, m.volume, m.flipped);
}

void Recovery(const std::vector<double>& times, const std::vector<double>& weights)
{
  std::printf("| shape | t | eps | solver | fit target | normal error (deg) | RMS (%% diag) | Hausdorff "
              "(%% diag) | volume (%%) | flipped |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Shape& shape : RecoveryShapes())
  {
    std::printf("| %s (%lld triangles) | input | | | |", shape.name.c_str(),
      static_cast<long long>(shape.input->GetNumberOfCells()));
    PrintMeasures(Measure(shape.input, shape.original));
    std::printf("\n");
    static const char* names[] = { "Projection", "Rotation", "Shear", "CentralProjection" };
    for (double t : times)
      for (double eps : weights)
        for (bool exact : { false, true })
          for (int target : { vtkPolyDataShockSharpenFilter::PROJECTION, vtkPolyDataShockSharpenFilter::ROTATION,
                 vtkPolyDataShockSharpenFilter::SHEAR, vtkPolyDataShockSharpenFilter::CENTRAL_PROJECTION })
          {
            std::printf("| | %g | %g | %s | %s |", t, eps, exact ? "exact" : "CG 25", names[target]);
            long long flipped = 0;
            const Mesh out = Sharpen(shape.input, t, eps, exact, target, 30.0, &flipped);
            Measures m = Measure(out, shape.original);
            m.flipped = flipped;
            PrintMeasures(m);
            std::printf("\n");
            std::fflush(stdout);
          }
  }
}

/// A coarse box subdivided 4 times and smoothed by 300 Laplacian passes (what ParaView's Smooth does).
Shape LaplacianBox()
{
  vtkNew<vtkCubeSource> box;
  box->SetXLength(1.6);
  box->SetYLength(1.0);
  box->SetZLength(0.8);
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputConnection(box->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(clean->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(4);
  subdivide->Update();
  Mesh original = subdivide->GetOutput();
  vtkNew<vtkSmoothPolyDataFilter> smooth;
  smooth->SetInputData(original);
  smooth->SetNumberOfIterations(300);
  smooth->Update();
  return { "Laplacian-smoothed box (300 passes)", smooth->GetOutput(), original };
}

/// The rounded and blurred shapes at several feature angles (180: none): blurred creases still sharpen.
void Features()
{
  using Target = vtkPolyDataShockSharpenFilter;
  std::printf("| shape | FeatureAngle | FitTarget | feature edges | normal error (deg) | RMS (%% diag) | Hausdorff (%% diag) | "
              "volume (%%) | flipped |\n|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Shape> shapes = RecoveryShapes();
  shapes.push_back(LaplacianBox());
  for (const Shape& shape : shapes)
  {
    std::printf("| %s | input | | |", shape.name.c_str());
    PrintMeasures(Measure(shape.input, shape.original));
    std::printf("\n");
    // FeatureAngle with the default fit; then the other fits at FeatureAngle 30 and the paper's.
    const std::vector<std::pair<double, int>> runs = { { 30.0, Target::CENTRAL_PROJECTION },
      { 45.0, Target::CENTRAL_PROJECTION }, { 60.0, Target::CENTRAL_PROJECTION },
      { 180.0, Target::CENTRAL_PROJECTION }, { 30.0, Target::SHEAR }, { 30.0, Target::ROTATION },
      { 180.0, Target::PROJECTION } };
    for (auto [angle, target] : runs)
    {
      vtkNew<vtkPolyDataShockSharpenFilter> filter;
      filter->SetInputData(shape.input);
      filter->SetFitTarget(target);
      filter->SetFlowTime(shape.name.rfind("Laplacian", 0) == 0 ? 256.0 : 1024.0); // a lighter blur
      filter->SetFeatureAngle(angle);
      filter->Update();
      Measures m = Measure(filter->GetOutput(), shape.original);
      m.flipped = filter->GetLastFlippedTriangles();
      static const char* names[] = { "Projection", "Rotation", "Shear", "CentralProjection" };
      std::printf("| | %g | %s | %lld |", angle, names[target], static_cast<long long>(filter->GetLastFeatureEdges()));
      PrintMeasures(m);
      std::printf("\n");
    }
  }
}

Mesh Cleaned(vtkAlgorithm* source, int linearSubdivisions)
{
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  clean->Update();
  Mesh mesh = clean->GetOutput();
  if (linearSubdivisions > 0)
  {
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputData(mesh);
    subdivide->SetNumberOfSubdivisions(linearSubdivisions);
    subdivide->Update();
    mesh = subdivide->GetOutput();
  }
  return mesh;
}

/// Largest displacement of an already sharp shape at default settings, % of its diagonal.
void Sharp()
{
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkCylinderSource> hexagon; // ParaView's Cylinder(): resolution 6, capped
  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetResolution(32);
  const double h = 1.0 / 24.0;
  auto block = [](int i, int j, int k) { return (i < 12 || j < 10) && !(i >= 20 && i < 26 && k >= 6); };
  const std::vector<std::pair<std::string, Mesh>> shapes = { { "vtkCubeSource, triangulated, cleaned", Cleaned(cube, 0) },
    { "the cube linearly subdivided 3 times", Cleaned(cube, 3) },
    { "capped cylinder, resolution 6, subdivided twice", Cleaned(hexagon, 2) },
    { "capped cylinder, resolution 32, subdivided twice", Cleaned(cylinder, 2) },
    { "CAD block (sharp)", BlockSurface(32, 24, 14, h, block) } };
  std::printf("| shape | triangles | FeatureAngle 180, Projection, CurvatureContrast 0 (the paper) | 180, "
              "CentralProjection | 30, Projection | 30, CentralProjection (default) |\n|---|---|---|---|---|---|\n");
  for (const auto& shape : shapes)
  {
    std::printf("| %s | %lld |", shape.first.c_str(), static_cast<long long>(shape.second->GetNumberOfCells()));
    for (double angle : { 180.0, 30.0 })
      for (int target : { vtkPolyDataShockSharpenFilter::PROJECTION, vtkPolyDataShockSharpenFilter::CENTRAL_PROJECTION })
      {
        vtkNew<vtkPolyDataShockSharpenFilter> filter;
        filter->SetInputData(shape.second);
        filter->SetFeatureAngle(angle);
        filter->SetFitTarget(target);
        if (angle == 180.0 && target == vtkPolyDataShockSharpenFilter::PROJECTION)
        {
          filter->SetCurvatureContrast(0.0); // the paper's potential
          filter->SetAnchorWeight(0.0);      // and fit
          filter->SetDriftRadius(0.0);
          filter->KeepUnmovedNormalsOff();
        }
        filter->Update();
        std::printf(" %.3f %% |", 100.0 * filter->GetLastMaxDisplacement());
      }
    std::printf("\n");
  }
}
} // namespace

int main(int argc, char* argv[])
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING); // the filter logs each run at INFO
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "recovery")
  {
    Recovery({ 256.0, 1024.0, 4096.0 }, { 0.1, 1.0, 10.0 });
  }
  else if (mode == "summary")
  {
    Recovery({ 1024.0 }, { 1.0 });
  }
  else if (mode == "features")
  {
    Features();
  }
  else if (mode == "sharp")
  {
    Sharp();
  }
  else
  {
    std::fprintf(stderr, "usage: sharpenbench recovery|summary|features|sharp\n");
    return 2;
  }
  return 0;
}
