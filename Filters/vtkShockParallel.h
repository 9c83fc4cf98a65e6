/**
 * @file vtkShockParallel.h
 * @brief Private MPI helpers of the shock filters, each on an explicit controller.
 *
 * VTK's convention (the vtkP* classes): the serial filters hold no MPI code;
 * what runs across processes takes the vtkMultiProcessController it runs on.
 * Every function here is collective: all processes of the controller call it,
 * in the same order, or none does.
 */
#ifndef vtkShockParallel_h
#define vtkShockParallel_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataSet;
class vtkInformation;
class vtkMultiProcessController;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vtkShockParallel
{
/**
 * The controller a filter's execution runs its collectives on, or nullptr for
 * a serial execution: the output asks for one of several pieces, `controller`
 * has that many processes, and the upstream output is not composite (the
 * pipeline then runs the filter block by block, and the number of blocks
 * differs between processes). `unknown` is set for a piece request that no
 * controller matches (e.g. serial streaming).
 */
vtkMultiProcessController* PieceController(
  vtkAlgorithm* filter, vtkMultiProcessController* controller, vtkInformation* outInfo, bool& unknown);

/**
 * The point ghost marks as the point data holds them now (vtkDataSet caches
 * GetPointGhostArray, which goes stale when MarkPointOwners replaces them).
 */
vtkUnsignedCharArray* PointGhosts(vtkDataSet* data);

/// Whether the filter's upstream produces composite data (the pipeline then runs it block by block).
bool UpstreamIsComposite(vtkAlgorithm* filter);

/// Replace values[0..count) by their sums over all processes.
void Sum(vtkMultiProcessController* controller, double* values, int count);

/// The number of processes for which `flag` is true.
int Count(vtkMultiProcessController* controller, bool flag);

/// high - low of the union of the processes' ranges (those with `has`), or 0 when none.
double GlobalRangeWidth(vtkMultiProcessController* controller, bool has, const double range[2]);

/**
 * Whether every process holds the same non-empty data set (same numbers of
 * points and cells, same coordinates): replicated, not split. Such data is
 * filtered once, on process 0.
 */
bool Replicated(vtkMultiProcessController* controller, vtkDataSet* input);

/**
 * The piece's own cells: those not marked DUPLICATECELL, with the points they
 * use (the others are dropped); returns `piece` itself when it has no ghost cells.
 */
vtkSmartPointer<vtkPolyData> OwnedCells(vtkPolyData* piece);

/**
 * The output of a surface filter's piece: OwnedCells of the filtered piece,
 * without the global ids made for it (those `input` did not have).
 */
vtkSmartPointer<vtkPolyData> OwnedPiece(vtkPolyData* filtered, vtkPolyData* input);

/**
 * `piece` (without ghost cells) with `layers` layers of its neighbours' cells
 * appended by vtkGhostCellsGenerator (marked DUPLICATECELL, their points
 * DUPLICATEPOINT; each point of the whole mesh is non-ghost on exactly one
 * process). The points first get global ids (vtkGenerateGlobalIds) unless
 * they have some: the key of the exchanges and of the owners' marks.
 * The generator may renumber the piece's own points and cells.
 */
vtkSmartPointer<vtkPolyData> WithGhostCells(
  vtkMultiProcessController* controller, vtkPolyData* piece, int layers, std::string& error);

/**
 * What one process filters of a surface: the serial input, or its piece with
 * ghost cells, or nothing (a replicated input is filtered by process 0 only).
 */
struct SurfacePiece
{
  /// The controller of the collectives, or nullptr for a serial (or replicated) execution.
  vtkMultiProcessController* controller = nullptr;
  /// Replicated input on a process other than 0: the output is empty.
  bool skip = false;
  /// What to filter: `input`, or the owned piece with ghost cells appended.
  vtkSmartPointer<vtkPolyData> work;
};

/**
 * Collective start of a surface filter's execution. All processes agree on
 * failure: when any has `localError` (e.g. an unusable input), every one
 * returns false, with its own message or one naming the process that failed.
 * Then a replicated input is recognised; otherwise the piece (without the
 * ghost cells it may have come with: their depth cannot be checked, as the
 * pipeline stamps DATA_NUMBER_OF_GHOST_LEVELS with the request whatever the
 * source made) gets `layers` layers of ghost cells from WithGhostCells, and
 * its points the owners' marks of MarkPointOwners.
 */
bool PrepareSurfacePiece(vtkMultiProcessController* controller, vtkPolyData* input,
  const std::string& localError, int layers, SurfacePiece& piece, std::string& error);

/// Whether any process has `failed` (collective); `error` names another process when this one did not fail.
bool AnyFailed(vtkMultiProcessController* controller, bool failed, std::string& error);

/**
 * Exchange of per-point values (3 doubles each) between pieces: each process
 * sends the values of the points it owns to the processes that need them.
 * Set up once per mesh from the points' global ids; then Exchange may be
 * called any number of times (collective).
 */
class PointExchange
{
public:
  /**
   * `owned`: per local point, 1 when this process owns it; `needed`: per local
   * point, 1 when this process needs its owner's values.
   */
  void Setup(vtkMultiProcessController* controller, const vtkIdType* globalIds,
    const std::vector<char>& owned, const std::vector<char>& needed);
  /// Overwrite the needed points' values (3 per point) with their owners'.
  void Exchange(double* values);
  /// Points this process receives per exchange.
  std::int64_t ReceivedPoints() const { return this->Received; }
  /// Points this process sends per exchange.
  std::int64_t SentPoints() const { return this->Sent; }

private:
  vtkMultiProcessController* Controller = nullptr;
  /// Per other process: local points whose values go there, in its order.
  std::vector<std::vector<vtkIdType>> SendPoints;
  /// Per other process: local points whose values come from there, in its order.
  std::vector<std::vector<vtkIdType>> ReceivePoints;
  std::int64_t Received = 0;
  std::int64_t Sent = 0;
};
}

#endif
