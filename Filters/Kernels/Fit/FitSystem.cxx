#include "FitSystem.h"

#include "FitOperators.h"
#include "FitSolve.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>

namespace shock
{

namespace
{
using fit::Coordinates;
using fit::Frame;
using fit::RowMatrix;

/// Area and area-weighted centroid of the (owned) triangles: the unit-area normalisation.
Frame UnitAreaFrame(const TriangleMesh& mesh, const MeshPartition* partition, int threads)
{
  // A ghost triangle is added by its owner.
  const auto total = fit::BlockSums<4>(mesh.NumberOfTriangles(), threads,
    partition ? &partition->ownedTriangles : nullptr, partition,
    [&](std::int64_t f, std::array<double, 4>& sum) {
      const double a = mesh.Area(f); // 0 for degenerate triangles
      const Vec3 c = mesh.Centroid(f);
      sum[0] += a;
      for (int k = 0; k < 3; ++k)
      {
        sum[k + 1] += a * c[k];
      }
    });
  Frame frame;
  if (total[0] > 0.0)
  {
    frame.scale = 1.0 / std::sqrt(total[0]);
    for (int k = 0; k < 3; ++k)
    {
      frame.center[k] = total[k + 1] / total[0];
    }
  }
  return frame;
}

/// Corner of non-degenerate triangle f at point p.
inline int CornerOf(const TriangleMesh& mesh, std::int64_t f, std::int64_t p)
{
  const std::int64_t* t = mesh.Corners(f);
  return t[0] == p ? 0 : (t[1] == p ? 1 : 2);
}

/**
 * The points in the order in which the triangles first use them (corner by
 * corner), then the points no non-degenerate triangle uses, in their order:
 * the order in which the assembly visits the rows, so that it reads the
 * triangles' data nearly in their order.
 */
std::vector<std::int64_t> FirstUseOrder(const TriangleMesh& mesh, int threads)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const std::int64_t nt = mesh.NumberOfTriangles();
  const CompressedLists& around = mesh.PointTriangles();
  std::vector<std::int64_t> first(static_cast<size_t>(np), -1); // 3 f + corner
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t p = 0; p < np; ++p)
  {
    std::int64_t key = -1;
    for (std::int64_t a = around.Begin(p); a < around.End(p); ++a)
    {
      const std::int64_t f = around.items[static_cast<size_t>(a)];
      if (!mesh.Degenerate(f) && (key < 0 || 3 * f < key))
      {
        key = 3 * f + CornerOf(mesh, f, p);
      }
    }
    first[static_cast<size_t>(p)] = key;
  }
  std::vector<std::int64_t> start(static_cast<size_t>(nt) + 1, 0); // rows before triangle f's
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      start[static_cast<size_t>(f) + 1] += first[static_cast<size_t>(mesh.Corners(f)[c])] == 3 * f + c;
    }
  }
  for (std::int64_t f = 0; f < nt; ++f)
  {
    start[static_cast<size_t>(f) + 1] += start[static_cast<size_t>(f)];
  }
  std::vector<std::int64_t> order(static_cast<size_t>(np));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t f = 0; f < nt; ++f)
  {
    std::int64_t row = start[static_cast<size_t>(f)];
    for (int c = 0; c < 3; ++c)
    {
      const std::int64_t p = mesh.Corners(f)[c];
      if (first[static_cast<size_t>(p)] == 3 * f + c)
      {
        order[static_cast<size_t>(row++)] = p;
      }
    }
  }
  std::int64_t row = start.back();
  for (std::int64_t p = 0; p < np; ++p)
  {
    if (first[static_cast<size_t>(p)] < 0)
    {
      order[static_cast<size_t>(row++)] = p;
    }
  }
  return order;
}

/**
 * The rows' points in breadth-first order over the one-rings, component by
 * component from its smallest point (neighbours in ring order). Every row's
 * columns are then within about two fronts of it, so the conjugate gradients'
 * products read nearby memory. Serial: a few milliseconds per million points.
 */
