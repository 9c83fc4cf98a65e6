// The grid kernel's fast paths (docs/performance.md) against the plain ones:
// the all-valid smoothing, the image and volume tracers, the short road of the
// advection, the reads of several components, the optional AVX2 build and the
// slabs of the flow computation; each bit for bit, or to rounding where it says.
#include "TestGridReferences.h"

namespace
{


TEST(GridSteps, TheAllValidSmoothingIsTheMaskedOneBitForBit)
{
  // Without a mask, every block of a row is smoothed in one pass per value
  // (SmoothRowFused); with a mask, sample by sample. Every sample valid, both
  // must perform the same operations: the same bits, for rows longer than a
  // block (blocks that start and end inside a row, a tail block of one sample)
  // and rows that are one block (both ends in it, down to 2 samples), 0 to 4
  // neighbour rows, 8-bit and double values, one and two threads.
  for (const RefGrid g : { RefGrid{ { 257, 4, 1 }, { 1.0, 2.5, 1.0 } },
         RefGrid{ { 513, 3, 3 }, { 0.7, 1.0, 1.9 } }, RefGrid{ { 300, 1, 1 }, { 1.3, 1.0, 1.0 } },
         RefGrid{ { 2, 3, 3 }, { 1.0, 0.8, 1.4 } }, RefGrid{ { 5, 4, 1 }, { 1.0, 2.5, 1.0 } },
         RefGrid{ { 130, 1, 1 }, { 1.0, 1.0, 1.0 } } })
  {
    const int C = 3;
    const auto values = Random(g.Samples() * C, 13, -2.0, 5.0);
    std::vector<unsigned char> bytes(values.size());
    for (size_t v = 0; v < values.size(); ++v)
      bytes[v] = static_cast<unsigned char>(37 * v % 256);
    const std::vector<unsigned char> valid(static_cast<size_t>(g.Samples()), 1);
    const auto check = [&](auto lattice, const auto* in) {
      for (int threads : { 1, 2 })
      {
        std::vector<double> blocks(values.size()), masked(values.size());
        SmoothPass(lattice, C, in, 0.5, blocks.data(), nullptr, threads);
        SmoothPass(lattice, C, in, 0.5, masked.data(), valid.data(), threads);
        EXPECT_EQ(blocks, masked) << g.n[0] << " threads " << threads;
        double change = 0.0;
        for (size_t v = 0; v < values.size(); ++v)
          change = std::max(change, std::abs(blocks[v] - 0.5 * static_cast<double>(in[v])));
        EXPECT_GT(change, 0.01); // something changed
      }
    };
    switch (g.Shape().ActiveAxes())
    {
      case 1: check(Lattice<1>(g.Shape()), values.data()); check(Lattice<1>(g.Shape()), bytes.data()); break;
      case 2: check(Lattice<2>(g.Shape()), values.data()); check(Lattice<2>(g.Shape()), bytes.data()); break;
      default: check(Lattice<3>(g.Shape()), values.data()); check(Lattice<3>(g.Shape()), bytes.data()); break;
    }
  }
}
namespace
{
/// Traces random starts on random flows of grid g (zero components, equal
/// speeds, starts on grid lines) with Trace (the tracer written for D, or the
/// one Wide names) and with `other` (called as other(tracer, q, c, f, t, cut)
/// on a copy of the start): the same steps and truncation, ends within
/// `tolerance` (0: bit for bit). Returns the number of traces that crossed
/// three faces or more.
template <int D, bool Wide = false, typename Other>
int TracesAgree(const RefGrid& g, unsigned seed, double tolerance, Other other)
{
  const Lattice<D> L(g.Shape());
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<float> v(static_cast<size_t>(L.numFaces * D));
  int longTraces = 0;
  for (int flow = 0; flow < 200; ++flow)
  {
    for (float& x : v)
    {
      const double r = u(random);
      x = r < 0.25 ? 0.0f : (r < 0.35 ? (r < 0.3 ? 0.5f : -0.5f) : static_cast<float>(2.0 * u(random) - 1.0));
    }
    AdvectionParameters p;
    const GridTracer<D> tracer(L, v.data(), p);
    for (int start = 0; start < 20; ++start)
    {
      std::array<double, D> q;
      for (int d = 0; d < D; ++d)
      {
        q[d] = static_cast<double>(L.m[d]) * u(random);
        q[d] = u(random) < 0.2 ? std::floor(q[d]) : q[d];
      }
      const double t = 12.0 * u(random);
      std::array<std::int64_t, D> c;
      const std::int64_t f = tracer.FaceOf(q, c);
      std::array<double, D> otherEnd = q;
      bool cut = false, otherCut = false;
      const std::int64_t n = tracer.template Trace<Wide>(q, c, f, t, cut);
      const std::int64_t otherSteps = other(tracer, otherEnd, c, f, t, otherCut);
      EXPECT_EQ(n, otherSteps) << "flow " << flow << " start " << start;
      EXPECT_EQ(cut, otherCut);
      for (int d = 0; d < D; ++d)
      {
        if (tolerance > 0.0)
        {
          EXPECT_NEAR(q[d], otherEnd[d], tolerance) << "flow " << flow << " start " << start << " axis " << d;
        }
        else
        {
          EXPECT_EQ(q[d], otherEnd[d]) << "flow " << flow << " start " << start << " axis " << d;
        }
      }
      longTraces += n >= 3 ? 1 : 0;
    }
  }
  return longTraces;
}

/// TracesAgree of Trace (the tracer written for D) with the general TraceFaceCrossing, to rounding.
template <int D>
int TracersAgree(const RefGrid& g, unsigned seed)
{
  return TracesAgree<D>(g, seed, 1e-9,
    [](const GridTracer<D>& tracer, std::array<double, D>& q, const std::array<std::int64_t, D>& c,
      std::int64_t f, double t, bool& cut) {
      TraceMarks<D> marks;
      const std::int64_t n = tracer.TraceFaceCrossing(q, c, f, t, marks);
      cut = marks.truncated;
      return n;
    });
}
} // namespace

TEST(GridSteps, TheImageAndVolumeTracersFollowTheGeneralRule)
{
  // Images and volumes have face-crossing tracers of their own (their state in
  // scalars); on random flows they take the general rule's paths: crossings,
  // slides along valleys, reversals, the grid's boundary, the stepped rest of
  // a trace pushed onto an edge or a corner.
  EXPECT_GT(TracersAgree<2>(RefGrid{ { 11, 9, 1 }, { 1.0, 1.7, 1.0 } }, 5), 100);
  EXPECT_GT(TracersAgree<3>(RefGrid{ { 7, 6, 5 }, { 1.0, 1.3, 0.8 } }, 6), 100);
}

TEST(GridSteps, TheImageTracerFollowsTheVolumeTracerOnAFlatVolume)
{
  // A volume one face thick, with no velocity across it, is the same image:
  // the image tracer (GridTracer<2>) and the volume tracer (GridTracer<3>) agree
  // on it. On random flows
  // (zero components, equal speeds, starts on grid lines) both take the same
  // paths: crossings, slides along valleys, reversals, the grid's boundary,
  // the stepped rest of a trace pushed onto a corner.
  const RefGrid image{ { 11, 9, 1 }, { 1.0, 1.7, 1.0 } };
  const RefGrid volume{ { 11, 9, 2 }, { 1.0, 1.7, 0.8 } };
  const Lattice<2> L2(image.Shape());
  const Lattice<3> L3(volume.Shape());
  ASSERT_EQ(L2.numFaces, L3.numFaces);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<float> v2(static_cast<size_t>(L2.numFaces * 2));
  std::vector<float> v3(static_cast<size_t>(L3.numFaces * 3));
  std::int64_t steps = 0, moved = 0, traces = 0, longTraces = 0;
  for (int flow = 0; flow < 300; ++flow)
  {
    for (std::int64_t f = 0; f < L2.numFaces; ++f)
    {
      for (int d = 0; d < 2; ++d)
      {
        const double r = u(random);
        const float value = r < 0.25 ? 0.0f : (r < 0.35 ? (r < 0.3 ? 0.5f : -0.5f) : static_cast<float>(2.0 * u(random) - 1.0));
        v2[f * 2 + d] = value;
        v3[f * 3 + d] = value;
      }
      v3[f * 3 + 2] = 0.0f;
    }
    AdvectionParameters p;
    const GridTracer<2> planar(L2, v2.data(), p);
    const GridTracer<3> general(L3, v3.data(), p);
    for (int start = 0; start < 20; ++start)
    {
      std::array<double, 2> q2{ 10.0 * u(random), 8.0 * u(random) };
      q2[0] = u(random) < 0.2 ? std::floor(q2[0]) : q2[0];
      q2[1] = u(random) < 0.2 ? std::floor(q2[1]) : q2[1];
      std::array<double, 3> q3{ q2[0], q2[1], 0.5 };
      const double t = 12.0 * u(random);
      std::array<std::int64_t, 2> c2;
      std::array<std::int64_t, 3> c3;
      const std::int64_t f2 = planar.FaceOf(q2, c2);
      const std::int64_t f3 = general.FaceOf(q3, c3);
      ASSERT_EQ(f2, f3);
      bool cut2 = false, cut3 = false;
      const std::array<double, 2> from = q2;
      const std::int64_t n2 = planar.Trace(q2, c2, f2, t, cut2);
      const std::int64_t n3 = general.Trace(q3, c3, f3, t, cut3);
      ASSERT_EQ(n2, n3) << "flow " << flow << " start " << start;
      EXPECT_NEAR(q2[0], q3[0], 1e-9) << "flow " << flow << " start " << start;
      EXPECT_NEAR(q2[1], q3[1], 1e-9) << "flow " << flow << " start " << start;
      EXPECT_EQ(q3[2], 0.5);
      EXPECT_EQ(cut2, cut3);
      steps += n2;
      longTraces += n2 >= 3 ? 1 : 0;
      moved += (q2 != from) ? 1 : 0;
      ++traces;
    }
  }
  EXPECT_GT(steps, traces); // random flows reverse soon: 1.2 crossings per trace
  EXPECT_GT(longTraces, traces / 20); // but some cross several faces
  EXPECT_GT(moved, traces / 2);
}

namespace
{
/// Trilinear read of channel c of a 3D grid signal at index position (x, y, z).
double RefTrilinear(const RefGrid& g, int C, const std::vector<double>& values, int c,
  const std::array<double, 3>& q)
{
  std::array<int, 3> cell;
  std::array<double, 3> frac;
  for (int d = 0; d < 3; ++d)
  {
    cell[d] = std::min(static_cast<int>(std::floor(q[d])), g.n[d] - 2);
    frac[d] = q[d] - cell[d];
  }
  double sum = 0.0;
  for (int dz = 0; dz <= 1; ++dz)
    for (int dy = 0; dy <= 1; ++dy)
      for (int dx = 0; dx <= 1; ++dx)
      {
        const double w = (dx ? frac[0] : 1.0 - frac[0]) * (dy ? frac[1] : 1.0 - frac[1]) *
          (dz ? frac[2] : 1.0 - frac[2]);
        sum += w * values[g.Index(cell[0] + dx, cell[1] + dy, cell[2] + dz) * C + c];
      }
  return sum;
}
} // namespace

TEST(GridSteps, AdvectVerticesReadsWhereTracesThatStayInTheirFacesEnd)
{
  // Random per-face velocities, small enough that many traces end inside their
  // start face and large enough that others leave it. A trace that stays ends
  // at its start (sample + epsilon (face centre - sample)) plus v t, where the
  // signal is read trilinearly; the faces are numbered x-fastest. Samples all of
  // whose traces stay are checked against this hand computation; the others
  // (and every sample) against the general per-trace path with its stencil.
  const RefGrid g{ { 7, 5, 6 }, { 1.0, 1.3, 0.8 } };
  const Lattice<3> L(g.Shape());
  const int C = 2;
  const std::vector<double> values = Random(g.Samples() * C, 71, -2.0, 3.0);
  const std::vector<double> random = Random(L.numFaces * 3, 72, -1.0, 1.0);
  std::vector<float> velocity(random.size());
  for (size_t k = 0; k < random.size(); ++k)
    velocity[k] = static_cast<float>(0.0011 * random[k]);
  const double t = 0.5; // displacements up to 0.00055; each start lies 0.0005 from three sides of its face
  AdvectionParameters p;
  const GridTracer<3> tracer(L, velocity.data(), p);
  AdvectionReport report;
  const ProgressFunction none;
  const AdvectionContext<3> ctx{ L, C, 1, Sampling::Linear, nullptr, none, report };
  std::vector<double> out(values.size());
  ASSERT_TRUE(AdvectVertices<3>(ctx, tracer, t, values.data(), Into(out, C), nullptr, RowBlocks<3>(L.n), 0.0, 1.0));

  const int mx = g.n[0] - 1, my = g.n[1] - 1;
  int handChecked = 0, leaving = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
      {
        double sum[C] = { 0.0, 0.0 };
        int traces = 0;
        bool allStay = true;
        for (int dk = -1; dk <= 0; ++dk)
          for (int dj = -1; dj <= 0; ++dj)
            for (int di = -1; di <= 0; ++di)
            {
              const std::array<int, 3> face{ i + di, j + dj, k + dk };
              if (face[0] < 0 || face[1] < 0 || face[2] < 0 || face[0] >= mx || face[1] >= my ||
                face[2] >= g.n[2] - 1)
                continue;
              const int f = (face[2] * my + face[1]) * mx + face[0];
              std::array<double, 3> q;
              bool stays = true;
              const std::array<int, 3> sample{ i, j, k };
              for (int d = 0; d < 3; ++d)
              {
                q[d] = sample[d] + 0.001 * (face[d] + 0.5 - sample[d]) +
                  static_cast<double>(velocity[f * 3 + d]) * t;
                stays = stays && q[d] >= face[d] && q[d] <= face[d] + 1;
              }
              allStay = allStay && stays;
              for (int c = 0; c < C && stays; ++c) // a trace that leaves may end outside the grid
                sum[c] += RefTrilinear(g, C, values, c, q);
              ++traces;
            }
        const std::int64_t s = g.Index(i, j, k);
        if (allStay)
        {
          ++handChecked;
          for (int c = 0; c < C; ++c)
            EXPECT_NEAR(out[s * C + c], sum[c] / traces, 1e-12) << i << "," << j << "," << k;
        }
        else
        {
          ++leaving;
        }
        // Every sample: the general per-trace path gives the same average.
        const std::array<std::int64_t, 3> index{ i, j, k };
        const std::array<std::int64_t, 3> rowStart{ 0, j, k };
        const AdjacentFaces<3> faces(L, rowStart);
        Stencil<3> stencil;
        TraceTally<3> tally;
        const int n = TraceSample<3>(ctx, tracer, t, faces, index, s, nullptr, stencil, tally);
        ASSERT_EQ(n, traces);
        for (int c = 0; c < C; ++c)
          EXPECT_NEAR(out[s * C + c], stencil.Apply(values.data(), C, c) / n, 1e-12);
      }
  // Both kinds occur, and the signal moved.
  EXPECT_GT(handChecked, 10);
  EXPECT_GT(leaving, 10);
  double moved = 0.0;
  for (size_t v = 0; v < out.size(); ++v)
    moved = std::max(moved, std::abs(out[v] - values[v]));
  EXPECT_GT(moved, 1e-5);
}

namespace
{
/**
 * AdvectVertices on the D axes of grid g, with random face velocities (a mix
 * of traces that stay in their faces and of traces that cross several; a share
 * `slow` of the faces slow, the others up to `fast`), on `signal` (C components per sample). Checked
 * sample by sample:
 * - interior samples (the short road) bit for bit against the reads of the
 *   former formulation: when the road tries traces within their faces first,
 *   the far reads as a Stencil applied per component, then the neighbourhood;
 *   otherwise the reads of all traces as one Stencil (the order of the sums is
 *   part of the contract: results stay byte-identical);
 * - every sample, to rounding, against the general per-trace path.
 * Both kinds of trace occur on the interior samples. `withinFirst`: the road
 * the slow share must select.
 */
template <int D>
std::vector<double> AdvectRandom(const RefGrid& g, int C, const std::vector<double>& signal,
  double slow, double fast, bool withinFirst)
{
  const Lattice<D> L(g.Shape());
  const std::vector<double> direction = Random(L.numFaces * D, 82, -1.0, 1.0);
  const std::vector<double> size = Random(L.numFaces, 83, 0.0, 1.0);
  std::vector<float> velocity(direction.size());
  for (std::int64_t f = 0; f < L.numFaces; ++f)
    for (int d = 0; d < D; ++d) // a third of the faces slow: their traces stay
      velocity[f * D + d] =
        static_cast<float>(direction[f * D + d] * (size[f] < slow ? 0.0004 : fast * size[f]));
  AdvectionParameters p;
  const GridTracer<D> tracer(L, velocity.data(), p);
  AdvectionReport report;
  const ProgressFunction none;
  const AdvectionContext<D> ctx{ L, C, 1, Sampling::Linear, nullptr, none, report };
  const double t = 1.0;
  EXPECT_EQ(TriesWithinFaceFirst<D>(L, tracer, t), withinFirst) << "share of slow faces " << slow;
  std::vector<double> out(signal.size());
  EXPECT_TRUE(AdvectVertices<D>(ctx, tracer, t, signal.data(), Into(out, C), nullptr, RowBlocks<D>(L.n), 0.0, 1.0));
  constexpr int Corners = Lattice<D>::Corners;
  const Neighbourhood<D> hood(L, C);
  int stay = 0, leave = 0;
  for (std::int64_t s = 0; s < L.numSamples; ++s)
  {
    std::array<std::int64_t, D> index, rowStart;
    std::int64_t rest = s;
    bool interior = true;
    for (int d = 0; d < D; ++d)
    {
      index[d] = rest % L.n[d];
      rest /= L.n[d];
      rowStart[d] = d == 0 ? 0 : index[d];
      interior = interior && index[d] >= 1 && index[d] + 1 < L.n[d];
    }
    const AdjacentFaces<D> faces(L, rowStart);
    Stencil<D> stencil;
    TraceTally<D> tally;
    const int n = TraceSample<D>(ctx, tracer, t, faces, index, s, nullptr, stencil, tally);
    for (int c = 0; c < C; ++c)
      EXPECT_NEAR(out[s * C + c], stencil.Apply(signal.data(), C, c) / n, 1e-12) << s << " " << c;
    if (!interior)
      continue;
    double weights[Neighbourhood<D>::Size] = {};
    Stencil<D> far;
    for (int b = 0; b < Corners; ++b)
    {
      const std::int64_t f = faces.Face(index[0], b);
      double unused[Neighbourhood<D>::Size] = {};
      const bool stays = TraceWithinFace<D>(tracer.Velocity(f), b, t, withinFirst ? weights : unused);
      stay += stays ? 1 : 0;
      leave += stays ? 0 : 1;
      if (stays && withinFirst)
      {
        continue;
      }
      std::array<double, D> q;
      std::array<std::int64_t, D> cell;
      StartInFace<D>(index, b, q, cell);
      bool cut = false;
      tracer.Trace(q, cell, f, t, cut);
      SampleGrid<D>(L, nullptr, Sampling::Linear, q, far);
    }
    for (int c = 0; c < C; ++c)
    {
      const double* value = signal.data() + s * C + c;
      double partial[4] = { far.Apply(signal.data(), C, c), 0.0, 0.0, 0.0 };
      int e = 0;
      for (; e + 4 <= Neighbourhood<D>::Size; e += 4)
        for (int r = 0; r < 4; ++r)
          partial[r] += weights[e + r] * value[hood.valueOffset[e + r]];
      for (; e < Neighbourhood<D>::Size; ++e)
        partial[0] += weights[e] * value[hood.valueOffset[e]];
      EXPECT_EQ(out[s * C + c], ((partial[0] + partial[1]) + (partial[2] + partial[3])) / Corners)
        << s << " " << c;
    }
  }
  EXPECT_GT(stay, 10);
  EXPECT_GT(leave, 10);
  return out;
}

/// AdvectRandom of each component alone equals, bit for bit, that component
/// of `together` (AdvectRandom of all C); returns the largest change.
template <int D>
double EachComponentAlone(const RefGrid& g, int C, const std::vector<double>& signal,
  const std::vector<double>& together, double slow, double fast, bool withinFirst)
{
  double moved = 0.0;
  for (int c = 0; c < C; ++c)
  {
    std::vector<double> alone(g.Samples());
    for (int s = 0; s < g.Samples(); ++s)
      alone[s] = signal[s * C + c];
    const std::vector<double> out = AdvectRandom<D>(g, 1, alone, slow, fast, withinFirst);
    for (int s = 0; s < g.Samples(); ++s)
    {
      EXPECT_EQ(out[s], together[s * C + c]) << s << " " << c;
      moved = std::max(moved, std::abs(out[s] - alone[s]));
    }
  }
  return moved;
}
} // namespace

TEST(GridSteps, EveryComponentIsAdvectedAsIfAlone)
{
  // The short road reads the components of a sample's traces a few at a time
  // (4, then what is left). Any number of components gives, bit for bit, what
  // each component gives alone and what the former per-component stencil
  // gave, and to rounding the general per-trace path's average; on lines,
  // images and volumes; and the signal moved.
  const RefGrid line{ { 61, 1, 1 }, { 1.3, 1.0, 1.0 } };
  const RefGrid image{ { 9, 7, 1 }, { 1.0, 1.4, 1.0 } };
  const RefGrid volume{ { 5, 6, 4 }, { 1.0, 0.8, 1.2 } };
  // Both roads: many faces slow (traces tried within their faces first), and
  // few slow, the others fast (lines and images trace everything; volumes still
  // try first).
  for (const auto& [slow, fast] : { std::pair{ 0.45, 1.5 }, std::pair{ 0.2, 6.0 } })
  {
    for (int C : { 1, 2, 3, 4, 5, 6, 7, 9 })
    {
      SCOPED_TRACE(C);
      SCOPED_TRACE(slow);
      const bool first = slow > 0.4;
      const auto lineSignal = Random(line.Samples() * C, 80 + C, -2.0, 3.0);
      const auto lineOut = AdvectRandom<1>(line, C, lineSignal, slow, fast, first);
      EXPECT_GT(EachComponentAlone<1>(line, C, lineSignal, lineOut, slow, fast, first), 0.1);
      const auto imageSignal = Random(image.Samples() * C, 81 + C, -2.0, 3.0);
      const auto imageOut = AdvectRandom<2>(image, C, imageSignal, slow, fast, first);
      EXPECT_GT(EachComponentAlone<2>(image, C, imageSignal, imageOut, slow, fast, first), 0.1);
      const auto volumeSignal = Random(volume.Samples() * C, 82 + C, -2.0, 3.0);
      const auto volumeOut = AdvectRandom<3>(volume, C, volumeSignal, slow, fast, true);
      EXPECT_GT(EachComponentAlone<3>(volume, C, volumeSignal, volumeOut, slow, fast, true), 0.1);
    }
  }
}

namespace
{
/// SHOCK_TEST_PORTABLE=1 (the test GridKernels.PortableBuild, with the build
/// option SHOCK_ENABLE_AVX2): the whole program runs the portable build.
const bool WholeRunPortable = [] {
  const char* setting = std::getenv("SHOCK_TEST_PORTABLE");
  const bool portable = setting && std::string(setting) == "1";
  if (portable)
  {
    AllowAvx2(false);
  }
  return portable;
}();

/// Forbids the AVX2 build for its lifetime (the portable build runs).
struct PortableBuild
{
  PortableBuild() { AllowAvx2(false); }
  ~PortableBuild() { AllowAvx2(!WholeRunPortable); }
  PortableBuild(const PortableBuild&) = delete;
  PortableBuild& operator=(const PortableBuild&) = delete;
};

/// Random back-trace velocities on L: zero components, equal speeds, and
/// a share `slow` of faces so slow that their traces stay in them.
template <int D>
std::vector<float> RandomVelocity(const Lattice<D>& L, std::mt19937& random, double slow, double fast)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<float> v(static_cast<size_t>(L.numFaces * D));
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    const double speed = u(random) < slow ? 0.0004 : fast;
    for (int d = 0; d < D; ++d)
    {
      const double r = u(random);
      v[f * D + d] = static_cast<float>(
        r < 0.15 ? 0.0 : (r < 0.25 ? (r < 0.2 ? 0.5 : -0.5) * speed : (2.0 * u(random) - 1.0) * speed));
    }
  }
  return v;
}

