/**
 * meshbench: timings of the mesh shock filters on real scanned meshes.
 *
 * Measures, like shockbench, the time "inside the filter": the wall time of
 * Update() on a filter whose input mesh is prepared beforehand and given with
 * SetInputData, Modified() between repetitions (and its points' Modified(), so that
 * every run prepares the mesh as a first execution does; --keep-mesh measures
 * re-executions with the kept mesh instead); best and median of N runs,
 * runs disturbed by other processes (CPU time of other processes > 5 % of the
 * run's wall time, from /proc/stat) replaced by extra runs. The filters' own
 * timers split each run into phases.
 *
 * Meshes: the scans of Debian's libcgal-demo package (Benchmarks/get_meshes.sh
 * puts them in the mesh directory), read with shockio::ReadMesh and refined by
 * Loop subdivision (vtkLoopSubdivisionFilter; each level multiplies the vertex
 * count by about 4). When a file is missing, a synthetic stand-in of the same
 * vertex count (a tessellated cube) is used instead, and the output says so.
 *
 * Modes (one per run; run each mesh size in its own process so that the
 * memory peak is the filter's):
 *  - colors: vtkPolyDataShockAdvectionFilter on per-vertex RGB colours (the
 *    paper's Table 2, "Color"): the mesh gets a deterministic pattern of
 *    coloured regions (Voronoi cells of fixed random seeds), blurred by
 *    umbrella smoothing so that every colour edge is a blurred edge, stored as
 *    unsigned char RGB. Tables: the t = 4096 target, time vs t for the fixed,
 *    composed and naive flows, 1 thread vs --threads (default all). Default:
 *    armadillo, 2 levels (~416K vertices).
 *  - sharpen: vtkPolyDataShockSharpenFilter (the paper's Table 3): t = 2048
 *    with 1 smoothing pass (the target), time vs t for --times with 1 pass
 *    (the paper's Table 2, "Positions"), then the phase table for 0, 1, 2, 4,
 *    8 and 16 smoothing passes. Default: ChineseDragon-10kv, 3 levels (~640K
 *    vertices).
 *
 * Peak memory: the high-water mark of the resident set (VmHWM) is reset
 * (/proc/self/clear_refs) after the mesh is prepared; the peak of the first
 * filter run above the resident set just before it is reported per vertex.
 *
 * Markdown on stdout, progress on stderr.
 */
#include "BenchmarkSupport.h"
#include "ShockMeshIO.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkLoopSubdivisionFilter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataShockAdvectionFilter.h"
#include "vtkPolyDataShockSharpenFilter.h"
#include "vtkSmartPointer.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
using namespace shockbench;

// =============================================================================
// Memory and threads (the rest: BenchmarkSupport.h)
// =============================================================================

/// "all (2)" for 0 (the filters' "all cores"), else the number.
std::string ThreadsText(int threads)
{
  return threads > 0 ? std::to_string(threads) : "all (" + std::to_string(HardwareThreads()) + ")";
}

/// A "VmRSS"/"VmHWM" figure of /proc/self/status in bytes, or -1.
long long StatusBytes(const std::string& key)
{
  const std::string value = ProcField("/proc/self/status", key);
  return value == "unknown" ? -1 : 1024LL * std::atoll(value.c_str());
}

/// Resets VmHWM to the current resident set (Linux >= 4.0); false if not possible.
bool ResetPeakResidentSet()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

// =============================================================================
// Options
// =============================================================================

struct Options
{
  std::string mode;        ///< "colors" or "sharpen"
  std::string meshDir;     ///< where get_meshes.sh put the .off files
  std::string mesh;        ///< file name without ".off"; empty: the mode's default
  int levels = -1;         ///< Loop subdivision levels; -1: the mode's default
  int threads = 0;         ///< threads of the target run and tables; 0: all
  int reps = 3;            ///< runs per measurement (best and median)
  int retries = 3;         ///< extra runs allowed to replace disturbed ones
  double disturbance = 0.05; ///< disturbed: other processes used > this x wall time in CPU s
  double maxRunSeconds = 60; ///< a measurement whose first run takes longer is not repeated
  int cap = 64;            ///< maximum flow updates K of the composed and naive flows
  std::vector<double> times{ 1, 4, 16, 64, 256, 1024, 4096 };
  bool flows[3] = { true, true, true }; ///< fixed, composed, naive
  double targetTime = -1;  ///< t of the target run; -1: 4096 (colors), 2048 (sharpen)
  std::vector<double> smoothing{ 0, 1, 2, 4, 8, 16 }; ///< sharpen: smoothing passes of the phase table
  int blurPasses = 16;     ///< colors: umbrella smoothing passes of the pattern
  double maxLoad = 0.5;    ///< wait for a 1-minute load average below this before starting
  double waitMinutes = 15; ///< at most this long
  std::string dump;        ///< write the input and the target result as DUMP-input.ply, DUMP-output.ply
  bool keepMesh = false;   ///< re-executions keep the prepared mesh (input unchanged between runs)
  std::string writeInput;  ///< write the mode's input mesh there and exit (for Benchmarks/userbench.sh)
};

std::string DefaultMeshDir()
{
  if (const char* dir = std::getenv("SHOCK_MESH_DIR"))
  {
    return dir;
  }
  if (const char* cache = std::getenv("XDG_CACHE_HOME"))
  {
    return std::string(cache) + "/shockfilters/meshes";
  }
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/shockfilters/meshes";
}