void BreadthFirstOrder(const TriangleMesh& mesh, FitSystemData& system)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const CompressedLists& ring = mesh.OneRing();
  system.order.clear();
  system.order.reserve(static_cast<size_t>(np));
  system.rank.assign(static_cast<size_t>(np), -1);
  for (std::int64_t seed = 0; seed < np; ++seed)
  {
    if (system.rank[static_cast<size_t>(seed)] >= 0)
    {
      continue;
    }
    system.rank[static_cast<size_t>(seed)] = static_cast<std::int64_t>(system.order.size());
    system.order.push_back(seed);
    for (size_t next = system.order.size() - 1; next < system.order.size(); ++next)
    {
      // The queue is known ahead: ask for the ranks of the ring of a point a few
      // places on, whose loads are scattered over the rank array.
      if (next + 8 < system.order.size())
      {
        const std::int64_t ahead = system.order[next + 8];
        for (std::int64_t e = ring.Begin(ahead); e < ring.End(ahead); ++e)
        {
          __builtin_prefetch(&system.rank[static_cast<size_t>(ring.items[static_cast<size_t>(e)])]);
        }
      }
      else if (next + 2 < system.order.size())
      {
        const std::int64_t ahead = system.order[next + 2];
        __builtin_prefetch(&ring.items[static_cast<size_t>(ring.Begin(ahead))]);
      }
      const std::int64_t p = system.order[next];
      for (std::int64_t e = ring.Begin(p); e < ring.End(p); ++e)
      {
        const std::int64_t q = ring.items[static_cast<size_t>(e)];
        if (system.rank[static_cast<size_t>(q)] < 0)
        {
          system.rank[static_cast<size_t>(q)] = static_cast<std::int64_t>(system.order.size());
          system.order.push_back(q);
        }
      }
    }
  }
}

/// Rows in the points' own order (a piece of a distributed mesh).
void IdentityOrder(std::int64_t np, FitSystemData& system)
{
  system.order.resize(static_cast<size_t>(np));
  for (std::int64_t p = 0; p < np; ++p)
  {
    system.order[static_cast<size_t>(p)] = p;
  }
  system.rank = system.order;
  system.visit = system.order;
}

/**
 * The compressed-row pattern: row r holds its point's one-ring and itself, as
 * rows (sorted). Built in parallel straight from the mesh's adjacency.
 */
void BuildPattern(const TriangleMesh& mesh, int threads, FitSystemData& system)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const CompressedLists& ring = mesh.OneRing();
  RowMatrix& A = system.matrix;
  A.resize(static_cast<Eigen::Index>(np), static_cast<Eigen::Index>(np));
  A.resizeNonZeros(static_cast<Eigen::Index>(np + static_cast<std::int64_t>(ring.items.size())));
  int* outer = A.outerIndexPtr();
  // The rows' sizes in parallel (their points are scattered), then their sum in sequence.
  outer[0] = 0;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < np; ++r)
  {
    const std::int64_t p = system.order[static_cast<size_t>(r)];
    outer[r + 1] = static_cast<int>(ring.End(p) - ring.Begin(p) + 1);
  }
  for (std::int64_t r = 0; r < np; ++r)
  {
    outer[r + 1] += outer[r];
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < np; ++i)
  {
    const std::int64_t p = system.visit[static_cast<size_t>(i)];
    const std::int64_t r = system.rank[static_cast<size_t>(p)];
    int* cols = A.innerIndexPtr() + outer[r];
    int* out = cols;
    *out++ = static_cast<int>(r);
    for (std::int64_t e = ring.Begin(p); e < ring.End(p); ++e)
    {
      *out++ = static_cast<int>(system.rank[static_cast<size_t>(ring.items[static_cast<size_t>(e)])]);
    }
    std::sort(cols, out);
  }
}

/// The target gradients of the triangles last asked for, by triangle modulo its size.
class TargetGradientCache
{
public:
  TargetGradientCache()
    : tags(Size, -1)
    , gradients(9 * Size)
  {
  }
  /// fit::TargetGradients of triangle f (computed on a miss).
  const double* Get(const TriangleMesh& mesh, const fit::Targets& targets, std::int64_t f)
  {
    const size_t slot = static_cast<size_t>(f) & (Size - 1);
    double* w = &this->gradients[9 * slot];
    if (this->tags[slot] != f)
    {
      fit::TargetGradients(mesh, targets.normals, targets.target, f, w);
      this->tags[slot] = f;
    }
    return w;
  }

private:
  static constexpr size_t Size = 4096;
  std::vector<std::int64_t> tags;
  std::vector<double> gradients;
};

/**
 * The row of point p while FillRows assembles it: its columns and values
 * (zeroed on construction), the slot of a point's entry, and the sums of its
 * mass term and divergence. A corner's entry: in a usual row (a one-ring: a
 * few points, whose rows are near this one) its point among the row's, found
 * without a branch to mispredict; in a long row (a point joined to thousands,
 * as a fan's centre) by a binary search of its column, or the row would cost
 * its length squared.
 */
struct PointRow
{
  static constexpr size_t ShortRow = 32;
  const std::vector<std::int64_t>& rank;
  const std::vector<std::int64_t>& points; ///< the points of the columns (of a short row)
  std::int64_t r;                          ///< the row
  const int* cols;
  double* values;
  size_t count;
  bool shortRow;
  size_t self = 0;                                ///< the slot of p's own entry
  double b[3] = { 0.0, 0.0, 0.0 };                ///< the mass term alpha M c0
  double divergence[3] = { 0.0, 0.0, 0.0 };       ///< D w (with targets)
  bool fitted = false;                            ///< a non-degenerate triangle has p