/// TracesAgree of Trace<true> (the AVX2 build) with Trace<false>, bit for bit.
template <int D>
int Avx2TracesAreThePortableOnes(const RefGrid& g, unsigned seed)
{
  return TracesAgree<D, true>(g, seed, 0.0,
    [](const GridTracer<D>& tracer, std::array<double, D>& q, const std::array<std::int64_t, D>& c,
      std::int64_t f, double t, bool& cut) { return tracer.template Trace<false>(q, c, f, t, cut); });
}

/// AdvectVertices of `signal` (C per sample) on grid g along a random flow,
/// for time t, on `threads` threads.
template <int D, typename T>
std::vector<double> AdvectAlongRandomFlow(const RefGrid& g, int C, const std::vector<T>& signal,
  const std::vector<float>& velocity, double t, int threads)
{
  const Lattice<D> L(g.Shape());
  AdvectionParameters p;
  const GridTracer<D> tracer(L, velocity.data(), p);
  AdvectionReport report;
  const ProgressFunction none;
  const AdvectionContext<D> ctx{ L, C, threads, Sampling::Linear, nullptr, none, report };
  std::vector<double> out(signal.size());
  EXPECT_TRUE(AdvectVertices<D>(ctx, tracer, t, signal.data(), Into(out, C), nullptr, RowBlocks<D>(L.n), 0.0, 1.0));
  return out;
}
} // namespace

