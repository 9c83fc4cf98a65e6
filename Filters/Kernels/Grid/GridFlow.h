/**
 * @file GridFlow.h
 * @brief The steps of the shock-filter flow on a regular grid (sections 3.2-3.3
 * and Appendix A of Prada and Kazhdan 2015), each a function one can call and
 * test alone:
 *
 *  1. SmoothPass, UmbrellaSmooth: umbrella smoothing with Gaussian weights
 *     exp(-|(v-w)/l|^2) over the grid one-ring;
 *  2. FaceGradient: per axis, the mean finite difference over a face's parallel
 *     edges; FaceEnergy: |grad I|^2 summed over the channels;
 *  3. FacesToSamples: the potential, the (equal-)area-weighted average of the
 *     energy of a sample's adjacent faces;
 *  4. UmbrellaSmooth of the potential; BackTraceVelocity: -u, u = 1/2 grad P.
 *
 * Step 1 lives in GridSmooth.h, the entry points' checks in GridChecks.h.
 * FlowComputation chains them with reused buffers. Shared by
 * GridShockAdvection.cxx and GridShockPDE.cxx, so that both methods compute the
 * potential and the flow identically. Loops use OpenMP: include only from
 * translation units built with it.
 */
#ifndef GridFlow_h
#define GridFlow_h

#include "GridChecks.h"
#include "GridLattice.h"
#include "GridLayered.h"
#include "GridShape.h"
#include "GridSmooth.h"
#include "ShockTypes.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <omp.h>

