// A piece of a grid with h samples of halo around its own samples (what a
// process of a distributed image filters): the grid kernel reports how far
// beyond the faces beside the own samples their traces went
// (AdvectionReport::haloReach), and whenever that plus GridStencilLayers is at
// most h on every side whose halo does not end at the grid's boundary, the own
// samples' results must be the whole grid's. The piece and its halo are cut
// here from the whole grid, independently of the filters' distributed code.
#include "GridLattice.h"
#include "GridShockAdvection.h"
#include "GridTrace.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace shock;

namespace
{
using Box = std::array<int, 6>; // first and last sample per axis x, y, z

/// A blurred step along a slanted line, bumps and a little deterministic noise: traces of every length.
std::vector<double> Signal(const GridShape& shape, int C)
{
  std::vector<double> values(static_cast<size_t>(shape.NumberOfSamples() * C));
  unsigned state = 12345u;
  std::int64_t s = 0;
  for (int k = 0; k < shape.dimensions[2]; ++k)
    for (int j = 0; j < shape.dimensions[1]; ++j)
      for (int i = 0; i < shape.dimensions[0]; ++i, ++s)
        for (int c = 0; c < C; ++c)
        {
          state = state * 1664525u + 1013904223u;
          const double noise = ((state >> 8) % 1000) / 1000.0 - 0.5;
          const double x = i * shape.spacing[0], y = j * shape.spacing[1], z = k * shape.spacing[2];
          const double step = std::tanh((0.8 * x - 0.5 * y + 0.3 * z - 9.0 - 2.0 * c) / 2.5);
          const double bumps = 0.4 * std::sin(0.45 * x + c) * std::cos(0.35 * y) + 0.2 * std::sin(0.5 * z);
          values[static_cast<size_t>(s * C + c)] = step + bumps + 0.05 * noise;
        }
  return values;
}

/// The samples of `box` (whole-grid coordinates) of `values`, x-fastest.
std::vector<double> Cut(const GridShape& whole, const std::vector<double>& values, int C, const Box& box)
{
  std::vector<double> piece;
  for (int k = box[4]; k <= box[5]; ++k)
    for (int j = box[2]; j <= box[3]; ++j)
      for (int i = box[0]; i <= box[1]; ++i)
      {
        const std::int64_t s = i + static_cast<std::int64_t>(whole.dimensions[0]) * (j + static_cast<std::int64_t>(whole.dimensions[1]) * k);
        for (int c = 0; c < C; ++c)
          piece.push_back(values[static_cast<size_t>(s * C + c)]);
      }
  return piece;
}

struct Case
{
  std::string name;
  GridShape whole;
  int C = 1;
  Box own;  // the piece's own samples
  AdvectionParameters p;
};

struct Outcome
{
  int exactRuns = 0;      // runs whose report says the own samples are the whole grid's
  int inexactRuns = 0;    // runs whose report says they may not be
  int inexactDiffering = 0; // of those, the runs where some own sample differs
  std::int64_t deepest = 0; // the deepest reach reported
};

/// Filter the whole grid, then the piece with every halo from 1 to stencil + 12 samples.
Outcome Check(const Case& c)
{
  Outcome outcome;
  const std::vector<double> whole = Signal(c.whole, c.C);
  const double range = *std::max_element(whole.begin(), whole.end()) - *std::min_element(whole.begin(), whole.end());
  AdvectionParameters p = c.p;
  p.valueScale = range; // a piece is normalised by the whole grid's range (the filters reduce it)
  std::vector<double> reference(whole.size());
  EXPECT_TRUE(AdvectGridSignal(c.whole, c.C, whole.data(), reference.data(), p).Ok());
  const int stencil = GridStencilLayers(p);
  EXPECT_EQ(stencil, 2 * p.smoothingPasses + 2);
  for (int h = 1; h <= stencil + 12; ++h)
  {
    Box halo;
    std::array<bool, 6> open{}; // sides whose halo has all h samples (else it ends at the grid's boundary)
    for (int a = 0; a < 3; ++a)
    {
      halo[2 * a] = std::max(0, c.own[2 * a] - h);
      halo[2 * a + 1] = std::min(c.whole.dimensions[a] - 1, c.own[2 * a + 1] + h);
      open[2 * a] = c.own[2 * a] - h >= 0;
      open[2 * a + 1] = c.own[2 * a + 1] + h <= c.whole.dimensions[a] - 1;
    }
    GridShape piece = c.whole;
    AdvectionParameters q = p;
    for (int a = 0; a < 3; ++a)
    {
      piece.dimensions[a] = halo[2 * a + 1] - halo[2 * a] + 1;
      piece.wholeDimensions[a] = c.whole.dimensions[a];
      q.writtenSamples[2 * a] = c.own[2 * a] - halo[2 * a];
      q.writtenSamples[2 * a + 1] = c.own[2 * a + 1] - halo[2 * a];
    }
    const std::vector<double> input = Cut(c.whole, whole, c.C, halo);
    std::vector<double> output(input.size(), 0.0);
    AdvectionReport report;
    const Status status = AdvectGridSignal(piece, c.C, input.data(), output.data(), q, &report);
    EXPECT_TRUE(status.Ok()) << status.error;
    bool exact = true;
    for (int side = 0; side < 6; ++side)
    {
      EXPECT_GE(report.haloReach[side], 0);
      outcome.deepest = std::max(outcome.deepest, report.haloReach[side]);
      if (open[side])
      {
        exact = exact && report.haloReach[side] + stencil <= h;
      }
    }
    // The own samples against the whole grid's results.
    double worst = 0.0;
    for (int k = c.own[4]; k <= c.own[5]; ++k)
      for (int j = c.own[2]; j <= c.own[3]; ++j)
        for (int i = c.own[0]; i <= c.own[1]; ++i)
        {
          const std::int64_t w = i + static_cast<std::int64_t>(c.whole.dimensions[0]) * (j + static_cast<std::int64_t>(c.whole.dimensions[1]) * k);
          const std::int64_t s = (i - halo[0]) +
            static_cast<std::int64_t>(piece.dimensions[0]) * ((j - halo[2]) + static_cast<std::int64_t>(piece.dimensions[1]) * (k - halo[4]));
          for (int m = 0; m < c.C; ++m)
            worst = std::max(worst, std::abs(output[static_cast<size_t>(s * c.C + m)] - reference[static_cast<size_t>(w * c.C + m)]));
        }
    if (exact)
    {
      ++outcome.exactRuns;
      EXPECT_LE(worst, 1e-12 * range) << c.name << ", halo " << h << ": the report says exact";
    }
    else
    {
      ++outcome.inexactRuns;
      outcome.inexactDiffering += worst > 1e-12 * range ? 1 : 0;
    }
  }
  return outcome;
}

Case Make(const std::string& name, std::array<int, 3> dimensions, Box own, double time)
{
  Case c;
  c.name = name;
  for (int a = 0; a < 3; ++a)
    c.whole.dimensions[a] = dimensions[a];
  c.own = own;
  c.p.time = time;
  c.p.numberOfThreads = 2;
  return c;
}

void Expect(const Case& c)
{
  const Outcome o = Check(c);
  SCOPED_TRACE(c.name);
  EXPECT_GT(o.exactRuns, 0);
  EXPECT_GE(o.deepest, 3) << "the traces hardly left the faces beside the own samples: a case that tests little";
  // A trace that entered a face of inexact flow need not change its sample's
  // value; but some runs the report calls too small must differ (else the
  // halo would not matter here).
  EXPECT_GT(o.inexactRuns, 0);
  EXPECT_GT(o.inexactDiffering, 0) << "no halo the report calls too small changed a result";
}
} // namespace

