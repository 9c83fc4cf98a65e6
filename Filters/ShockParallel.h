/**
 * @file ShockParallel.h
 * @brief Private MPI helpers of the shock filters, each on an explicit controller.
 *
 * VTK's convention (the vtkP* classes): the serial filters hold no MPI code;
 * what runs across processes takes the vtkMultiProcessController it runs on.
 * Every function here is collective: all processes of the controller call it,
 * in the same order, or none does.
 */
#ifndef ShockParallel_h
#define ShockParallel_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataSet;
class vtkIdList;
class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace ShockParallel
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
 * GetPointGhostArray, which goes stale when the owners' marks are replaced).
 */
vtkUnsignedCharArray* PointGhosts(vtkDataSet* data);

/**
 * The halo exchange of an image piece (ShockImageHalo.cxx, collective):
 * `array` holds the samples of `held` (a sample extent: points, or cells),
 * which contains the process's piece `own`; the result holds those of
 * `grown`, `own` with `layers` more samples on every axis the pieces together
 * span, clamped to the box around all the held extents (the same on every
 * process, whatever each pipeline says of the whole extent). The samples
 * outside `held` are received point to point from the processes whose held
 * extents have them (held extents may overlap: a piece read with part of its
 * halo). When the held extents do not cover a process's grown extent, that
 * process keeps its own piece (the same decision everywhere). An empty piece
 * (null `array`) takes part and gets nullptr.
 */
vtkSmartPointer<vtkDataArray> GrowImageSamples(vtkMultiProcessController* controller, vtkDataArray* array,
  const int held[6], const int own[6], int layers, int grown[6]);

/**
 * A piece's halo without a copy of the piece (shock::LayeredSignal): when the
 * grown extent differs from the piece only along its last axis of more than
 * one sample, and the piece's array holds exactly the piece (float, double or
 * 8-bit, contiguous), the halo layers below and above the piece, each with
 * the shock::LayeredSignalOverlap layers of the piece beside it, in arrays of
 * their own; the piece is read where it lies.
 */
struct ImageLayers
{
  bool used = false;                   ///< the halo came in layers (else as one grown array)
  vtkDataArray* piece = nullptr;       ///< the piece's own array
  vtkSmartPointer<vtkDataArray> below; ///< null when the piece starts at the grown extent's first layer
  vtkSmartPointer<vtkDataArray> above; ///< null when it ends at the last
  vtkIdType pieceFirst = 0;            ///< the piece's layers in the grown extent: [pieceFirst, pieceEnd)
  vtkIdType pieceEnd = 0;
};

/**
 * The axis along which the extent `halo` (points, or cells) adds layers to
 * `piece` when it does so only along its last axis of more than one sample;
 * -1 when it grows along another axis too.
 */
int HaloLayersAxis(const int piece[6], const int halo[6]);

/// Whether the kernel can read `array` in place as a piece beside its halo layers
/// (ImageLayers): float, double or unsigned 8-bit, contiguous.
bool ReadableInLayers(vtkDataArray* array);

/**
 * GrowImageSamples, the halo in layers when `layered` is given and the piece
 * allows (ImageLayers; then nullptr is returned and `layered->used` is set).
 * The same exchange on every process, whichever way each one stores it.
 */
vtkSmartPointer<vtkDataArray> GrowImageSamples(vtkMultiProcessController* controller, vtkDataArray* array,
  const int held[6], const int own[6], int layers, int grown[6], ImageLayers* layered);

/**
 * The image piece `own` (a point extent within `input`'s; null: `input`'s
 * whole extent) with a halo of `layers` samples of `array` around it
 * (GrowImageSamples), and of the blanking marks when any process's piece has
 * some (`hidden`: this one's has), as an image of its own holding only that
 * array (as its scalars) and those marks; nullptr for an empty piece.
 * With `layered` and no blanking on any process, the halo may come in layers
 * (ImageLayers): the image then holds no array. Collective: every process
 * takes part, empty pieces too (null `array`).
 */
vtkSmartPointer<vtkImageData> ImageWithHalo(vtkMultiProcessController* controller, vtkImageData* input,
  const int* own, vtkDataArray* array, bool cellData, bool hidden, int layers, ImageLayers* layered = nullptr);

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

/// The ids 0 .. n-1 (the rows of a copy, for vtkDataSetAttributes::CopyData).
vtkSmartPointer<vtkIdList> Sequence(vtkIdType n);

/**
 * The piece's own cells: those not marked DUPLICATECELL, with the points they
 * use (the others are dropped); returns `piece` itself when it has no ghost cells.
 */
vtkSmartPointer<vtkPolyData> OwnedCells(vtkPolyData* piece);

/**
 * Which point and cell arrays of a piece its ghost rings carry: every one, or
 * those named (the arrays a filter reads; the ghost marks and the point global
 * ids always travel). The arrays left behind reach the output from the owned
 * piece unchanged (OwnedPiece), so a filter carries only what it reads.
 */
struct CarriedArrays
{
  bool all = true;
  std::vector<std::string> point, cell;
};

/// `owned` with only the arrays `carried` names (points and cells shared), or `owned` itself.
vtkSmartPointer<vtkPolyData> Carrying(vtkPolyData* owned, const CarriedArrays& carried);

