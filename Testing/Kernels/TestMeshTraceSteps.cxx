// The mesh tracer and the advection of Appendix A (Trace, AdvectVertices,
// AdvectFaces, the Naive and Composed flows) against independent computations
// on small irregular meshes (TestMeshSteps.h).
#include "TestMeshSteps.h"

namespace
{
using namespace shock;
using namespace meshsteps;


TEST(MeshSteps, TraceCrossesAnEdgeIntoTheUnfoldedNextTriangle)
{
  // B leans back over A, so its flow away from the edge makes an obtuse angle
  // with A's flow in space, but an acute one once B is unfolded into A's plane:
  // the paper's <v, v0> > 0 is read in the unfolded frame, and the trace goes on.
  SmallMesh m = meshsteps::Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 });
  const V3 vB = Add(into, { 0.0, 0.2, 0.0 });
  std::vector<double> velocity = { 1.0, 0.0, 0.0, vB[0], vB[1], vB[2] };
  ASSERT_LT(Dot3(vB, { 1.0, 0.0, 0.0 }), 0.0);
  AdvectionParameters p;
  p.tracing = Tracing::FaceCrossing;
  SurfacePoint q;
  q.triangle = 0;
  const V3 start = Position(m, q); // the centre of A: (-1/3, 1, 0)
  TraceOnMesh(m.mesh, velocity.data(), q, 0.6, p);
  ASSERT_EQ(q.triangle, 1);
  // 1/3 to reach the edge, then 0.6 - 1/3 along B's flow.
  const V3 expected = Add(Add(start, { 1.0 / 3.0, 0.0, 0.0 }), Mul(0.6 - 1.0 / 3.0, vB));
  const V3 x = Position(m, q);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(x[k], expected[k], 1e-12);
}

TEST(MeshSteps, TraceStopsWhereTheUnfoldedFlowReverses)
{
  SmallMesh m = meshsteps::Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 });
  // B pushes back towards the edge: unfolded, against A's flow.
  const V3 vB = Add(Mul(-1.0, into), { 0.0, 0.1, 0.0 });
  std::vector<double> velocity = { 1.0, 0.0, 0.0, vB[0], vB[1], vB[2] };
  ASSERT_GT(Dot3(vB, { 1.0, 0.0, 0.0 }), 0.0); // acute in space
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    AdvectionParameters p;
    p.tracing = tracing;
    p.stepFraction = 0.01;
    SurfacePoint q;
    q.triangle = 0;
    const V3 start = Position(m, q);
    TraceOnMesh(m.mesh, velocity.data(), q, 2.0, p);
    const V3 x = Position(m, q);
    // At the edge x = 0, within one step of it for the stepped trace.
    const double step = tracing == Tracing::Stepped ? 0.01 * m.mesh.MeanEdgeLength() : 1e-12;
    EXPECT_NEAR(x[0], 0.0, step + 1e-12);
    EXPECT_NEAR(x[1], start[1], step + 1e-12);
  }
}