TEST(GridPieceHalo, ImageOwnSamplesAreTheWholeGridsWithinTheReportedReach)
{
  for (int passes = 0; passes <= 2; ++passes)
  {
    Case c = Make("image, " + std::to_string(passes) + " smoothing passes", { 44, 37, 1 }, { 16, 27, 9, 25, 0, 0 }, 100000.0);
    c.p.smoothingPasses = passes;
    Expect(c);
  }
}

TEST(GridPieceHalo, StepsAnisotropicSpacingAndChannels)
{
  Case stepped = Make("image, stepped tracing", { 44, 37, 1 }, { 14, 26, 0, 36, 0, 0 }, 100000.0);
  stepped.p.tracing = Tracing::Stepped;
  Expect(stepped);
  // The unit of length is the whole grid's mean edge: a piece's own would
  // differ where the spacing is not the same along every axis.
  Case anisotropic = Make("image, anisotropic, two channels", { 40, 36, 1 }, { 9, 19, 0, 35, 0, 0 }, 100000.0);
  anisotropic.whole.spacing = { 1.0, 1.7, 1.0 };
  anisotropic.C = 2;
  Expect(anisotropic);
}

TEST(GridPieceHalo, VolumeOwnSamplesAreTheWholeGridsWithinTheReportedReach)
{
  Case c = Make("volume", { 20, 17, 16 }, { 0, 19, 0, 16, 6, 9 }, 50000.0);
  c.whole.spacing = { 1.0, 1.0, 0.8 };
  Expect(c);
}

TEST(GridPieceHalo, TheTraceCapIsTheWholeGrids)
{
  GridShape whole;
  whole.dimensions = { 60, 50, 1 };
  GridShape piece = whole;
  piece.dimensions = { 60, 12, 1 };
  for (Tracing tracing : { Tracing::FaceCrossing, Tracing::Stepped })
  {
    AdvectionParameters p;
    p.tracing = tracing;
    const std::vector<float> velocity(static_cast<size_t>(60 * 50 * 2), 0.0f);
    const grid::Lattice<2> wholeLattice(whole);
    const grid::Lattice<2> alone(piece);
    piece.wholeDimensions = { 60, 50, 0 };
    const grid::Lattice<2> ofTheWhole(piece);
    const grid::GridTracer<2> a(wholeLattice, velocity.data(), p);
    const grid::GridTracer<2> b(ofTheWhole, velocity.data(), p);
    const grid::GridTracer<2> c(alone, velocity.data(), p);
    EXPECT_EQ(b.StepCap(), a.StepCap());
    EXPECT_LT(c.StepCap(), a.StepCap()); // the piece's own size would cap it sooner
    piece.wholeDimensions = { 0, 0, 0 };
  }
}