  /// p's row of the system's matrix, zeroed; `scratch` holds its columns' points.
  SHOCK_ALWAYS_INLINE PointRow(FitSystemData& system, std::int64_t p, std::vector<std::int64_t>& scratch)
    : rank(system.rank)
    , points(scratch)
    , r(system.rank[static_cast<size_t>(p)])
  {
    RowMatrix& A = system.matrix;
    this->cols = A.innerIndexPtr() + A.outerIndexPtr()[this->r];
    this->count = static_cast<size_t>(A.outerIndexPtr()[this->r + 1] - A.outerIndexPtr()[this->r]);
    this->values = A.valuePtr() + A.outerIndexPtr()[this->r];
    std::fill(this->values, this->values + this->count, 0.0);
    this->shortRow = this->count <= ShortRow;
    scratch.resize(this->shortRow ? this->count : 0);
    for (size_t k = 0; k < scratch.size(); ++k)
    {
      scratch[k] = system.order[static_cast<size_t>(this->cols[k])];
    }
    this->self = this->SlotOf(p);
  }

  /// The slot of `point`'s entry in the row.
  SHOCK_ALWAYS_INLINE size_t SlotOf(std::int64_t point) const
  {
    if (!this->shortRow)
    {
      const int column = static_cast<int>(this->rank[static_cast<size_t>(point)]);
      return static_cast<size_t>(std::lower_bound(this->cols, this->cols + this->count, column) - this->cols);
    }
    size_t slot = 0;
    for (size_t k = 0; k < this->count; ++k)
    {
      slot = this->points[k] == point ? k : slot;
    }
    return slot;
  }
};

/**
 * The terms of the non-degenerate triangles around p in p's row: per corner,
 * alpha s^2 times the mass and beta times the stiffness, the mass term's share
 * of the corner's original position and, with targets, the divergence of the
 * target gradients.
 */
SHOCK_ALWAYS_INLINE void AddTriangleTerms(const TriangleMesh& mesh, const FitSystemData& system,
  const fit::Targets* targets, TargetGradientCache& cache, std::int64_t p, PointRow& pointRow)
{
  const CompressedLists& around = mesh.PointTriangles();
  const double s = system.frame.scale;
  const int* cols = pointRow.cols;
  double* row = pointRow.values;
  const size_t self = pointRow.self;
  for (std::int64_t a = around.Begin(p); a < around.End(p); ++a)
  {
    const std::int64_t f = around.items[static_cast<size_t>(a)];
    if (mesh.Degenerate(f))
    {
      continue;
    }
    pointRow.fitted = true;
    const std::int64_t* t = mesh.Corners(f);
    const int corner = CornerOf(mesh, f, p);
    const double area = mesh.Area(f);
    const Vec3 gp = Load(mesh.HatGradient(f, corner));
    if (targets)
    {
      fit::AddDivergence(mesh, f, gp.data(), cache.Get(mesh, *targets, f), pointRow.divergence);
    }
    for (int c = 0; c < 3; ++c)
    {
      const double mass = system.alpha * s * s * TriangleMass(area, corner, c);
      const size_t slot = c == corner ? self : pointRow.SlotOf(t[c]);
      row[slot] += mass + system.beta * area * Dot(gp, Load(mesh.HatGradient(f, c)));
      for (int k = 0; k < 3; ++k)
      {
        pointRow.b[k] += mass * system.original(cols[slot], k);
      }
    }
  }
}

/**
 * The end of a row: an identity row when nothing constrains its point, then
 * its flag, inverse diagonal and mass term and, with targets, its right-hand
 * side b + weight D w.
 */
SHOCK_ALWAYS_INLINE void FinishRow(FitSystemData& system, const fit::Targets* targets, double weight,
  PointRow& pointRow, Coordinates& rhs)
{
  const std::int64_t r = pointRow.r;
  double* row = pointRow.values;
  double* b = pointRow.b;
  if (!pointRow.fitted)
  {
    row[pointRow.self] = 1.0; // nothing constrains the point: an identity row keeps it where it is
    for (int k = 0; k < 3; ++k)
    {
      b[k] = system.original(r, k);
    }
  }
  system.fitted[static_cast<size_t>(r)] = pointRow.fitted ? 1 : 0;
  system.inverseDiagonal[static_cast<size_t>(r)] = 1.0 / row[pointRow.self]; // > 0: M's diagonal is
  for (int k = 0; k < 3; ++k)
  {
    system.massTerm(r, k) = b[k];
    if (targets)
    {
      rhs(r, k) = b[k] + weight * pointRow.divergence[k];
    }
  }
}