TEST(GridSteps, TheAvx2ImageTracerTakesThePortablePathsBitForBit)
{
  // The image tracer built for AVX2 (GridAvx2.h) does the portable build's
  // operations: on random flows, the same crossings, slides, reversals and
  // stepped rests, ending at the same doubles. (The volume tracer has no AVX2
  // build: Trace<true> is the portable one there.)
  if (!UsesAvx2())
  {
    GTEST_SKIP() << "no AVX2 build (SHOCK_ENABLE_AVX2 is off) or no AVX2 here: only the portable build runs";
  }
  EXPECT_GT(Avx2TracesAreThePortableOnes<2>(RefGrid{ { 11, 9, 1 }, { 1.0, 1.7, 1.0 } }, 15), 100);
  EXPECT_GT(Avx2TracesAreThePortableOnes<2>(RefGrid{ { 5, 13, 1 }, { 0.6, 1.0, 1.0 } }, 16), 100);
}

TEST(GridSteps, TheAvx2AdvectionGivesThePortableValuesBitForBit)
{
  // AdvectVertices built for AVX2, with its reads of 8-bit images of 3 or 4
  // components a sample at a time, gives the portable build's values bit for
  // bit: any number of components, 8-bit, float and double signals, images
  // and volumes, both roads (traces tried in their faces first or not), 1 and
  // 2 threads. The flow pushes the traces near the last sample into the last
  // cell, whose 3-component reads are left to the portable code (the
  // sanitizers' build would see a read past the array).
  if (!UsesAvx2())
  {
    GTEST_SKIP() << "no AVX2 build (SHOCK_ENABLE_AVX2 is off) or no AVX2 here: only the portable build runs";
  }
  const RefGrid image{ { 23, 17, 1 }, { 1.0, 1.4, 1.0 } };
  const RefGrid volume{ { 9, 7, 6 }, { 1.0, 0.8, 1.2 } };
  std::mt19937 random(17);
  std::uniform_int_distribution<int> byte(0, 255);
  for (const auto& [slow, fast, t] : { std::tuple{ 0.7, 1.5, 1.0 }, std::tuple{ 0.1, 3.0, 40.0 } })
  {
    SCOPED_TRACE(t);
    const Lattice<2> L(image.Shape());
    std::vector<float> flow = RandomVelocity<2>(L, random, slow, fast);
    for (std::int64_t f = L.numFaces - 3; f < L.numFaces; ++f)
    {
      flow[f * 2] = 2.0f; // towards the last sample
      flow[f * 2 + 1] = 2.0f;
    }
    for (int C : { 1, 2, 3, 4, 5 })
    {
      SCOPED_TRACE(C);
      std::vector<unsigned char> bytes(static_cast<size_t>(image.Samples() * C));
      for (unsigned char& b : bytes)
      {
        b = static_cast<unsigned char>(byte(random));
      }
      const std::vector<double> values = Random(bytes.size(), 90 + C, -2.0, 3.0);
      for (int threads : { 1, 2 })
      {
        const std::vector<double> wide = AdvectAlongRandomFlow<2>(image, C, bytes, flow, t, threads);
        const std::vector<double> wideValues = AdvectAlongRandomFlow<2>(image, C, values, flow, t, threads);
        const PortableBuild portable;
        ASSERT_FALSE(UsesAvx2());
        const std::vector<double> narrow = AdvectAlongRandomFlow<2>(image, C, bytes, flow, t, threads);
        const std::vector<double> narrowValues = AdvectAlongRandomFlow<2>(image, C, values, flow, t, threads);
        double moved = 0.0;
        for (size_t k = 0; k < bytes.size(); ++k)
        {
          ASSERT_EQ(wide[k], narrow[k]) << "sample " << k / C << " component " << k % C;
          ASSERT_EQ(wideValues[k], narrowValues[k]) << "sample " << k / C << " component " << k % C;
          moved = std::max(moved, std::abs(wide[k] - bytes[k]));
        }
        EXPECT_GT(moved, 10.0); // the signal moved
        // The last cell is the first face of the sample at (n - 2, m - 2), an
        // interior one: its trace there ends at the last sample, which it reads.
        const size_t corner = static_cast<size_t>(image.Index(21, 15, 0) * C);
        EXPECT_NE(wide[corner], static_cast<double>(bytes[corner]));
      }
    }
  }
  const Lattice<3> L(volume.Shape());
  const std::vector<float> flow = RandomVelocity<3>(L, random, 0.6, 1.5);
  const std::vector<double> values = Random(static_cast<size_t>(volume.Samples() * 2), 99, -2.0, 3.0);
  const std::vector<double> wide = AdvectAlongRandomFlow<3>(volume, 2, values, flow, 1.0, 2);
  const PortableBuild portable;
  const std::vector<double> narrow = AdvectAlongRandomFlow<3>(volume, 2, values, flow, 1.0, 2);
  EXPECT_EQ(wide, narrow);
  EXPECT_NE(wide, values);
}