TEST(MeshSteps, TraceSlidesAlongAnEdgeBothTrianglesPushInto)
{
  // A's flow crosses the edge x = 0 at (1, +-1); B's, unfolded into A's plane,
  // is (-0.3, +-0.8): it pushes back into the edge yet makes an acute angle with
  // A's, so the trace neither stops nor enters B. The limit of the stepped
  // zig-zag is the Filippov velocity: the convex combination (1 - w) vA + w vB
  // with no component across the edge, w = 1 / 1.3, along the edge at speed
  // (1 - w) 1 + w 0.8. B leans back over A, so unfolding matters.
  SmallMesh m = meshsteps::Hinge();
  m.Build();
  const V3 into = Mul(1.0 / Norm3({ -0.3, 0.0, 1.0 }), { -0.3, 0.0, 1.0 }); // in B, away from the edge
  // Trace from the centre of A, (-1/3, 1, 0), with A's flow (1, sense, 0) and B's
  // flow `across` along `into` plus `along` along the edge (y): at the edge after 1/3.
  auto trace = [&](double sense, double across, double along, double t) {
    const V3 vB = Add(Mul(across, into), { 0.0, along, 0.0 });
    std::vector<double> velocity = { 1.0, sense, 0.0, vB[0], vB[1], vB[2] };
    AdvectionParameters p;
    p.tracing = Tracing::FaceCrossing;
    SurfacePoint q;
    q.triangle = 0;
    TraceOnMesh(m.mesh, velocity.data(), q, t, p);
    return q;
  };
  const double w = 1.0 / 1.3;
  const double speed = (1.0 - w) * 1.0 + w * 0.8;
  const double t = 0.6;
  for (const double sense : { 1.0, -1.0 })
  {
    const V3 x = Position(m, trace(sense, -0.3, 0.8 * sense, t));
    EXPECT_NEAR(x[0], 0.0, 1e-12) << sense;
    EXPECT_NEAR(x[1], 1.0 + sense / 3.0 + sense * speed * (t - 1.0 / 3.0), 1e-12) << sense;
    EXPECT_NEAR(x[2], 0.0, 1e-12) << sense;
  }
  // B's unfolded flow (-0.3, 0.2) makes an obtuse angle with A's (1, 1)
  // (-0.3 + 0.2 < 0): the flow reverses, the trace stops where it meets the edge.
  const V3 stop = Position(m, trace(1.0, -0.3, 0.2, t));
  EXPECT_NEAR(stop[0], 0.0, 1e-12);
  EXPECT_NEAR(stop[1], 4.0 / 3.0, 1e-12);
  // Where B's unfolded flow leaves the edge (+0.3 instead of -0.3) the trace enters B.
  const SurfacePoint entered = trace(1.0, 0.3, 0.8, t);
  EXPECT_EQ(entered.triangle, 1);
  const V3 expected = Add({ 0.0, 4.0 / 3.0, 0.0 }, Mul(t - 1.0 / 3.0, Add(Mul(0.3, into), { 0.0, 0.8, 0.0 })));
  const V3 x = Position(m, entered);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(x[k], expected[k], 1e-12);
}