namespace shock
{
namespace grid
{

/// Offsets, in values, of a face's corners from its lower corner, for C values per sample.
template <int D>
std::array<std::int64_t, Lattice<D>::Corners> CornerOffsets(const Lattice<D>& L, int C)
{
  std::array<std::int64_t, Lattice<D>::Corners> offset;
  for (int b = 0; b < Lattice<D>::Corners; ++b)
  {
    offset[b] = L.corner[b] * C;
  }
  return offset;
}

/// Face gradient of the channel whose value at the face's lower corner is at
/// `lower`, the other corners at `offset` (CornerOffsets): per axis, the mean
/// finite difference over the face's parallel edges.
template <int D>
SHOCK_ALWAYS_INLINE std::array<double, D> FaceGradientAt(const Lattice<D>& L, const double* lower,
  const std::array<std::int64_t, Lattice<D>::Corners>& offset)
{
  constexpr int Corners = Lattice<D>::Corners;
  // Each corner value is read once.
  double corner[Corners];
  for (int b = 0; b < Corners; ++b)
  {
    corner[b] = lower[offset[b]];
  }
  std::array<double, D> g{};
  for (int d = 0; d < D; ++d)
  {
    double sum = 0.0;
    for (int b = 0; b < Corners; ++b)
    {
      if (!((b >> d) & 1))
      {
        sum += corner[b | (1 << d)] - corner[b];
      }
    }
    g[d] = sum * L.meanDifference[d]; // sum / (edges per axis x h)
  }
  return g;
}

/// Face gradient of channel c of the face whose lower corner is sample `base`.
template <int D>
std::array<double, D> FaceGradient(
  const Lattice<D>& L, const double* values, int C, int c, std::int64_t base)
{
  return FaceGradientAt<D>(L, values + base * C + c, CornerOffsets<D>(L, C));
}

/**
 * Section 3.3: |grad I|^2 per face, summed over the C channels (the channels are
 * coupled through one flow); 0 on invalid faces (`validFace` null: all valid).
 */
template <int D>
void FaceEnergy(const Lattice<D>& L, int C, const double* values, const unsigned char* validFace,
  double* energy, int threads)
{
  const auto offset = CornerOffsets<D>(L, C);
  ForEachFaceBlock<D>(L, threads, [=, &L](std::int64_t f0, std::int64_t base0, std::int64_t length) {
    for (std::int64_t j = 0; j < length; ++j)
    {
      double e = 0.0;
      if (!validFace || validFace[f0 + j])
      {
        const double* lower = values + (base0 + j) * C;
        for (int channel = 0; channel < C; ++channel)
        {
          const auto g = FaceGradientAt<D>(L, lower + channel, offset);
          for (int d = 0; d < D; ++d)
          {
            e += g[d] * g[d];
          }
        }
      }
      energy[f0 + j] = e;
    }
  });
}

/**
 * Appendix A potential before smoothing: the face energy averaged over each
 * sample's valid adjacent faces, weighted by area (all faces of a grid have
 * the same area, so the weights are equal).
 */
template <int D>
void FacesToSamples(const Lattice<D>& L, const double* energy, const unsigned char* validFace,
  double* potential, int threads)
{
  ForEachSampleBlock<D>(L, threads, [=, &L](const auto& i, std::int64_t s0, std::int64_t length) {
    const AdjacentFaces<D> faces(L, i);
    if (!validFace)
    {
      // Every face valid: the same sums in the same order, without a test per face.
      std::array<std::int64_t, Lattice<D>::Corners / 2> rows;
      int rowCount = 0;
      for (int r = 0; r < Lattice<D>::Corners / 2; ++r)
      {
        if (faces.RowStart(r) >= 0)
        {
          rows[rowCount++] = faces.RowStart(r);
        }
      }
      for (std::int64_t j = 0; j < length; ++j)
      {
        const std::int64_t x = i[0] + j;
        const bool right = x < L.m[0]; // the face from x to x + 1 exists
        const bool left = x > 0;       // the face from x - 1 to x exists
        double sum = 0.0;
        for (int r = 0; r < rowCount; ++r)
        {
          sum += right ? energy[rows[r] + x] : 0.0;
          sum += left ? energy[rows[r] + x - 1] : 0.0;
        }
        const int count = rowCount * ((right ? 1 : 0) + (left ? 1 : 0));
        potential[s0 + j] = count > 0 ? sum / count : 0.0;
      }
      return;
    }
    for (std::int64_t j = 0; j < length; ++j)
    {
      double sum = 0.0;
      int count = 0;
      for (int b = 0; b < Lattice<D>::Corners; ++b)
      {
        const std::int64_t f = faces.Face(i[0] + j, b);
        if (f >= 0 && (!validFace || validFace[f]))
        {
          sum += energy[f];
          ++count;
        }
      }
      potential[s0 + j] = count > 0 ? sum / count : 0.0;
    }
  });
}

/**
 * Section 3.2 flow u = 1/2 grad P per face, returned as the back-trace velocity
 * -u in index units (-u / h per axis), D floats per face; 0 on invalid faces.
 */
template <int D>
void BackTraceVelocity(const Lattice<D>& L, const double* potential,
  const unsigned char* validFace, float* velocity, int threads)
{
  // -u / h with u = 1/2 grad P: index units of the back trace.
  std::array<double, D> toIndex;
  for (int d = 0; d < D; ++d)
  {
    toIndex[d] = -0.5 / L.h[d];
  }
  const auto offset = CornerOffsets<D>(L, 1);
  ForEachFaceBlock<D>(L, threads, [=, &L](std::int64_t f0, std::int64_t base0, std::int64_t length) {
    for (std::int64_t j = 0; j < length; ++j)
    {
      float* v = velocity + (f0 + j) * D;
      if (validFace && !validFace[f0 + j])
      {
        std::fill(v, v + D, 0.0f);
        continue;
      }
      const auto g = FaceGradientAt<D>(L, potential + base0 + j, offset);
      for (int d = 0; d < D; ++d)
      {
        v[d] = static_cast<float>(g[d] * toIndex[d]);
      }
    }
  });
}

/**
 * The flow of a signal (sections 3.2-3.3): smoothing, face gradients, potential,
 * smoothing of the potential, back-trace velocity. Holds the buffers, which the
 * flow updates of a run reuse.
 *
 * The steps run slab by slab: consecutive layers along the last active axis,
 * each with the 2 x passes + 1 layers beyond it on either side that its faces'
 * flow depends on (recomputed, not stored). Every value is computed by the same
 * operations as over the whole grid, so the flow is the same for any slab size
 * and thread count, while the workspace holds a slab rather than the grid. Each
 * thread takes whole slabs, one after the other, in a workspace of its own:
 * an image's slab stays in the thread's cache, no step waits for the other
 * threads, and each thread writes only its own few megabytes again and again
 * (when the threads shared each slab, the steps that write the shared slab
 * buffer ran at times at half speed for a whole run). A grid of fewer than two slabs per thread (a thin
 * volume) has the threads work on each slab in turn, in one workspace.
 */
template <int D>
class FlowComputation
{
public:
  /// `validSample` and `validFace` are null when every sample is finite.
  FlowComputation(const Lattice<D>& lattice, int components, int smoothingPasses,
    const unsigned char* validSample, const unsigned char* validFace, int threads)
    : L(lattice)
    , C(components)
    , Passes(smoothingPasses)
    , ValidSample(validSample)
    , ValidFace(validFace)
    , Threads(threads)
    , VelocityField(AllocateLargeArray<float>(lattice.numFaces * D))
  {
    this->SlabFaces = this->DefaultSlabFaces();
  }