TEST(GridSteps, TheAvx2ByteReadsLeaveTheLastCellToThePortableOnes)
{
  // CombineByteReadsAvx2 reads four bytes per corner: with 3 components the
  // last sample's would pass the array's end, so a cell that holds it is
  // refused (nothing written). Elsewhere, and everywhere with 4 components,
  // it gives CombineAllReads's values bit for bit.
#ifdef SHOCK_GRID_AVX2
  if (!UsesAvx2())
  {
    GTEST_SKIP() << "no AVX2 build (SHOCK_ENABLE_AVX2 is off) or no AVX2 here";
  }
  const RefGrid image{ { 6, 5, 1 }, { 1.0, 1.0, 1.0 } };
  const Lattice<2> L(image.Shape());
  for (int C : { 3, 4 })
  {
    SCOPED_TRACE(C);
    std::vector<unsigned char> bytes(static_cast<size_t>(image.Samples() * C));
    for (size_t k = 0; k < bytes.size(); ++k)
    {
      bytes[k] = static_cast<unsigned char>((k * 37 + 11) % 256);
    }
    const Neighbourhood<2> hood(L, C);
    const std::int64_t lastLower = C == 4 ? std::numeric_limits<std::int64_t>::max()
                                          : L.numSamples - 2 - L.corner[3];
    const std::int64_t s = image.Index(2, 2, 0);
    double weights[Neighbourhood<2>::Size];
    for (int e = 0; e < Neighbourhood<2>::Size; ++e)
    {
      weights[e] = 0.05 * (e + 1);
    }
    const std::array<double, 2> inside[4] = { { 0.3, 0.7 }, { 3.2, 3.9 }, { 2.5, 1.25 }, { 4.99, 0.01 } };
    const std::array<double, 2> lastCell[4] = { { 0.3, 0.7 }, { 3.2, 3.9 }, { 4.6, 3.2 }, { 1.0, 1.0 } };
    for (int far = 0; far <= 4; ++far)
    {
      double expected[4] = { -1, -1, -1, -1 }, got[4] = { -1, -1, -1, -1 };
      CombineAllReads<2, const unsigned char*, true>(L, hood, bytes.data(), s, C, weights, inside, far, expected);
      ASSERT_TRUE(CombineByteReadsAvx2<true>(L, hood, bytes.data(), s, C, lastLower, weights, inside, far, got));
      for (int k = 0; k < 4; ++k)
      {
        EXPECT_EQ(got[k], expected[k]) << "far " << far << " component " << k;
      }
    }
    double expected[4] = { -1, -1, -1, -1 }, got[4] = { -1, -1, -1, -1 };
    CombineAllReads<2, const unsigned char*, false>(L, hood, bytes.data(), s, C, nullptr, inside, 4, expected);
    ASSERT_TRUE(CombineByteReadsAvx2<false>(L, hood, bytes.data(), s, C, lastLower, nullptr, inside, 4, got));
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_EQ(got[k], expected[k]) << "component " << k;
    }
    EXPECT_GT(expected[0], 0.0);
    double untouched[4] = { -1, -1, -1, -1 };
    const bool read = CombineByteReadsAvx2<false>(L, hood, bytes.data(), s, C, lastLower, nullptr, lastCell, 4, untouched);
    EXPECT_EQ(read, C == 4);
    if (!read)
    {
      EXPECT_EQ(untouched[0], -1.0);
    }
    // Nor the neighbourhood of the sample whose neighbourhood holds the last sample.
    const std::int64_t corner = image.Index(4, 3, 0);
    EXPECT_EQ(CombineByteReadsAvx2<true>(L, hood, bytes.data(), corner, C, lastLower, weights, inside, 0, untouched), C == 4);
  }