// =============================================================================
// Meshes
// =============================================================================

/// Vertex counts of the scans get_meshes.sh fetches (for same-size stand-ins).
const std::vector<std::pair<std::string, int>>& KnownMeshes()
{
  static const std::vector<std::pair<std::string, int>> meshes = { { "ChineseDragon-10kv", 10000 },
    { "armadillo", 26002 }, { "bunny00", 37706 }, { "fandisk_large", 15843 },
    { "refined_elephant", 44460 } };
  return meshes;
}

struct BenchMesh
{
  vtkSmartPointer<vtkPolyData> mesh;
  std::string description; ///< for the report: source, sizes, subdivision
};

/// Runs a filter on 'input' and returns a copy of its polydata output.
template <typename Filter>
vtkSmartPointer<vtkPolyData> RunMeshFilter(Filter* filter, vtkPolyData* input)
{
  filter->SetInputData(input);
  filter->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

/**
 * A cube of about 'vertices' vertices (subdivided faces, shared edges and
 * corners), triangulated: the stand-in for a missing scan.
 */
vtkSmartPointer<vtkPolyData> StandInCube(int vertices)
{
  vtkNew<vtkTessellatedBoxSource> box;
  // A box of level n has 6 n^2 + 2 points.
  box->SetLevel(std::max(1, static_cast<int>(std::lround(std::sqrt((vertices - 2) / 6.0)))));
  box->QuadsOn();
  box->Update();
  vtkNew<vtkTriangleFilter> triangulate;
  return RunMeshFilter(triangulate.Get(), box->GetOutput());
}

BenchMesh PrepareMesh(const std::string& name, int levels, const std::string& meshDir)
{
  BenchMesh result;
  const std::string path = meshDir + "/" + name + ".off";
  double start = Now();
  vtkSmartPointer<vtkPolyData> base;
  std::string source;
  if (std::filesystem::exists(path))
  {
    std::string error;
    base = shockio::ReadMesh(path, error);
    if (!base)
    {
      std::cerr << "cannot read " << path << ": " << error << "\n";
      std::exit(2);
    }
    source = "`" + name + ".off` (libcgal-demo, " + std::to_string(base->GetNumberOfPoints()) +
      " vertices, " + std::to_string(base->GetNumberOfPolys()) + " faces)";
  }
  else
  {
    int vertices = 10000;
    for (const auto& [known, count] : KnownMeshes())
    {
      vertices = known == name ? count : vertices;
    }
    std::cerr << "NOTE: " << path << " is missing (run Benchmarks/get_meshes.sh): using a synthetic "
              << "stand-in\n";
    base = StandInCube(vertices);
    source = "**synthetic stand-in** (`" + path + "` missing: tessellated cube of " +
      std::to_string(base->GetNumberOfPoints()) + " vertices, the size of " + name + ")";
  }
  vtkNew<vtkTriangleFilter> triangulate; // Loop subdivision takes triangles only
  base = RunMeshFilter(triangulate.Get(), base);
  std::cerr << "read " << name << " in " << Seconds(Now() - start) << " s\n";

  start = Now();
  result.mesh = base;
  if (levels > 0)
  {
    vtkNew<vtkLoopSubdivisionFilter> loop;
    loop->SetNumberOfSubdivisions(levels);
    result.mesh = RunMeshFilter(loop.Get(), base);
  }
  std::cerr << "subdivided " << levels << "x in " << Seconds(Now() - start) << " s: "
            << result.mesh->GetNumberOfPoints() << " vertices, " << result.mesh->GetNumberOfPolys()
            << " triangles\n";
  result.description = source + ", Loop-subdivided " + std::to_string(levels) + "x " +
    "(vtkLoopSubdivisionFilter): **" + std::to_string(result.mesh->GetNumberOfPoints()) +
    " vertices, " + std::to_string(result.mesh->GetNumberOfPolys()) + " triangles**";
  return result;
}

/// The distinct edges of a triangle mesh, as (smaller, larger) point ids.
std::vector<std::pair<vtkIdType, vtkIdType>> Edges(vtkPolyData* mesh)
{
  std::vector<std::pair<vtkIdType, vtkIdType>> edges;
  edges.reserve(3 * static_cast<size_t>(mesh->GetNumberOfPolys()));
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(size, ids);)
  {
    for (vtkIdType k = 0; k < size; ++k)
    {
      const vtkIdType a = ids[k], b = ids[(k + 1) % size];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

/// splitmix64: the same numbers on every platform (unlike the std distributions).
struct Random
{
  std::uint64_t state;
  double Uniform()
  {
    std::uint64_t z = (this->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

/**
 * Gives the mesh unsigned char RGB point colours "Colors": the Voronoi cells
 * of 32 fixed random seeds in the bounding box, each a random saturated colour
 * (sharp colour edges where cells meet), then 'blurPasses' passes of uniform
 * umbrella smoothing (each vertex becomes the mean of itself and its
 * neighbours), so that the edges are blurred over a few edge lengths.
 */
void PaintBlurredColours(vtkPolyData* mesh, int blurPasses)
{
  double bounds[6];
  mesh->GetBounds(bounds);
  Random random{ 20150713 };
  struct Seed
  {
    std::array<double, 3> position;
    std::array<double, 3> colour;
  };
  std::vector<Seed> seeds(32);
  for (Seed& seed : seeds)
  {
    for (int k = 0; k < 3; ++k)
    {
      seed.position[k] = bounds[2 * k] + random.Uniform() * (bounds[2 * k + 1] - bounds[2 * k]);
    }
    // A random hue, full saturation, varied brightness.
    const double hue = 6.0 * random.Uniform();
    const double value = 0.55 + 0.45 * random.Uniform();
    for (int k = 0; k < 3; ++k)
    {
      const double h = std::fmod(hue + 2.0 * k, 6.0);
      seed.colour[k] = 255.0 * value * std::clamp(std::abs(h - 3.0) - 1.0, 0.0, 1.0);
    }
  }
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<double> colours(3 * static_cast<size_t>(n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    const Seed* nearest = &seeds[0];
    double best = std::numeric_limits<double>::max();
    for (const Seed& seed : seeds)
    {
      const double d = std::pow(x[0] - seed.position[0], 2) + std::pow(x[1] - seed.position[1], 2) +
        std::pow(x[2] - seed.position[2], 2);
      if (d < best)
      {
        best = d;
        nearest = &seed;
      }
    }
    std::copy(nearest->colour.begin(), nearest->colour.end(), &colours[3 * p]);
  }

  const auto edges = Edges(mesh);
  std::vector<double> sums(colours.size());
  std::vector<int> degree(static_cast<size_t>(n));
  for (const auto& [a, b] : edges)
  {
    ++degree[a];
    ++degree[b];
  }
  for (int pass = 0; pass < blurPasses; ++pass)
  {
    sums = colours; // the vertex itself
    for (const auto& [a, b] : edges)
    {
      for (int k = 0; k < 3; ++k)
      {
        sums[3 * a + k] += colours[3 * b + k];
        sums[3 * b + k] += colours[3 * a + k];
      }
    }
    for (vtkIdType p = 0; p < n; ++p)
    {
      for (int k = 0; k < 3; ++k)
      {
        colours[3 * p + k] = sums[3 * p + k] / (1.0 + degree[p]);
      }
    }
  }

  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName(shockio::PointColorsName);
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(n);
  for (size_t i = 0; i < colours.size(); ++i)
  {
    rgb->SetValue(static_cast<vtkIdType>(i), static_cast<unsigned char>(std::lround(colours[i])));
  }
  mesh->GetPointData()->SetScalars(rgb);
}

void WriteForLook(vtkPolyData* mesh, const std::string& path)
{
  std::string error;
  if (shockio::WriteMesh(mesh, path, error))
  {
    std::cerr << "wrote " << path << "\n";
  }
  else
  {
    std::cerr << "cannot write " << path << ": " << error << "\n";
  }
}

// =============================================================================
// Measurement
// =============================================================================

/// One run of a filter: wall time of Update() and the filter's own figures.
struct RunRecord
{
  double wall = 0.0;
  double setup = 0.0;     ///< LastSetupSeconds: mesh preparation
  double flow = 0.0;      ///< LastFlowSeconds
  double advection = 0.0; ///< LastAdvectionSeconds
  double fitSetup = 0.0;  ///< sharpen: LastFitSetupSeconds
  double fitSolve = 0.0;  ///< sharpen: LastFitSolveSeconds
  std::uint64_t steps = 0;
  int iterations = 0;
  double residual = 0.0;
  long long flipped = 0;
  double displacement = 0.0;
  double others = 0.0; ///< CPU seconds of other processes during the run
  bool disturbed = false;

  /// The part of the wall time outside the filter's timers.
  double Other() const
  {
    return std::max(0.0, this->wall - this->setup - this->flow - this->advection - this->fitSetup - this->fitSolve);
  }
};

RunRecord ReadRecord(vtkShockAdvectionFilter* filter, double wall)
{
  RunRecord record;
  record.wall = wall;
  record.setup = filter->GetLastSetupSeconds();
  record.flow = filter->GetLastFlowSeconds();
  record.advection = filter->GetLastAdvectionSeconds();
  record.steps = filter->GetLastTraceSteps();
  if (auto* sharpen = vtkPolyDataShockSharpenFilter::SafeDownCast(filter))
  {
    record.fitSetup = sharpen->GetLastFitSetupSeconds();
    record.fitSolve = sharpen->GetLastFitSolveSeconds();
    record.iterations = sharpen->GetLastSolverIterations();
    record.residual = sharpen->GetLastSolverResidual();
    record.flipped = static_cast<long long>(sharpen->GetLastFlippedTriangles());
    record.displacement = sharpen->GetLastMaxDisplacement();
  }
  return record;
}

/// Best and median of the repetitions of one configuration.
struct Measurement
{
  RunRecord best;        ///< the fastest run (its phases are reported)
  double median = 0.0;
  int runs = 0;          ///< runs the statistics are over
  bool disturbed = false; ///< they include disturbed runs (not enough clean ones)
  long long peakBytes = -1; ///< peak resident set of the first run above the one before it
};

/// Collects the errors of a filter (a failed benchmark run stops the program).
void FailOnError(vtkObject*, unsigned long, void*, void* callData)
{
  std::cerr << "ERROR: " << (callData ? static_cast<const char*>(callData) : "filter failed") << "\n";
  std::exit(1);
}

/**
 * Runs 'filter' (input and parameters set) reps times plus retries for
 * disturbed runs; with 'probeMemory', the first run's memory peak.
 */
Measurement Measure(vtkShockAdvectionFilter* filter, const Options& options, const std::string& label,
  bool probeMemory = false)
{
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(FailOnError);
  const unsigned long observer = filter->AddObserver(vtkCommand::ErrorEvent, onError);

  Measurement m;
  std::vector<RunRecord> runs;
  int clean = 0;
  while (clean < options.reps && static_cast<int>(runs.size()) < options.reps + options.retries)
  {
    long long baseline = -1;
    if (probeMemory && runs.empty())
    {
      malloc_trim(0); // freed heap would otherwise hide part of the filter's allocations
      baseline = ResetPeakResidentSet() ? StatusBytes("VmRSS") : -1;
    }
    filter->Modified();
    vtkPolyData* input = vtkPolyData::SafeDownCast(filter->GetInputDataObject(0, 0));
    if (!options.keepMesh && input && input->GetPoints())
    {
      input->GetPoints()->Modified(); // a new mesh for the filter: prepared again
    }
    const CpuClock cpu = CpuClock::Read();
    const double start = Now();
    filter->Update();
    RunRecord record = ReadRecord(filter, Now() - start);
    record.others = CpuClock::Read().OthersSince(cpu);
    record.disturbed = record.others > options.disturbance * record.wall + 0.02;
    if (baseline >= 0)
    {
      m.peakBytes = StatusBytes("VmHWM") - baseline;
    }
    clean += record.disturbed ? 0 : 1;
    runs.push_back(record);
    std::cerr << "  " << label << "  run " << runs.size() << ": " << Seconds(record.wall) << " s (setup "
              << Seconds(record.setup) << ", flow " << Seconds(record.flow) << ", advection "
              << Seconds(record.advection);
    if (record.fitSetup + record.fitSolve > 0.0)
    {
      std::cerr << ", fit " << Seconds(record.fitSetup) << " + " << Seconds(record.fitSolve);
    }
    std::cerr << ", other processes " << Fixed(record.others, 2) << " CPU s"
              << (record.disturbed ? ": DISTURBED" : "") << ")\n";
    if (runs.size() == 1 && record.wall > options.maxRunSeconds)
    {
      std::cerr << "  (over " << options.maxRunSeconds << " s: not repeated)\n";
      break;
    }
  }
  filter->RemoveObserver(observer);

  // The clean runs when there are enough, else all of them.
  std::vector<RunRecord> used;
  for (const RunRecord& r : runs)
  {
    if (!r.disturbed || clean < options.reps)
    {
      used.push_back(r);
    }
  }
  std::sort(used.begin(), used.end(), [](const RunRecord& a, const RunRecord& b) { return a.wall < b.wall; });
  m.best = used.front();
  const size_t k = used.size();
  m.median = k % 2 ? used[k / 2].wall : 0.5 * (used[k / 2 - 1].wall + used[k / 2].wall);
  m.runs = static_cast<int>(k);
  m.disturbed = clean < options.reps && clean < static_cast<int>(runs.size());
  return m;
}

/// "best (median)"; † when disturbed runs are included.
std::string BestMedian(const Measurement& m)
{
  const std::string mark = m.disturbed ? " †" : "";
  if (m.runs <= 1)
  {
    return Seconds(m.best.wall) + " (1 run)" + mark;
  }
  return Seconds(m.best.wall) + " (" + Seconds(m.median) + ")" + mark;
}

std::string PeakText(const Measurement& m, vtkIdType vertices)
{
  if (m.peakBytes < 0)
  {
    return "not measured (no /proc/self/clear_refs)";
  }
  return Fixed(m.peakBytes / 1048576.0, 1) + " MiB above the " + "resident set before the run, " +
    Fixed(static_cast<double>(m.peakBytes) / static_cast<double>(vertices), 0) + " bytes per vertex";
}

const char* FlowName(int mode)
{
  return mode == vtkShockAdvectionFilter::FIXED ? "fixed"
    : (mode == vtkShockAdvectionFilter::COMPOSED ? "composed" : "naive");
}

std::string Verdict(double seconds, double target)
{
  return seconds < target ? "**met** (" + Seconds(seconds) + " s < " + Seconds(target) + " s)"
                          : "**NOT met** (" + Seconds(seconds) + " s >= " + Seconds(target) + " s)";
}

// =============================================================================
// colors mode
// =============================================================================

void ColoursBenchmark(const Options& options)
{
  const std::string name = options.mesh.empty() ? "armadillo" : options.mesh;
  const int levels = options.levels < 0 ? 2 : options.levels;
  const double target = options.targetTime < 0 ? 4096 : options.targetTime;
  BenchMesh bench = PrepareMesh(name, levels, options.meshDir);
  double start = Now();
  PaintBlurredColours(bench.mesh, options.blurPasses);
  std::cerr << "painted the colours in " << Seconds(Now() - start) << " s\n";
  const vtkIdType vertices = bench.mesh->GetNumberOfPoints();

  vtkNew<vtkPolyDataShockAdvectionFilter> filter;
  filter->SetInputData(bench.mesh);
  filter->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, shockio::PointColorsName);
  filter->SetSmoothingPasses(1);
  const auto configure = [&](double t, int flowMode, int updates, int threads)
  {
    filter->SetFlowTime(t);
    filter->SetFlowMode(flowMode);
    filter->SetNumberOfFlowUpdates(updates);
    filter->SetNumberOfThreads(threads);
  };

  std::cout << "\n### Mesh\n\n"
            << "- " << bench.description << "\n"
            << "- colours: unsigned char RGB point array, Voronoi cells of 32 fixed random seeds in "
               "random saturated colours, blurred by "
            << options.blurPasses << " umbrella smoothing passes\n"
            << "- filter: vtkPolyDataShockAdvectionFilter on the point colours, 1 smoothing pass, "
               "linear sampling, face-crossing tracing\n";

  // The target: fixed flow at t = 4096, with the memory peak.
  std::cerr << "[target]\n";
  configure(target, vtkShockAdvectionFilter::FIXED, 1, options.threads);
  const Measurement goal = Measure(filter, options, "fixed t=" + Fixed(target, 0), true);
  if (!options.dump.empty())
  {
    WriteForLook(bench.mesh, options.dump + "-input.ply");
    WriteForLook(filter->GetOutput(), options.dump + "-t" + Fixed(target, 0) + ".ply");
  }
  std::cout << "\n### Target: fixed flow, t = " << Fixed(target, 0) << ", threads: "
            << ThreadsText(options.threads) << "\n\n"
            << "Wall time of `Update()`, best of " << options.reps << " (median): **"
            << BestMedian(goal) << " s**; target < 0.5 s: " << Verdict(goal.best.wall, 0.5)
            << ". Phases of the best run: setup " << Seconds(goal.best.setup) << " s, flow "
            << Seconds(goal.best.flow) << " s, advection " << Seconds(goal.best.advection)
            << " s, other " << Seconds(goal.best.Other()) << " s; " << Count(goal.best.steps)
            << " trace steps. Peak memory: " << PeakText(goal, vertices) << ".\n";
  std::cout.flush();

  // Time vs t for the three flows.
  std::cerr << "[time vs t]\n";
  struct Row
  {
    double t;
    int updates;
    Measurement flows[3];
  };
  const int modes[3] = { vtkShockAdvectionFilter::FIXED, vtkShockAdvectionFilter::COMPOSED,
    vtkShockAdvectionFilter::NAIVE };
  std::vector<Row> rows;
  for (const double t : options.times)
  {
    Row row;
    row.t = t;
    row.updates = std::max(1, std::min(options.cap, static_cast<int>(std::lround(t))));
    for (int f = 0; f < 3; ++f)
    {
      if (options.flows[f])
      {
        const int k = f == 0 ? 1 : row.updates;
        configure(t, modes[f], k, options.threads);
        row.flows[f] = Measure(filter, options,
          std::string(FlowName(modes[f])) + " t=" + Fixed(t, 0) + " K=" + std::to_string(k));
      }
    }
    rows.push_back(row);
  }
  std::cout << "\n### Time vs t\n\n"
            << "Threads: " << ThreadsText(options.threads) << ", wall time of `Update()` in seconds, best of "
            << options.reps << " (median). Composed and naive flows use K = min(t, " << options.cap
            << ") flow updates: **capped at " << options.cap
            << "** (the paper uses one update per unit time, K = t).\n\n"
            << "| t | fixed | composed | naive | K (composed/naive) |\n|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows)
  {
    std::cout << "| " << Fixed(r.t, 0);
    for (int f = 0; f < 3; ++f)
    {
      std::cout << " | " << (options.flows[f] ? BestMedian(r.flows[f]) : "-");
    }
    std::cout << " | " << r.updates << " |\n";
  }
  std::cout << "\nPhases of the best run: setup = mesh preparation (topology, geometry), flow = "
               "smoothing + potential + flow (all K updates), advection = tracing + sampling, "
               "other = the rest of `Update()` (conversions to and from double, output arrays). "
               "Steps/trace = trace steps / (traces per pass x K); a pass traces each vertex from "
               "each of its triangles.\n\n"
            << "| t | flow | K | best s | setup s | flow s | advection s | other s | trace steps | "
               "steps/trace |\n|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const double traces = 3.0 * static_cast<double>(bench.mesh->GetNumberOfPolys());
  for (const Row& r : rows)
  {
    for (int f = 0; f < 3; ++f)
    {
      if (!options.flows[f])
      {
        continue;
      }
      const RunRecord& b = r.flows[f].best;
      const int k = f == 0 ? 1 : r.updates;
      std::cout << "| " << Fixed(r.t, 0) << " | " << FlowName(modes[f]) << " | " << k << " | "
                << Seconds(b.wall) << " | " << Seconds(b.setup) << " | " << Seconds(b.flow) << " | "
                << Seconds(b.advection) << " | " << Seconds(b.Other()) << " | " << Count(b.steps)
                << " | " << Fixed(b.steps / (traces * k), 2) << " |\n";
    }
  }
  std::cout.flush();

  // 1 thread vs all.
  std::cerr << "[threads]\n";
  configure(target, vtkShockAdvectionFilter::FIXED, 1, 1);
  const Measurement one = Measure(filter, options, "fixed t=" + Fixed(target, 0) + " threads=1");
  std::cout << "\n### Threads: fixed flow, t = " << Fixed(target, 0) << "\n\n"
            << "Best of " << options.reps << " (median); speed-up = best(1 thread) / best(n).\n\n"
            << "| threads | time s | setup s | flow s | advection s | other s | speed-up |\n"
            << "|---:|---:|---:|---:|---:|---:|---:|\n";
  const std::vector<std::pair<std::string, const Measurement*>> threadRows = { { "1", &one },
    { ThreadsText(options.threads), &goal } };
  for (const auto& [label, m] : threadRows)
  {
    const RunRecord& b = m->best;
    std::cout << "| " << label << " | " << BestMedian(*m) << " | " << Seconds(b.setup) << " | "
              << Seconds(b.flow) << " | " << Seconds(b.advection) << " | " << Seconds(b.Other())
              << " | " << Fixed(one.best.wall / b.wall, 2) << " |\n";
  }
  std::cout.flush();
}

// =============================================================================
// sharpen mode
// =============================================================================

void SharpenBenchmark(const Options& options)
{
  const std::string name = options.mesh.empty() ? "ChineseDragon-10kv" : options.mesh;
  const int levels = options.levels < 0 ? 3 : options.levels;
  const double t = options.targetTime < 0 ? 2048 : options.targetTime;
  BenchMesh bench = PrepareMesh(name, levels, options.meshDir);
  const vtkIdType vertices = bench.mesh->GetNumberOfPoints();
  // The targets: >= 600K vertices in 4 s, >= 2M in 12 s.
  const double target = vertices >= 2000000 ? 12.0 : (vertices >= 600000 ? 4.0 : -1.0);

  vtkNew<vtkPolyDataShockSharpenFilter> filter;
  filter->SetInputData(bench.mesh);
  filter->SetFlowTime(t);
  filter->SetNumberOfThreads(options.threads);
  filter->SetFeatureAngle(180.0);     // the paper: no feature split
  filter->SetFitTargetToProjection(); // the paper's fit target
  filter->SetAnchorWeight(0.0);       // the paper's fit: no anchor
  filter->SetDriftRadius(0.0);        // nor drift removal
  filter->KeepUnmovedNormalsOff();    // the paper's sampling everywhere
  std::cout << "\n### Mesh\n\n"
            << "- " << bench.description << "\n"
            << "- filter: vtkPolyDataShockSharpenFilter, t = " << Fixed(t, 0)
            << ", linear sampling, face-crossing tracing, fixed flow, screening weight 1, "
               "25 iterations of Jacobi-preconditioned CG, no feature angle, projection fit target "
               "(the paper's settings), coincident points "
               "merged, threads: "
            << ThreadsText(options.threads) << "\n";

  std::cerr << "[target]\n";
  filter->SetSmoothingPasses(1);
  const Measurement goal = Measure(filter, options, "t=" + Fixed(t, 0) + " smoothing=1", true);
  if (!options.dump.empty())
  {
    WriteForLook(bench.mesh, options.dump + "-input.ply");
    WriteForLook(filter->GetOutput(), options.dump + "-t" + Fixed(t, 0) + ".ply");
  }
  const RunRecord& g = goal.best;
  std::cout << "\n### Target: t = " << Fixed(t, 0) << ", 1 smoothing pass\n\n"
            << "Wall time of `Update()`, best of " << options.reps << " (median): **" << BestMedian(goal)
            << " s**";
  if (target > 0)
  {
    std::cout << "; target < " << Fixed(target, 0) << " s for >= " << (target > 5 ? "2M" : "600K")
              << " vertices: " << Verdict(g.wall, target);
  }
  std::cout << ". Solver: " << g.iterations << " iterations, relative residual " << g.residual << ", "
            << g.flipped << " flipped triangles, max displacement " << g.displacement
            << " of the bounding-box diagonal. Peak memory: " << PeakText(goal, vertices) << ".\n";
  std::cout.flush();

  // Time vs t, 1 smoothing pass (the paper's Table 2, "Positions" row).
  std::cerr << "[time vs t]\n";
  std::cout << "\n### Time vs t (the paper's Table 2, positions), 1 smoothing pass\n\n"
            << "Wall time of `Update()` in seconds, best of " << options.reps
            << " (median), and its phases as in the table below.\n\n"
            << "| t | total | pre-processing | flow | advection | fitting | trace steps |\n"
            << "|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const double time : options.times)
  {
    filter->SetFlowTime(time);
    const Measurement m =
      time == t ? goal : Measure(filter, options, "t=" + Fixed(time, 0) + " smoothing=1");
    const RunRecord& b = m.best;
    std::cout << "| " << Fixed(time, 0) << " | " << BestMedian(m) << " | "
              << Seconds(b.setup + b.fitSetup) << " | " << Seconds(b.flow) << " | "
              << Seconds(b.advection) << " | " << Seconds(b.fitSolve) << " | " << Count(b.steps)
              << " |\n";
    std::cout.flush();
  }
  filter->SetFlowTime(t);

  std::cerr << "[smoothing passes]\n";
  std::vector<std::pair<int, Measurement>> rows;
  for (const double passes : options.smoothing)
  {
    const int n = static_cast<int>(passes);
    if (n == 1)
    {
      rows.emplace_back(n, goal);
      continue;
    }
    filter->SetSmoothingPasses(n);
    rows.emplace_back(n, Measure(filter, options, "t=" + Fixed(t, 0) + " smoothing=" + std::to_string(n)));
  }
  std::cout << "\n### Phases vs smoothing passes (the paper's Table 3), t = " << Fixed(t, 0) << "\n\n"
            << "Seconds, phases of the best of " << options.reps
            << " runs: pre-processing = mesh preparation (`LastSetupSeconds`: triangles, coincident "
               "points, topology, geometry) + fit system set-up (`LastFitSetupSeconds`); flow = face "
               "normals + smoothing + potential + flow; advection = tracing + sampling of the "
               "normals; fitting = CG solve (`LastFitSolveSeconds`); other = the rest of `Update()` "
               "(output points and arrays); total = wall time of `Update()` (median in parentheses). "
               "The set-up columns split pre-processing.\n\n"
            << "| smoothing passes | pre-processing | flow | advection | fitting | other | total | "
               "(mesh set-up) | (fit set-up) | trace steps |\n"
            << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& [passes, m] : rows)
  {
    const RunRecord& b = m.best;
    std::cout << "| " << passes << " | " << Seconds(b.setup + b.fitSetup) << " | " << Seconds(b.flow)
              << " | " << Seconds(b.advection) << " | " << Seconds(b.fitSolve) << " | "
              << Seconds(b.Other()) << " | " << BestMedian(m) << " | " << Seconds(b.setup) << " | "
              << Seconds(b.fitSetup) << " | " << Count(b.steps) << " |\n";
  }
  std::cout.flush();
}

// =============================================================================
// Command line
// =============================================================================

std::vector<double> ParseList(const std::string& text)
{
  std::vector<double> values;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
  {
    values.push_back(std::atof(item.c_str()));
  }
  return values;
}

/// --write-input: the mesh the mode would measure (colors: with its colours), written to a file.
int WriteInput(const Options& options)
{
  const bool colours = options.mode == "colors";
  const std::string name =
    !options.mesh.empty() ? options.mesh : (colours ? "armadillo" : "ChineseDragon-10kv");
  const int levels = options.levels >= 0 ? options.levels : (colours ? 2 : 3);
  BenchMesh bench = PrepareMesh(name, levels, options.meshDir);
  if (colours)
  {
    PaintBlurredColours(bench.mesh, options.blurPasses);
  }
  std::string error;
  if (!shockio::WriteMesh(bench.mesh, options.writeInput, error))
  {
    std::cerr << "cannot write " << options.writeInput << ": " << error << "\n";
    return 2;
  }
  std::cerr << "wrote " << options.writeInput << "\n";
  return 0;
}

void Usage()
{
  std::cerr
    << "usage: meshbench colors|sharpen [options]\n"
       "  colors                vtkPolyDataShockAdvectionFilter on blurred vertex colours\n"
       "                        (default mesh armadillo, 2 subdivision levels, target t 4096)\n"
       "  sharpen               vtkPolyDataShockSharpenFilter (default ChineseDragon-10kv, 3 levels,\n"
       "                        t 2048)\n"
       "  --mesh-dir DIR        the meshes of Benchmarks/get_meshes.sh (default $SHOCK_MESH_DIR,\n"
       "                        else ${XDG_CACHE_HOME:-~/.cache}/shockfilters/meshes)\n"
       "  --mesh NAME           mesh file NAME.off in the mesh directory\n"
       "  --levels L            Loop subdivision levels (each ~4x the vertices)\n"
       "  --time T              t of the target run\n"
       "  --threads N           threads of the runs (0: all, the default; colors: 1 thread is\n"
       "                        also measured for the speed-up)\n"
       "  --reps N              runs per measurement, best and median reported (default 3)\n"
       "  --retries N           extra runs to replace disturbed ones (default 3)\n"
       "  --disturbance F       a run is disturbed when other processes used more than F x its\n"
       "                        wall time in CPU seconds (+0.02 s) (default 0.05)\n"
       "  --max-run-seconds S   do not repeat a measurement whose first run took longer (default 60)\n"
       "  --cap K               colors: maximum flow updates of composed/naive (default 64)\n"
       "  --times a,b,...       colors, sharpen: t of the time-vs-t table (default 1,4,16,64,256,1024,4096)\n"
       "  --flows a,b,...       colors: among fixed,composed,naive (default all)\n"
       "  --blur N              colors: umbrella smoothing passes of the colours (default 16)\n"
       "  --smoothing a,b,...   sharpen: smoothing passes of the phase table (default 0,1,2,4,8,16)\n"
       "  --max-load L          wait for a 1-minute load average below L first (default 0.5)\n"
       "  --wait-minutes M      ... for at most M minutes, then run anyway (default 15)\n"
       "  --keep-mesh           do not mark the input modified between runs: re-executions\n"
       "                        with the kept mesh (what changing only a parameter costs)\n"
       "  --dump PREFIX         write the input mesh and the target result as PREFIX-*.ply\n"
       "  --write-input FILE    write the mode's input mesh (colors: with its colours) to FILE\n"
       "                        (any format of shockfilter, e.g. .ply) and exit, measuring nothing\n"
       "Markdown on stdout, progress on stderr.\n";
}

bool ParseOptions(int argc, char* argv[], Options& options)
{
  options.meshDir = DefaultMeshDir();
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string
    {
      if (i + 1 >= argc)
      {
        std::cerr << arg << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "colors" || arg == "sharpen")
    {
      options.mode = arg;
    }
    else if (arg == "--mesh-dir")
    {
      options.meshDir = value();
    }
    else if (arg == "--mesh")
    {
      options.mesh = value();
    }
    else if (arg == "--levels")
    {
      options.levels = std::max(0, std::atoi(value().c_str()));
    }
    else if (arg == "--threads")
    {
      options.threads = std::max(0, std::atoi(value().c_str()));
    }
    else if (arg == "--time")
    {
      options.targetTime = std::max(0.0, std::atof(value().c_str()));
    }
    else if (arg == "--reps")
    {
      options.reps = std::max(1, std::atoi(value().c_str()));
    }
    else if (arg == "--retries")
    {
      options.retries = std::max(0, std::atoi(value().c_str()));
    }
    else if (arg == "--disturbance")
    {
      options.disturbance = std::atof(value().c_str());
    }
    else if (arg == "--max-run-seconds")
    {
      options.maxRunSeconds = std::atof(value().c_str());
    }
    else if (arg == "--cap")
    {
      options.cap = std::max(1, std::atoi(value().c_str()));
    }
    else if (arg == "--times")
    {
      options.times = ParseList(value());
    }
    else if (arg == "--flows")
    {
      const std::string list = "," + value() + ",";
      const char* names[3] = { ",fixed,", ",composed,", ",naive," };
      for (int f = 0; f < 3; ++f)
      {
        options.flows[f] = list.find(names[f]) != std::string::npos;
      }
    }
    else if (arg == "--blur")
    {
      options.blurPasses = std::max(0, std::atoi(value().c_str()));
    }
    else if (arg == "--smoothing")
    {
      options.smoothing = ParseList(value());
    }
    else if (arg == "--max-load")
    {
      options.maxLoad = std::atof(value().c_str());
    }
    else if (arg == "--wait-minutes")
    {
      options.waitMinutes = std::atof(value().c_str());
    }
    else if (arg == "--keep-mesh")
    {
      options.keepMesh = true;
    }
    else if (arg == "--dump")
    {
      options.dump = value();
    }
    else if (arg == "--write-input")
    {
      options.writeInput = value();
    }
    else
    {
      if (arg != "-h" && arg != "--help")
      {
        std::cerr << "unknown argument '" << arg << "'\n";
      }
      return false;
    }
  }
  return !options.mode.empty();
}

/// Waits until the 1-minute load average is below options.maxLoad (at most options.waitMinutes).
void WaitForQuietMachine(const Options& options)
{
  const double start = Now();
  for (double load = LoadAverage1(); load >= options.maxLoad; load = LoadAverage1())
  {
    if (Now() - start > 60.0 * options.waitMinutes)
    {
      std::cerr << "load " << load << " still >= " << options.maxLoad << " after " << options.waitMinutes
                << " min: running anyway\n";
      return;
    }
    std::cerr << "load " << load << " >= " << options.maxLoad << ": waiting\n";
    std::this_thread::sleep_for(std::chrono::seconds(30));
  }
}
} // namespace

int main(int argc, char* argv[])
{
  // The sharpening filter logs its solver figures at INFO: meshbench reports them itself.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_WARNING);
  Options options;
  if (!ParseOptions(argc, argv, options))
  {
    Usage();
    return argc > 1 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") ? 0 : 2;
  }
  if (!options.writeInput.empty())
  {
    return WriteInput(options);
  }
  std::ostringstream command;
  for (int i = 0; i < argc; ++i)
  {
    command << (i ? " " : "") << argv[i];
  }
  WaitForQuietMachine(options);
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M:%S %Z", std::localtime(&now));
  std::cout << "## meshbench " << options.mode << "\n\n"
            << "- command: `" << command.str() << "`\n"
            << "- date: " << date << "\n"
            << "- CPU: " << ProcField("/proc/cpuinfo", "model name") << ", " << HardwareThreads()
            << " hardware threads\n"
            << "- RAM: " << ProcField("/proc/meminfo", "MemTotal") << "\n"
            << "- compiler: " << __VERSION__
#ifdef SHOCKBENCH_BUILD_TYPE
            << ", build type " << SHOCKBENCH_BUILD_TYPE
#endif
            << "\n"
            << "- load average at start (1, 5, 15 min): " << LoadAverages() << "\n"
            << "- runs per measurement: best and median of " << options.reps
            << " runs undisturbed by other processes (up to " << options.retries
            << " extra runs replace runs during which other processes used more than "
            << options.disturbance * 100 << "% of the run's wall time in CPU time, from /proc/stat; "
            << "† marks figures that still include disturbed runs)\n";
  std::cout.flush();

  const double start = Now();
  if (options.mode == "colors")
  {
    ColoursBenchmark(options);
  }
  else
  {
    SharpenBenchmark(options);
  }
  std::cout << "\n- load average at end (1, 5, 15 min): " << LoadAverages() << "\n"
            << "- peak RSS of the process (VmHWM since the reset before the target run): "
            << Fixed(StatusBytes("VmHWM") / 1048576.0, 1) << " MiB\n"
            << "- total benchmark time: " << Seconds(Now() - start) << " s\n";
  return 0;
}