  /// Keep the potential of the whole grid (KeptPotential()), for ExportFlowFields.
  void KeepPotential() { this->Keep = true; }

  /// Face layers per slab (>= 1); a test hook: the flow does not depend on it.
  void SetSlabFaces(std::int64_t faces) { this->SlabFaces = std::max<std::int64_t>(faces, 1); }

  /// Compute the flow of `signal` (float, double or 8-bit; one array or
  /// LayeredValues, GridLayered.h), intensities divided by `range`.
  template <typename S>
  void Compute(const S& signal, double range)
  {
    const std::int64_t M = L.m[D - 1];
    const std::int64_t slabFaces = std::min(this->SlabFaces, M);
    const std::int64_t slabs = (M + slabFaces - 1) / slabFaces;
    const int teams = this->ThreadsTakeWholeSlabs(slabFaces, slabs) ? this->Threads : 1;
    const std::int64_t layers = std::min(slabFaces + 2 * this->Halo() + 1, L.n[D - 1]);
    if (static_cast<int>(this->Spaces.size()) < teams)
    {
      this->Spaces.resize(static_cast<size_t>(teams));
    }
    for (int t = 0; t < teams; ++t)
    {
      Workspace& w = this->Spaces[static_cast<size_t>(t)];
      if (w.layers < layers)
      {
        w = Workspace(); // the smaller buffers go first
        w.smoothed = AllocateLargeArray<double>(layers * L.sampleStride[D - 1] * C);
        w.potential = AllocateLargeArray<double>(layers * L.sampleStride[D - 1]);
        if (this->Passes >= 2)
        {
          w.scratch = AllocateLargeArray<double>(layers * L.sampleStride[D - 1] * C);
        }
        w.layers = layers;
      }
    }
    if (this->Keep && !this->PotentialField)
    {
      this->PotentialField = AllocateLargeArray<double>(L.numSamples);
    }
    if (teams == 1)
    {
      for (std::int64_t k = 0; k < slabs; ++k)
      {
        this->ComputeSlabFlow(signal, range, k * slabFaces, std::min(M, (k + 1) * slabFaces),
          this->Spaces[0], this->Threads);
      }
      return;
    }
#pragma omp parallel for schedule(dynamic, 1) num_threads(teams)
    for (std::int64_t k = 0; k < slabs; ++k)
    {
      this->ComputeSlabFlow(signal, range, k * slabFaces, std::min(M, (k + 1) * slabFaces),
        this->Spaces[omp_get_thread_num()], 1);
    }
  }