TEST(MeshSteps, TraceStopsAtTheBoundaryAndWhenTheTimeIsUsedUp)
{
  SmallMesh m = meshsteps::Hinge();
  m.Build();
  std::vector<double> velocity = { -1.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  AdvectionParameters p;
  SurfacePoint q;
  q.triangle = 0;
  const V3 start = Position(m, q);
  TraceOnMesh(m.mesh, velocity.data(), q, 0.1, p);
  EXPECT_NEAR(Position(m, q)[0], start[0] - 0.1, 1e-12);
  // On to the boundary edge from (0, 0) to (-1, 1) or (-1, 1) to (0, 2): x = -1/3 - s, y = 1.
  TraceOnMesh(m.mesh, velocity.data(), q, 10.0, p);
  EXPECT_EQ(q.triangle, 0);
  EXPECT_NEAR(Position(m, q)[0], -1.0, 1e-12);
}

/// A flat irregular sheet (z = 0) for advection with a uniform velocity.
struct FlatCase
{
  SmallMesh m = Sheet(7, 6, 17, 0.0);
  V3 v{ 0.31, -0.17, 0.0 };
  FlatCase() { m.Build(); }
  static double I(const V3& x, int c) { return c == 0 ? 0.4 * x[0] - 0.9 * x[1] : 1.0 + 0.2 * x[1]; }
  /// Distance from x to the sheet's outer rectangle [0, 6] x [0, 4].
  static double Inside(const V3& x) { return std::min({ x[0], 6.0 - x[0], x[1], 4.0 - x[1] }); }
};

TEST(MeshSteps, AdvectVerticesAveragesTracesFromOffsetsIntoEachTriangle)
{
  // Appendix A AdvectVertices with a uniform back-trace velocity v on a flat
  // sheet: the trace from p's offset into triangle f ends at
  // p + 0.001 (centre(f) - p) + v t, and a linear signal is read exactly there.
  FlatCase flat;
  const SmallMesh& m = flat.m;
  const int C = 2;
  std::vector<double> values(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      values[p * C + c] = FlatCase::I(m.P(p), c);
  std::vector<double> velocity;
  for (int f = 0; f < m.Triangles(); ++f)
    velocity.insert(velocity.end(), flat.v.begin(), flat.v.end());
  const double t = 1.3;
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    AdvectionParameters p;
    p.tracing = tracing;
    const SurfaceTracer tracer(m.mesh, velocity.data(), p, m.mesh.MeanEdgeLength());
    AdvectionReport report;
    const ProgressFunction none;
    AdvectionPass pass{ m.mesh, tracer, t, Sampling::Linear, 1, none, 0.0, 1.0, report };
    const std::vector<unsigned char> valid(m.Points(), 1);
    const MeshSource source{ C, values.data(), nullptr, valid.data() };
    std::vector<double> out(values.size(), 123.0);
    ASSERT_TRUE(AdvectVertices(pass, source, out.data(), nullptr));
    int checked = 0;
    for (int q = 0; q < m.Points(); ++q)
    {
      if (FlatCase::Inside(m.P(q)) < Norm3(flat.v) * t + 0.01)
        continue; // a trace may reach the boundary
      double sum[2] = { 0.0, 0.0 };
      int traces = 0;
      for (int f = 0; f < m.Triangles(); ++f)
      {
        const auto tri = m.T(f);
        if (std::find(tri.begin(), tri.end(), q) == tri.end())
          continue;
        const V3 start = Add(m.P(q), Mul(0.001, Sub(m.Centre(f), m.P(q))));
        const V3 end = Add(start, Mul(t, flat.v));
        for (int c = 0; c < C; ++c)
          sum[c] += FlatCase::I(end, c);
        ++traces;
      }
      for (int c = 0; c < C; ++c)
        EXPECT_NEAR(out[q * C + c], sum[c] / traces, 1e-9) << q;
      ++checked;
    }
    EXPECT_GE(checked, 4);
  }
}

/// The triangle of the flat sheet that holds x (by barycentric signs).
int Holding(const SmallMesh& m, const V3& x)
{
  for (int f = 0; f < m.Triangles(); ++f)
  {
    const auto t = m.T(f);
    const V3 n = Cross3(Sub(m.P(t[1]), m.P(t[0])), Sub(m.P(t[2]), m.P(t[0])));
    bool inside = true;
    for (int e = 0; e < 3; ++e)
    {
      const V3 side = Cross3(Sub(m.P(t[(e + 1) % 3]), m.P(t[e])), Sub(x, m.P(t[e])));
      inside = inside && Dot3(side, n) > 1e-9;
    }
    if (inside)
      return f;
  }
  return -1;
}

TEST(MeshSteps, AdvectFacesReadsTheSignalWhereTheTraceFromTheCentreEnds)
{
  FlatCase flat;
  const SmallMesh& m = flat.m;
  const int C = 2;
  std::vector<double> cells = Random(m.Triangles() * C, 53, 0.0, 1.0);
  std::vector<double> points(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      points[p * C + c] = FlatCase::I(m.P(p), c);
  std::vector<double> velocity;
  for (int f = 0; f < m.Triangles(); ++f)
    velocity.insert(velocity.end(), flat.v.begin(), flat.v.end());
  const double t = 1.1;
  AdvectionParameters p;
  const SurfaceTracer tracer(m.mesh, velocity.data(), p, m.mesh.MeanEdgeLength());
  AdvectionReport report;
  const ProgressFunction none;
  const std::vector<unsigned char> valid(m.Points(), 1);
  const MeshSource source{ C, points.data(), cells.data(), valid.data() };
  std::vector<double> nearest(cells.size()), linear(cells.size());
  AdvectionPass byNearest{ m.mesh, tracer, t, Sampling::Nearest, 1, none, 0.0, 1.0, report };
  ASSERT_TRUE(AdvectFaces(byNearest, source, nearest.data(), nullptr));
  AdvectionPass byLinear{ m.mesh, tracer, t, Sampling::Linear, 1, none, 0.0, 1.0, report };
  ASSERT_TRUE(AdvectFaces(byLinear, source, linear.data(), nullptr));
  int checked = 0;
  for (int f = 0; f < m.Triangles(); ++f)
  {
    const V3 end = Add(m.Centre(f), Mul(t, flat.v));
    const int g = Holding(m, end);
    if (FlatCase::Inside(m.Centre(f)) < Norm3(flat.v) * t + 0.01 || g < 0)
      continue;
    for (int c = 0; c < C; ++c)
    {
      EXPECT_EQ(nearest[f * C + c], cells[g * C + c]) << f;
      EXPECT_NEAR(linear[f * C + c], FlatCase::I(end, c), 1e-9) << f;
    }
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

TEST(MeshSteps, SamplingIsBarycentricOrTheNearestCorner)
{
  SmallMesh m = Sheet(4, 4, 19, 0.5);
  m.Build();
  const int C = 2;
  const auto points = Random(m.Points() * C, 59, 0.0, 1.0);
  std::vector<unsigned char> valid(m.Points(), 1);
  const int f = 4;
  const auto t = m.T(f);
  SurfacePoint q;
  q.triangle = f;
  q.barycentric[0] = 0.2;
  q.barycentric[1] = 0.5;
  q.barycentric[2] = 0.3;
  const MeshSource source{ C, points.data(), nullptr, valid.data() };
  for (int c = 0; c < C; ++c)
  {
    double linear[2] = { 0.0, 0.0 };
    ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Linear, source, linear));
    EXPECT_NEAR(linear[c],
      0.2 * points[t[0] * C + c] + 0.5 * points[t[1] * C + c] + 0.3 * points[t[2] * C + c], 1e-14);
  }
  // Nearest: the corner closest in space (not the largest coordinate: the triangle is irregular).
  const V3 x = Position(m, q);
  int closest = 0;
  for (int k = 1; k < 3; ++k)
    if (Norm3(Sub(x, m.P(t[k]))) < Norm3(Sub(x, m.P(t[closest]))))
      closest = k;
  double nearest[2] = { 0.0, 0.0 };
  ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Nearest, source, nearest));
  EXPECT_EQ(nearest[1], points[t[closest] * C + 1]);
  // An invalid corner is left out and the others renormalised.
  valid[t[1]] = 0;
  double partial[2] = { 0.0, 0.0 };
  ASSERT_TRUE(SampleSurface(m.mesh, q, Sampling::Linear, source, partial));
  EXPECT_NEAR(partial[0], (0.2 * points[t[0] * C] + 0.3 * points[t[2] * C]) / 0.5, 1e-14);
}