/**
 * The output of a surface filter's piece: `piece.owned` (the piece's own
 * cells, with every array) where `filtered` (the filter's result on
 * `piece.work`, the piece WithGhostCells made: own points first, each kind's
 * own cells before its ghost cells; its cells counted by the piece when
 * ReleaseGeometry dropped them) changed it: the filtered points, the arrays the filter made or
 * replaced (their own rows), the owners' point marks, and the attribute roles
 * the filter changed. Arrays the filter left alone are the owned piece's, so
 * the global ids the rings made (those the input did not have) and the ghost
 * cells' marks are not in it.
 */
struct SurfacePiece;
vtkSmartPointer<vtkPolyData> OwnedPiece(vtkPolyData* filtered, const SurfacePiece& piece);

/**
 * `piece` (without ghost cells) with `layers` rings of its neighbours' cells
 * (ShockGhostCells.h): point global ids (the input's, else made from the
 * coordinates of the points on the pieces' borders: coincident points of
 * different pieces are one point), each ring fetched from the processes that
 * hold its points in one exchange. The result holds the piece's points and
 * cells first (same order), then the ghost ones; ghost cells are marked
 * DUPLICATECELL, and every point but those its process owns DUPLICATEPOINT
 * (a shared point is owned by the lowest process whose own cells use it, so
 * each point of the whole mesh is unmarked on exactly one process).
 * `cellRings`, when given, receives each cell's ring (0: the piece's own,
 * k: the k-th ring around them). Collective.
 */
vtkSmartPointer<vtkPolyData> WithGhostCells(vtkMultiProcessController* controller, vtkPolyData* piece, int layers,
  std::string& error, std::vector<unsigned char>* cellRings = nullptr);

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
  /// The piece's own cells (OwnedCells of the input) that `work` starts with.
  vtkSmartPointer<vtkPolyData> owned;
  /// ReleaseGeometry dropped `work`'s points and cells; these are their counts.
  bool released = false;
  vtkIdType workPoints = 0;
  int workPointType = 0;
  std::array<vtkIdType, 4> workCells{}; ///< verts, lines, polygons, strips
  /// The rings `work` has around the own cells, and each of its cells' ring (0: own).
  int rings = 0;
  std::vector<unsigned char> cellRing;
};

/**
 * Drop the points and cells of `piece.work`, the copy of the piece with its
 * rings that WithGhostCells assembled, keeping their counts (and the point
 * type): for a filter that has read them into its own mesh and writes its
 * output from counts (OwnedPiece), so that the copy does not stay through
 * the filter's largest phase. Its point and cell arrays stay. Nothing is done
 * (false) for a serial execution, or when `work` is not such a copy.
 */
bool ReleaseGeometry(SurfacePiece& piece);

/**
 * Collective start of a surface filter's execution. All processes agree
 * (Agree): when any has `localError` (e.g. an unusable input), or their
 * `parameters`, arrays or `selection` (the filtered array, compared with the
 * arrays of non-empty pieces) differ, every one returns false with the same
 * message.
 * Then a replicated input is recognised; otherwise the piece (without the
 * ghost cells it may have come with: their depth cannot be checked, as the
 * pipeline stamps DATA_NUMBER_OF_GHOST_LEVELS with the request whatever the
 * source made) gets `layers` rings of ghost cells, carrying the arrays
 * `carried` names, and the owners' marks from WithGhostCells.
 */
bool PrepareSurfacePiece(vtkMultiProcessController* controller, vtkPolyData* input,
  const std::string& localError, const std::string& parameters, const std::string& selection, int layers,
  const CarriedArrays& carried, SurfacePiece& piece, std::string& error);

/**
 * Whether any process has `failed` (collective, one reduction; the message
 * only when one has). On failure every process gets the same `error`: "process
 * F of P cannot filter its piece: " and the `error` process F had, F the
 * lowest failing process.
 */
bool AnyFailed(vtkMultiProcessController* controller, bool failed, std::string& error);

/**
 * The ghost layers (a surface's rings, an image's halo samples) every piece
 * gets next, the same on every process (collective, one reduction): more than
 * `layers` when a piece's own flow lines `needed` more to be exact (their
 * reach plus the flow's stencil), up to `most`; `layers` when none did, or a
 * process `aborted`. `tooFew`: some piece needed more with `most` already.
 * `anyAborted`, when given: whether some process aborted.
 */
int MoreLayers(vtkMultiProcessController* controller, bool aborted, int needed, int layers, int most, bool& tooFew,
  bool* anyAborted = nullptr);

/**
 * The agreement before a distributed execution (collective, one reduction
 * when all is well): false when a process has a `localError`, or when the
 * processes' `parameters` (a "name=value;..." text of the filter's
 * parameters and the array it filters) or `arrays` (ArraysFingerprintText of
 * the piece; "" for an empty piece, which is not compared) differ. Every
 * process then gets the same one-line `error`, naming the process and what
 * is wrong or differs. `grid` (an image's GridText; "" for a surface, not
 * compared) is compared in the same reduction: pieces of images with
 * different whole extents, origins, spacings or directions do not fit together.
 */
bool Agree(vtkMultiProcessController* controller, const std::string& localError,
  const std::string& parameters, const std::string& arrays, std::string& error,
  const std::string& grid = std::string());

/**
 * The point and cell arrays of a piece as a "name (type, components);..."
 * text in name order, without the ghost marks; "" for a piece without points.
 */
std::string ArraysFingerprintText(vtkDataSet* piece);

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
  /// Per local point (`count` of them): 1 when Exchange sends its values to another process.
  std::vector<char> SentMask(std::int64_t count) const;

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