  /**
   * Release the smoothing and potential buffers (the velocity stays): after the
   * last flow of a run, so that the advection's output reuses their memory
   * instead of raising the peak. The kept potential stays.
   */
  void ReleaseWorkspace() { this->Spaces.clear(); }

  /// Potential P per sample, normalised units; null unless KeepPotential was asked.
  const double* KeptPotential() const { return this->PotentialField.get(); }
  /// Back-trace velocity per face in index units, -u / h with u = 1/2 grad P; D per face.
  const float* Velocity() const { return this->VelocityField.get(); }

private:
  /// Sample layers beyond a slab's faces that their flow depends on.
  std::int64_t Halo() const { return 2 * this->Passes + 1; }

  /// Bytes of a workspace per sample layer.
  double LayerBytes() const
  {
    return static_cast<double>(L.sampleStride[D - 1]) * (C + 1 + (this->Passes >= 2 ? C : 0)) *
      static_cast<double>(sizeof(double));
  }

  /**
   * Whether each thread takes whole slabs (of `slabFaces` face layers, `slabs` of
   * them) in a workspace of its own (one thread: slabs of that size one after
   * the other): with at least two slabs per thread, and
   * when the threads' workspaces together take no more than 3 MiB per thread or
   * an eighth of the grid (a volume's layers are large: its threads share each
   * slab, in one workspace).
   */
  bool ThreadsTakeWholeSlabs(std::int64_t slabFaces, std::int64_t slabs) const
  {
    if (slabs < 2 * this->Threads)
    {
      return false;
    }
    const double layers = static_cast<double>(
      std::min(slabFaces + 2 * this->Halo() + 1, L.n[D - 1]));
    const double workspaces = this->Threads * layers * this->LayerBytes();
    const double bound = std::max(this->Threads * WorkspaceBytes,
      static_cast<double>(L.n[D - 1]) * this->LayerBytes() / 8.0);
    return workspaces <= bound;
  }

  /**
   * The slab thickness in face layers. Where the threads can take whole slabs
   * (ThreadsTakeWholeSlabs): each thread's workspace about WorkspaceBytes and
   * at least 8 halos thick (the recomputed halo layers then cost little), so
   * that an image's slab stays in cache, evened out over the threads, at
   * least two slabs each. Otherwise about 8 slabs, each at least 8 halos
   * thick, which the threads share; a grid thinner than that is one slab.
   */
  std::int64_t DefaultSlabFaces() const
  {
    const std::int64_t M = L.m[D - 1];
    const std::int64_t H = this->Halo();
    const std::int64_t fit =
      static_cast<std::int64_t>(WorkspaceBytes / this->LayerBytes()) - 2 * H - 1;
    const std::int64_t wanted = std::max<std::int64_t>(fit, 8 * H);
    // Slabs at most `wanted` thick, at least two per thread.
    const std::int64_t teamWork = std::max(1, this->Threads) * wanted;
    const std::int64_t perThread = (M + teamWork - 1) / teamWork;
    if (perThread >= 2)
    {
      const std::int64_t slabs = this->Threads * perThread;
      std::int64_t faces = (M + slabs - 1) / slabs;
      if ((M + faces - 1) / faces < 2 * this->Threads)
      {
        faces = M / slabs; // rounded down: at least `slabs` slabs
      }
      if (this->ThreadsTakeWholeSlabs(faces, (M + faces - 1) / faces))
      {
        return faces;
      }
    }
    return std::max<std::int64_t>((M + 7) / 8, 8 * H);
  }

  /// One thread's buffers for a slab: the smoothed signal (then the raw
  /// potential), the face energy (then the smoothed potential), and the second
  /// smoothing buffer (2+ passes).
  struct Workspace
  {
    std::int64_t layers = 0; // sample layers it holds
    LargeArray<double> smoothed;
    LargeArray<double> potential;
    LargeArray<double> scratch;
  };