std::vector<double> FilterMesh(const SmallMesh& m, const std::vector<double>& values, int C,
  const AdvectionParameters& p, double valueScale = 0.0)
{
  MeshSignal signal;
  signal.components = C;
  signal.values = values.data();
  signal.valueScale = valueScale;
  std::vector<double> out(values.size());
  EXPECT_TRUE(AdvectMeshSignal(m.mesh, signal, out.data(), p).Ok());
  return out;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

std::vector<double> StepSignal(const SmallMesh& m, int C)
{
  std::vector<double> v(m.Points() * C);
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      v[p * C + c] = std::tanh(2.0 * (m.P(p)[0] - 3.0 + 0.5 * c + 0.3 * m.P(p)[1])) + 0.2 * c;
  return v;
}

TEST(MeshSteps, NaiveEqualsChainedFixedRunsWithTheInputsRange)
{
  SmallMesh m = Sheet(9, 7, 23, 0.3);
  m.Build();
  const int C = 2;
  const auto input = StepSignal(m, C);
  const auto [lo, hi] = std::minmax_element(input.begin(), input.end());
  const double range = *hi - *lo;
  const double t = 6.0;
  const int K = 3;
  AdvectionParameters naive;
  naive.time = t;
  naive.flowMode = FlowMode::Naive;
  naive.flowUpdates = K;
  const auto result = FilterMesh(m, input, C, naive);
  std::vector<double> chained = input;
  AdvectionParameters step;
  step.time = t / K;
  for (int k = 0; k < K; ++k)
    chained = FilterMesh(m, chained, C, step, range);
  EXPECT_LT(MaxDifference(result, chained), 1e-12);
  AdvectionParameters fixed;
  fixed.time = t;
  EXPECT_GT(MaxDifference(result, FilterMesh(m, input, C, fixed)), 1e-3);
  EXPECT_GT(MaxDifference(result, input), 1e-2);
}

TEST(MeshSteps, ComposedContinuesTheTracesAlongTheIntermediateFlow)
{
  SmallMesh m = Sheet(9, 7, 29, 0.3);
  m.Build();
  const int C = 2;
  const auto input = StepSignal(m, C);
  const auto [lo, hi] = std::minmax_element(input.begin(), input.end());
  const double range = *hi - *lo;
  const double t = 6.0;
  AdvectionParameters composed;
  composed.time = t;
  composed.flowMode = FlowMode::Composed;
  composed.flowUpdates = 2;
  const auto result = FilterMesh(m, input, C, composed);

  // The flows of the input and of the intermediate signal (the fixed flow for t/2).
  const auto flowOf = [&](const std::vector<double>& signal) {
    MeshSignal s;
    s.components = C;
    s.values = signal.data();
    s.valueScale = range;
    MeshFlowFields fields;
    std::vector<double> out(signal.size());
    EXPECT_TRUE(AdvectMeshSignal(m.mesh, s, out.data(), AdvectionParameters(), nullptr, &fields).Ok());
    for (double& u : fields.flow)
      u *= -m.mesh.MeanEdgeLength(); // back-trace velocity, world units
    return fields.flow;
  };
  AdvectionParameters half;
  half.time = t / 2;
  const auto v0 = flowOf(input);
  const auto v1 = flowOf(FilterMesh(m, input, C, half, range));
  const auto compose = [&](const std::vector<double>& second) {
    std::vector<double> out(input.size(), 0.0);
    std::vector<int> traces(m.Points(), 0);
    for (int p = 0; p < m.Points(); ++p)
      for (int f = 0; f < m.Triangles(); ++f)
      {
        const auto tri = m.T(f);
        if (std::find(tri.begin(), tri.end(), p) == tri.end())
          continue;
        SurfacePoint q;
        q.triangle = f;
        for (int k = 0; k < 3; ++k)
          q.barycentric[k] = tri[k] == p ? 1.0 - 0.001 * 2.0 / 3.0 : 0.001 / 3.0;
        TraceOnMesh(m.mesh, v0.data(), q, t / 2, AdvectionParameters());
        TraceOnMesh(m.mesh, second.data(), q, t / 2, AdvectionParameters());
        const auto e = m.T(static_cast<int>(q.triangle));
        for (int c = 0; c < C; ++c)
          for (int k = 0; k < 3; ++k)
            out[p * C + c] += q.barycentric[k] * input[e[k] * C + c];
        ++traces[p];
      }
    for (int p = 0; p < m.Points(); ++p)
      for (int c = 0; c < C; ++c)
        out[p * C + c] /= traces[p];
    return out;
  };
  EXPECT_LT(MaxDifference(result, compose(v1)), 1e-9);
  // Not the input's flow twice (the fixed flow), and not the naive mode.
  EXPECT_GT(MaxDifference(result, compose(v0)), 1e-4);
  AdvectionParameters naive = composed;
  naive.flowMode = FlowMode::Naive;
  EXPECT_GT(MaxDifference(result, FilterMesh(m, input, C, naive)), 1e-4);
}

// A cell signal's Linear sampling reads each corner's area-weighted average of
// its triangles' values; a corner whose average differs from one of its
// triangles' values by more than cornerDeviation (the apex of a cone, where
// the averaged normal is the axis) reads the sampled triangle's own value.
// At t = 0 each face is read at its centre: a third of each corner's value.
TEST(MeshSteps, ACornerThatDoesNotStandForItsTrianglesIsReadPerTriangle)
{
  // A cone's tip over an irregular ring (radii and heights vary), closed by
  // nothing: the apex (point 0) is shared by every triangle.
  SmallMesh m;
  const int n = 24;
  m.points = { 0.0, 0.0, 1.0 };
  for (int i = 0; i < n; ++i)
  {
    const double a = 2.0 * 3.14159265358979323846 * (i + 0.2 * std::sin(1.7 * i)) / n;
    const double r = 0.5 + 0.03 * std::cos(2.3 * i);
    m.points.insert(m.points.end(), { r * std::cos(a), r * std::sin(a), 0.01 * std::sin(3.1 * i) });
  }
  for (int i = 0; i < n; ++i)
    m.triangles.insert(m.triangles.end(), { 0, 1 + i, 1 + (i + 1) % n });
  m.Build();
  // The signal: each triangle's unit normal.
  const int C = 3;
  std::vector<double> normals(3 * n);
  for (int f = 0; f < n; ++f)
  {
    const auto t = m.T(f);
    const V3 c = Cross3(Sub(m.P(t[1]), m.P(t[0])), Sub(m.P(t[2]), m.P(t[0])));
    for (int k = 0; k < 3; ++k)
      normals[3 * f + k] = c[k] / Norm3(c);
  }
  // Independently: the corners' area-weighted averages, and which of them are
  // farther than `deviation` from one of their triangles' values.
  std::vector<double> average(3 * m.Points(), 0.0), weight(m.Points(), 0.0);
  for (int f = 0; f < n; ++f)
    for (std::int64_t p : m.T(f))
    {
      weight[p] += m.Area(f);
      for (int c = 0; c < C; ++c)
        average[3 * p + c] += m.Area(f) * normals[3 * f + c];
    }
  for (int p = 0; p < m.Points(); ++p)
    for (int c = 0; c < C; ++c)
      average[3 * p + c] /= weight[p];
  const double deviation = 2.0 * std::sin(30.0 * 3.14159265358979323846 / 360.0); // 30 degrees apart
  std::vector<bool> own(m.Points(), false);
  for (int f = 0; f < n; ++f)
    for (std::int64_t p : m.T(f))
    {
      double d2 = 0.0;
      for (int c = 0; c < C; ++c)
        d2 += (normals[3 * f + c] - average[3 * p + c]) * (normals[3 * f + c] - average[3 * p + c]);
      own[p] = own[p] || d2 > deviation * deviation;
    }
  ASSERT_TRUE(own[0]);                                      // the apex: its average is about the axis
  ASSERT_LT(std::count(own.begin(), own.end(), true), n / 2); // most ring corners read their averages

  AdvectionParameters p;
  p.time = 0.0;
  for (const double given : { 0.0, deviation })
  {
    MeshSignal signal;
    signal.location = MeshLocation::Triangles;
    signal.components = C;
    signal.values = normals.data();
    signal.valueScale = 2.0;
    signal.sampleAtTimeZero = true;
    signal.cornerDeviation = given;
    std::vector<double> out(normals.size());
    ASSERT_TRUE(AdvectMeshSignal(m.mesh, signal, out.data(), p).Ok());
    double changed = 0.0;
    for (int f = 0; f < n; ++f)
      for (int c = 0; c < C; ++c)
      {
        double expected = 0.0;
        for (std::int64_t q : m.T(f))
          expected += (given > 0.0 && own[q] ? normals[3 * f + c] : average[3 * q + c]) / 3.0;
        EXPECT_NEAR(out[3 * f + c], expected, 1e-12) << "deviation " << given << ", face " << f;
        changed = std::max(changed, std::abs(out[3 * f + c] - normals[3 * f + c]));
      }
    EXPECT_GT(changed, 0.05) << "the ring's averages still blend the neighbouring faces";
  }
}

} // namespace