#else
  GTEST_SKIP() << "no AVX2 build (SHOCK_ENABLE_AVX2 is off, or not x86-64)";
#endif
}

TEST(GridSteps, TheFlowIsTheSameForEverySlabSize)
{
  // The flow is computed slab by slab along the last active axis, each slab with
  // the layers its flow depends on, each thread taking whole slabs in a
  // workspace of its own. Thin slabs (down to one face layer), on one or two
  // threads, give the Appendix pipeline's potential and flow, and bit for bit
  // the whole grid's, with and without non-finite samples.
  for (int passes : { 0, 1, 2, 3 })
  {
    for (const RefGrid g : { RefGrid{ { 5, 4, 17 }, { 0.7, 1.0, 1.6 } },
           RefGrid{ { 6, 23, 1 }, { 1.0, 2.5, 1.0 } } })
    {
      const int C = 2;
      const auto input = Random(g.Samples() * C, 31 + passes, -1.0, 4.0);
      const double range = *std::max_element(input.begin(), input.end()) -
        *std::min_element(input.begin(), input.end());
      std::vector<double> potential;
      std::vector<std::vector<double>> reference;
      RefFlow(g, C, input, range, passes, potential, reference);
      const auto axes = g.ActiveAxes();

      const auto run = [&](auto lattice, std::int64_t slabFaces, const std::vector<double>& values,
                         const unsigned char* validSample, const unsigned char* validFace,
                         int threads = 1) {
        constexpr int D = decltype(lattice)::Corners == 8 ? 3 : 2;
        FlowComputation<D> flow(lattice, C, passes, validSample, validFace, threads);
        flow.KeepPotential();
        flow.SetSlabFaces(slabFaces);
        flow.Compute(values.data(), range);
        GridFlowFields fields;
        ExportFlowFields<D>(lattice, flow, fields);
        return fields;
      };
      const auto check = [&](auto lattice) {
        const std::int64_t M = lattice.m[lattice.m.size() - 1];
        const GridFlowFields whole = run(lattice, M, input, nullptr, nullptr);
        // Two threads take whole slabs (1, 2, 5 faces thick) or share each slab (8).
        for (std::int64_t slabFaces : { std::int64_t(1), std::int64_t(2), std::int64_t(5), std::int64_t(8) })
        for (int threads : { 1, 2 })
        {
          const GridFlowFields sliced = run(lattice, slabFaces, input, nullptr, nullptr, threads);
          EXPECT_EQ(sliced.potential, whole.potential) << slabFaces << " passes " << passes << " threads " << threads;
          EXPECT_EQ(sliced.flow, whole.flow) << slabFaces << " passes " << passes << " threads " << threads;
          for (int s = 0; s < g.Samples(); ++s)
            EXPECT_NEAR(sliced.potential[s], potential[s], 1e-12 * (1.0 + potential[s]));
          for (size_t f = 0; f < reference.size(); ++f)
            for (size_t d = 0; d < axes.size(); ++d)
              EXPECT_NEAR(sliced.flow[f * 3 + axes[d]], reference[f][d],
                2e-7 * (1.0 + std::abs(reference[f][d])));
        }
        // One computation reused with slabs thick, thin, then thicker again (its
        // workspaces grow and are reused), on two threads.
        {
          constexpr int D = decltype(lattice)::Corners == 8 ? 3 : 2;
          FlowComputation<D> flow(lattice, C, passes, nullptr, nullptr, 2);
          flow.KeepPotential();
          for (std::int64_t slabFaces : { std::int64_t(1), M, std::int64_t(3), std::int64_t(2), std::int64_t(5) })
          {
            flow.SetSlabFaces(slabFaces);
            flow.Compute(input.data(), range);
            GridFlowFields fields;
            ExportFlowFields<D>(lattice, flow, fields);
            EXPECT_EQ(fields.flow, whole.flow) << "reused, " << slabFaces << " passes " << passes;
            EXPECT_EQ(fields.potential, whole.potential) << "reused, " << slabFaces;
          }
          flow.ReleaseWorkspace();
          flow.SetSlabFaces(4);
          flow.Compute(input.data(), range);
          GridFlowFields fields;
          ExportFlowFields<D>(lattice, flow, fields);
          EXPECT_EQ(fields.flow, whole.flow) << "after a release, passes " << passes;
        }
        // Non-finite samples: the masks are cut with the slabs.
        std::vector<double> holes = input;
        holes[C * (g.Samples() / 2)] = std::numeric_limits<double>::quiet_NaN();
        holes[C * (g.Samples() / 3) + 1] = std::numeric_limits<double>::infinity();
        using L = decltype(lattice);
        const ValidityMasks<L::Corners == 8 ? 3 : 2> masks(lattice, C, holes.data(), false, 1);
        const GridFlowFields wholeHoles = run(lattice, M, holes, masks.Samples(), masks.Faces());
        for (int threads : { 1, 2 })
        {
          const GridFlowFields slicedHoles =
            run(lattice, 1, holes, masks.Samples(), masks.Faces(), threads);
          EXPECT_EQ(slicedHoles.potential, wholeHoles.potential) << threads;
          EXPECT_EQ(slicedHoles.flow, wholeHoles.flow) << threads;
        }
        EXPECT_NE(wholeHoles.flow, whole.flow); // something changed
      };
      if (g.n[2] > 1)
        check(Lattice<3>(g.Shape()));
      else
        check(Lattice<2>(g.Shape()));
    }
  }
}

} // namespace