  /// The velocity of the face layers [f0, f1), in workspace `w`, by `threads` threads.
  template <typename S>
  void ComputeSlabFlow(const S& signal, double range, std::int64_t f0, std::int64_t f1,
    Workspace& w, int threads)
  {
    using T = SignalValue<S>;
    const std::int64_t M = L.m[D - 1];
    const std::int64_t layerSamples = L.sampleStride[D - 1];
    const std::int64_t layerFaces = L.faceStride[D - 1];
    // Sample layers [a, b] hold every value the flow of face layers [f0, f1) depends on.
    const std::int64_t a = std::max<std::int64_t>(0, f0 - this->Halo());
    const std::int64_t b = std::min(M, f1 + this->Halo());
    const Lattice<D> slab = L.Layers(b - a + 1);
    const unsigned char* validSample = this->ValidSample ? this->ValidSample + a * layerSamples : nullptr;
    const unsigned char* validFace = this->ValidFace ? this->ValidFace + a * layerFaces : nullptr;
    // Smoothing, face energy, potential and its smoothing over the samples of
    // the slab. Each buffer serves twice, to save memory: the energy per face
    // (there are fewer faces than samples) goes to the potential's buffer, and
    // the raw potential to the smoothed signal's, each once its previous
    // content has been used.
    std::vector<T> gathered; // the slab's layers, when they lie in more than one array
    UmbrellaSmooth<D>(slab, C, SlabValues(signal, C, a * layerSamples, slab.numSamples, gathered), 1.0 / range,
      w.smoothed.get(),
      w.scratch.get(), validSample, this->Passes, threads);
    double* energy = w.potential.get();
    FaceEnergy<D>(slab, C, w.smoothed.get(), validFace, energy, threads);
    double* rawPotential = w.smoothed.get();
    FacesToSamples<D>(slab, energy, validFace, rawPotential, threads);
    UmbrellaSmooth<D>(slab, 1, rawPotential, 1.0, w.potential.get(), w.scratch.get(),
      validSample, this->Passes, threads);
    // The velocity of the faces [f0, f1), from the potential of the samples [f0, f1].
    const double* potential = w.potential.get() + (f0 - a) * layerSamples;
    BackTraceVelocity<D>(L.Layers(f1 - f0 + 1), potential,
      this->ValidFace ? this->ValidFace + f0 * layerFaces : nullptr,
      this->VelocityField.get() + f0 * layerFaces * D, threads);
    if (this->Keep)
    {
      const std::int64_t end = (f1 == M ? f1 + 1 : f1) * layerSamples;
      std::copy(potential, potential + end - f0 * layerSamples,
        this->PotentialField.get() + f0 * layerSamples);
    }
  }

  const Lattice<D>& L;
  const int C;
  const int Passes;
  const unsigned char* ValidSample;
  const unsigned char* ValidFace;
  const int Threads;
  std::int64_t SlabFaces = 1;
  bool Keep = false;
  std::vector<Workspace> Spaces;     // one per thread taking whole slabs, else one
  static constexpr double WorkspaceBytes = 3 << 20; // per thread taking whole slabs
  LargeArray<double> PotentialField; // the whole grid's potential (KeepPotential)
  LargeArray<float> VelocityField;
};

/// Copy the potential and the flow u (world grid axes, 3 per face) of `flow` into `fields`.
template <int D>
void ExportFlowFields(const Lattice<D>& L, const FlowComputation<D>& flow, GridFlowFields& fields)
{
  fields.potential.assign(flow.KeptPotential(), flow.KeptPotential() + L.numSamples);
  fields.flow.assign(static_cast<size_t>(L.numFaces * 3), 0.0);
  const float* velocity = flow.Velocity();
  for (std::int64_t f = 0; f < L.numFaces; ++f)
  {
    for (int d = 0; d < D; ++d)
    {
      fields.flow[f * 3 + L.axis[d]] = -static_cast<double>(velocity[f * D + d]) * L.h[d];
    }
  }
}

} // namespace grid
} // namespace shock

#endif
