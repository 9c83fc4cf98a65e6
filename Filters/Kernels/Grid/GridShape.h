/**
 * @file GridShape.h
 * @brief The shape of a regular grid of samples, the flow fields a grid run can
 * export, and the writer that receives a grid kernel's results: what every grid
 * step shares (GridLattice.h, GridFlow.h, GridShockAdvection.h, ...).
 */
#ifndef GridShape_h
#define GridShape_h

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace shock
{

/// Shape of a regular grid of samples.
struct GridShape
{
  std::array<int, 3> dimensions{ { 1, 1, 1 } };        ///< samples per axis, each >= 1
  std::array<double, 3> spacing{ { 1.0, 1.0, 1.0 } };  ///< distance between samples per axis, > 0
  /**
   * A piece of a larger grid (with its halo, AdvectionParameters::writtenSamples):
   * the whole grid's samples per axis, so that the mean edge length (the unit
   * of lengths) and the trace step cap (a few grid diameters) are the whole
   * grid's, as in a serial run. 0 on an axis: this grid's own count.
   */
  std::array<int, 3> wholeDimensions{ { 0, 0, 0 } };

  std::int64_t NumberOfSamples() const;
  /// Faces per axis: dimensions - 1 on axes with more than one sample, 1 on flat axes.
  std::int64_t NumberOfFaces() const;
  /// Number of axes with more than one sample (0 to 3).
  int ActiveAxes() const;
  /// Mean length of the grid's edges (the paper's l-bar; of the whole grid's, see
  /// wholeDimensions); 0 when there is no edge.
  double MeanEdgeLength() const;
  /// Samples along axis a of the whole grid (wholeDimensions, else dimensions).
  int WholeDimension(int a) const { return this->wholeDimensions[a] > 0 ? this->wholeDimensions[a] : this->dimensions[a]; }
};

/// Optional outputs describing the flow of the last flow computation.
struct GridFlowFields
{
  /// Potential P per sample (|grad I|^2 averaged to samples, then smoothed), normalised units.
  std::vector<double> potential;
  /// Flow u = 1/2 grad P per face, 3 components (x, y, z grid axes), normalised units.
  std::vector<double> flow;
};

/**
 * Receives a kernel's results: `count` samples from sample index `first`, C
 * interleaved values each, valid only during the call. Called from several
 * threads at once for disjoint runs of samples, in no particular order, so that
 * results can go straight into the caller's storage type without a full-size
 * double buffer.
 */
using SampleWriter =
  std::function<void(std::int64_t first, std::int64_t count, const double* values)>;

} // namespace shock

#endif