/**
 * The values of A = alpha M + beta S (normalised: stiffness A g.g, mass s^2 A/12),
 * the mass term alpha M c0 and the inverse diagonal, row by row in parallel;
 * with targets, also the right-hand sides b = alpha M c0 + beta s D w (the
 * same sums as fit::RightHandSides). A point used by no non-degenerate
 * triangle gets an identity row that keeps it.
 */
void FillRows(const TriangleMesh& mesh, int threads, const fit::Targets* targets,
  FitSystemData& system, Coordinates& rhs)
{
  const std::int64_t np = mesh.NumberOfPoints();
  const double s = system.frame.scale;
  system.massTerm.resize(np, 3);
  system.inverseDiagonal.resize(static_cast<size_t>(np));
  system.fitted.assign(static_cast<size_t>(np), 0);
  system.baseDiagonal.clear(); // taken from the diagonal by the first anchor
  system.anchored = false;
  rhs.resize(targets ? np : 0, 3);
  const double weight = system.beta * s;
#pragma omp parallel num_threads(threads)
  {
    // Each triangle's target gradients serve its three corners' rows, which the
    // visit order reaches at nearby times: kept in a small direct-mapped cache.
    TargetGradientCache cache;
    std::vector<std::int64_t> points; // the points of a row's columns
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < np; ++i)
    {
      const std::int64_t p = system.visit[static_cast<size_t>(i)];
      PointRow pointRow(system, p, points);
      AddTriangleTerms(mesh, system, targets, cache, p, pointRow);
      FinishRow(system, targets, weight, pointRow, rhs);
    }
  }
}
Status BuildSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, const fit::Targets* targets, FitSystem& system,
  Coordinates& b, bool rowsInMeshOrder);
} // namespace

Status BuildFitSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, FitSystem& system, bool rowsInMeshOrder)
{
  Coordinates none;
  return BuildSystem(mesh, screeningWeight, partition, threads, nullptr, system, none, rowsInMeshOrder);
}

Status fit::BuildFitSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, const Targets& targets, FitSystem& system,
  Coordinates& b, bool rowsInMeshOrder)
{
  return BuildSystem(mesh, screeningWeight, partition, threads, &targets, system, b, rowsInMeshOrder);
}

namespace
{
Status BuildSystem(const TriangleMesh& mesh, double screeningWeight,
  const MeshPartition* partition, int threads, const fit::Targets* targets, FitSystem& system,
  Coordinates& b, bool rowsInMeshOrder)
{
  system.Clear();
  if (!(std::isfinite(screeningWeight) && screeningWeight > 0.0))
  {
    return { "the screening weight must be finite and > 0" };
  }
  auto data = std::make_shared<FitSystemData>();
  const std::int64_t np = mesh.NumberOfPoints();
  if (partition || rowsInMeshOrder)
  {
    data->frame = UnitAreaFrame(mesh, partition, threads);
    IdentityOrder(np, *data);
  }
  else
  {
    // The breadth-first order is serial: meanwhile another thread finds the
    // normalisation and the assembly's visiting order, which do not depend on
    // it (nor their results on the number of threads).
#pragma omp parallel sections num_threads(std::min(threads, 2))
    {
#pragma omp section
      BreadthFirstOrder(mesh, *data);
#pragma omp section
      {
        data->frame = UnitAreaFrame(mesh, nullptr, std::max(1, threads - 1));
        data->visit = FirstUseOrder(mesh, std::max(1, threads - 1));
      }
    }
  }
  if (data->frame.scale > 0.0)
  {
    // A = alpha M + beta S and b = alpha M c0 + beta D w have the solution of
    // (eps M + S) c = eps M c0 + D w; dividing by max(1, eps) keeps every entry
    // bounded, so any finite eps > 0 is safe from overflow.
    data->alpha = std::min(screeningWeight, 1.0);
    data->beta = 1.0 / std::max(screeningWeight, 1.0);
    data->original.resize(np, 3);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t r = 0; r < np; ++r)
    {
      const double* x = mesh.Point(data->order[static_cast<size_t>(r)]);
      for (int k = 0; k < 3; ++k)
      {
        data->original(r, k) = data->frame.scale * (x[k] - data->frame.center[k]);
      }
    }
    BuildPattern(mesh, threads, *data);
    FillRows(mesh, threads, targets, *data, b);
    system.data = std::move(data);
  }
  system.mesh = &mesh;
  system.points = mesh.NumberOfPoints();
  system.triangles = mesh.NumberOfTriangles();
  system.screeningWeight = screeningWeight;
  system.rowsInMeshOrder = rowsInMeshOrder;
  return {};
}
} // namespace

} // namespace shock
