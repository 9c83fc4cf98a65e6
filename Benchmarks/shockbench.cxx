/**
 * shockbench: timings of vtkImageShockAdvectionFilter on synthetic data.
 *
 * Measures the time "inside the filter": the wall time of Update() on a filter
 * whose input is a vtkImageData given with SetInputData (generated beforehand),
 * with Modified() between repetitions. Reports the best (minimum) and the median
 * of N repetitions, the kernel's flow/advection split of the best repetition and
 * the number of tracing steps.
 *
 * Data (deterministic, fixed seed, plain C++ loops):
 *  - image: 1368 x 1824 RGB unsigned char "photo-like" picture (the size of
 *    Table 1 of Prada and Kazhdan 2015): smooth background gradients and
 *    low-frequency texture, several hundred shaded shapes of varied colour and
 *    size, fine stripes on some of them, per-pixel noise, then a Gaussian blur
 *    (sigma 2 px) so that every edge is a blurred edge to sharpen;
 *  - volume: 256^3 float, blurred (sigma 1.5 voxels) spheres and boxes plus mild noise.
 *
 * Modes: table1, threads, volume, tracing, all (several may be given).
 * Markdown tables go to stdout, progress to stderr.
 */
#include "BenchmarkSupport.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageShockAdvectionFilter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataWriter.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using namespace shockbench;

// ----------------------------------------------------------------------------
// Deterministic random numbers (splitmix64: identical on every platform, unlike
// the std:: distributions).
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : State(seed)
  {
  }
  std::uint64_t Next()
  {
    std::uint64_t z = (this->State += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(this->Next() >> 11) * (1.0 / 9007199254740992.0); }
  double Uniform(double a, double b) { return a + (b - a) * this->Uniform(); }
  /// Approximately normal (sum of 4 uniforms), unit variance.
  double Normal()
  {
    double s = 0.0;
    for (int i = 0; i < 4; ++i)
    {
      s += this->Uniform();
    }
    return (s - 2.0) * std::sqrt(3.0);
  }

private:
  std::uint64_t State;
};

// ----------------------------------------------------------------------------
// Separable Gaussian blur on a buffer laid out as [outer][n][inner], along the
// middle axis, clamp-to-edge.
void BlurAxis(std::vector<float>& data, std::int64_t outer, std::int64_t n, std::int64_t inner,
  double sigma)
{
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<float> w(2 * radius + 1);
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k)
  {
    w[k + radius] = static_cast<float>(std::exp(-0.5 * k * k / (sigma * sigma)));
    sum += w[k + radius];
  }
  for (float& v : w)
  {
    v = static_cast<float>(v / sum);
  }
  std::vector<float> line(static_cast<size_t>(n * inner));
  for (std::int64_t o = 0; o < outer; ++o)
  {
    float* base = data.data() + o * n * inner;
    std::fill(line.begin(), line.end(), 0.0f);
    for (std::int64_t i = 0; i < n; ++i)
    {
      float* out = line.data() + i * inner;
      for (int k = -radius; k <= radius; ++k)
      {
        const std::int64_t src = std::min<std::int64_t>(std::max<std::int64_t>(i + k, 0), n - 1);
        const float* in = base + src * inner;
        const float wk = w[k + radius];
        for (std::int64_t j = 0; j < inner; ++j)
        {
          out[j] += wk * in[j];
        }
      }
    }
    std::copy(line.begin(), line.end(), base);
  }
}

// Smooth value noise in [-1, 1]: random values on a lattice of `cell` pixels,
// smoothstep-interpolated.
struct ValueNoise2D
{
  ValueNoise2D(Random& rng, int width, int height, double cell)
    : Cell(cell)
    , NX(static_cast<int>(width / cell) + 2)
    , NY(static_cast<int>(height / cell) + 2)
    , Values(static_cast<size_t>(NX * NY))
  {
    for (double& v : this->Values)
    {
      v = rng.Uniform(-1.0, 1.0);
    }
  }
  double operator()(double x, double y) const
  {
    const double fx = x / this->Cell;
    const double fy = y / this->Cell;
    const int ix = static_cast<int>(fx);
    const int iy = static_cast<int>(fy);
    double tx = fx - ix;
    double ty = fy - iy;
    tx = tx * tx * (3.0 - 2.0 * tx);
    ty = ty * ty * (3.0 - 2.0 * ty);
    const double* row0 = &this->Values[static_cast<size_t>(iy * this->NX)];
    const double* row1 = row0 + this->NX;
    const double a = row0[ix] + tx * (row0[ix + 1] - row0[ix]);
    const double b = row1[ix] + tx * (row1[ix + 1] - row1[ix]);
    return a + ty * (b - a);
  }
  double Cell;
  int NX, NY;
  std::vector<double> Values;
};

// ----------------------------------------------------------------------------
/// A photo-like RGB image, width x height, unsigned char, blurred with sigma 2 px.
vtkSmartPointer<vtkImageData> MakePhotoImage(int width, int height, std::uint64_t seed)
{
  Random rng(seed);
  const int C = 3;
  std::vector<float> rgb(static_cast<size_t>(width) * height * C);

  // Background: a vertical "sky to ground" gradient, a horizontal tint and two
  // octaves of low-frequency texture per channel.
  double top[3], bottom[3], side[3];
  for (int c = 0; c < C; ++c)
  {
    top[c] = rng.Uniform(120.0, 230.0);
    bottom[c] = rng.Uniform(30.0, 140.0);
    side[c] = rng.Uniform(-30.0, 30.0);
  }
  ValueNoise2D coarse(rng, width, height, 96.0);
  ValueNoise2D fine(rng, width, height, 12.0);
  for (int y = 0; y < height; ++y)
  {
    const double v = static_cast<double>(y) / (height - 1);
    for (int x = 0; x < width; ++x)
    {
      const double u = static_cast<double>(x) / (width - 1);
      const double texture = 18.0 * coarse(x, y) + 6.0 * fine(x, y);
      float* p = &rgb[(static_cast<size_t>(y) * width + x) * C];
      for (int c = 0; c < C; ++c)
      {
        p[c] = static_cast<float>(top[c] + (bottom[c] - top[c]) * v + side[c] * u + texture);
      }
    }
  }

  // Shapes: discs, rotated ellipses, rotated rectangles and rings, largest
  // first so that small objects sit on top of large ones. Each is shaded by a
  // linear gradient; some carry fine stripes.
  struct Shape
  {
    int type;
    double cx, cy, a, b, angle;
    double colour[3];
    double shade, shadeAngle;
    double stripes, stripeAngle, stripePeriod;
  };
  const int shapeCount = 450;
  std::vector<Shape> shapes(shapeCount);
  const double minSize = 6.0;
  const double maxSize = 320.0;
  for (Shape& s : shapes)
  {
    s.type = static_cast<int>(rng.Next() % 4);
    s.a = minSize * std::pow(maxSize / minSize, std::pow(rng.Uniform(), 1.6)); // many small, few large
    s.b = s.a * rng.Uniform(0.3, 1.0);
    s.cx = rng.Uniform(-0.05, 1.05) * width;
    s.cy = rng.Uniform(-0.05, 1.05) * height;
    s.angle = rng.Uniform(0.0, M_PI);
    for (double& c : s.colour)
    {
      c = rng.Uniform(10.0, 245.0);
    }
    s.shade = rng.Uniform(0.0, 45.0);
    s.shadeAngle = rng.Uniform(0.0, 2.0 * M_PI);
    s.stripes = rng.Uniform() < 0.25 ? rng.Uniform(5.0, 20.0) : 0.0;
    s.stripeAngle = rng.Uniform(0.0, M_PI);
    s.stripePeriod = rng.Uniform(3.0, 9.0);
  }
  std::sort(shapes.begin(), shapes.end(), [](const Shape& l, const Shape& r) { return l.a > r.a; });
  for (const Shape& s : shapes)
  {
    const double extent = s.a + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(s.cx - extent)));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(s.cx + extent)));
    const int y0 = std::max(0, static_cast<int>(std::floor(s.cy - extent)));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(s.cy + extent)));
    const double ca = std::cos(s.angle), sa = std::sin(s.angle);
    const double cs = std::cos(s.shadeAngle), ss = std::sin(s.shadeAngle);
    const double ct = std::cos(s.stripeAngle), st = std::sin(s.stripeAngle);
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        const double dx = x - s.cx, dy = y - s.cy;
        const double lu = (ca * dx + sa * dy) / s.a;
        const double lv = (-sa * dx + ca * dy) / s.b;
        bool inside = false;
        switch (s.type)
        {
          case 0: // disc (a circle of radius a)
            inside = dx * dx + dy * dy <= s.a * s.a;
            break;
          case 1: // ellipse
            inside = lu * lu + lv * lv <= 1.0;
            break;
          case 2: // rectangle
            inside = std::abs(lu) <= 0.75 && std::abs(lv) <= 0.75;
            break;
          default: // ring
          {
            const double r2 = lu * lu + lv * lv;
            inside = r2 <= 1.0 && r2 >= 0.45;
          }
        }
        if (!inside)
        {
          continue;
        }
        const double shade = s.shade * (cs * dx + ss * dy) / s.a;
        const double stripe =
          s.stripes > 0.0 ? s.stripes * std::sin(2.0 * M_PI * (ct * dx + st * dy) / s.stripePeriod) : 0.0;
        float* p = &rgb[(static_cast<size_t>(y) * width + x) * C];
        for (int c = 0; c < C; ++c)
        {
          p[c] = static_cast<float>(s.colour[c] + shade + stripe);
        }
      }
    }
  }

  // Sensor-like noise, then the optical blur.
  for (float& v : rgb)
  {
    v += static_cast<float>(3.0 * rng.Normal());
  }
  const double sigma = 2.0;
  BlurAxis(rgb, height, width, C, sigma);          // x
  BlurAxis(rgb, 1, height, static_cast<std::int64_t>(width) * C, sigma); // y

  vtkNew<vtkUnsignedCharArray> array;
  array->SetName("RGB");
  array->SetNumberOfComponents(C);
  array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  unsigned char* out = array->GetPointer(0);
  for (size_t i = 0; i < rgb.size(); ++i)
  {
    out[i] = static_cast<unsigned char>(std::min(255.0f, std::max(0.0f, std::round(rgb[i]))));
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  image->GetPointData()->SetScalars(array);
  return image;
}

/// A n^3 float volume: blurred spheres and boxes on a soft background, mild noise.
vtkSmartPointer<vtkImageData> MakeVolume(int n, std::uint64_t seed)
{
  Random rng(seed);
  const std::int64_t count = static_cast<std::int64_t>(n) * n * n;
  std::vector<float> v(static_cast<size_t>(count));
  for (int z = 0; z < n; ++z)
  {
    for (int y = 0; y < n; ++y)
    {
      for (int x = 0; x < n; ++x)
      {
        v[(static_cast<size_t>(z) * n + y) * n + x] = static_cast<float>(0.1 + 0.1 * z / n);
      }
    }
  }
  const int objects = 90;
  for (int o = 0; o < objects; ++o)
  {
    const bool sphere = rng.Uniform() < 0.6;
    const double r = n * 0.02 * std::pow(12.0, rng.Uniform()); // 0.02 n to 0.24 n
    const double rx = r, ry = r * rng.Uniform(0.5, 1.0), rz = r * rng.Uniform(0.5, 1.0);
    const double cx = rng.Uniform(0.0, n), cy = rng.Uniform(0.0, n), cz = rng.Uniform(0.0, n);
    const float value = static_cast<float>(rng.Uniform(0.2, 1.0));
    const int x0 = std::max(0, static_cast<int>(cx - rx)), x1 = std::min(n - 1, static_cast<int>(cx + rx) + 1);
    const int y0 = std::max(0, static_cast<int>(cy - ry)), y1 = std::min(n - 1, static_cast<int>(cy + ry) + 1);
    const int z0 = std::max(0, static_cast<int>(cz - rz)), z1 = std::min(n - 1, static_cast<int>(cz + rz) + 1);
    for (int z = z0; z <= z1; ++z)
    {
      for (int y = y0; y <= y1; ++y)
      {
        for (int x = x0; x <= x1; ++x)
        {
          const double u = (x - cx) / rx, w = (y - cy) / ry, t = (z - cz) / rz;
          const bool inside = sphere
            ? u * u + w * w + t * t <= 1.0
            : std::abs(u) <= 0.8 && std::abs(w) <= 0.8 && std::abs(t) <= 0.8;
          if (inside)
          {
            v[(static_cast<size_t>(z) * n + y) * n + x] = value;
          }
        }
      }
    }
  }
  for (float& x : v)
  {
    x += static_cast<float>(0.02 * rng.Normal());
  }
  const double sigma = 1.5;
  BlurAxis(v, static_cast<std::int64_t>(n) * n, n, 1, sigma);           // x
  BlurAxis(v, n, n, n, sigma);                                          // y
  BlurAxis(v, 1, n, static_cast<std::int64_t>(n) * n, sigma);           // z

  vtkNew<vtkFloatArray> array;
  array->SetName("Density");
  array->SetNumberOfTuples(count);
  std::copy(v.begin(), v.end(), array->GetPointer(0));
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->GetPointData()->SetScalars(array);
  return image;
}

// ----------------------------------------------------------------------------
struct Options
{
  int reps = 3;
  int cap = 64;               // maximum NumberOfFlowUpdates for composed/naive
  double maxCellSeconds = 60; // stop repeating a cell whose first run exceeds this
  int retries = 3;            // extra runs allowed per measurement to replace disturbed ones
  double cellBudget = 240;    // no retries once a measurement has taken this many seconds
  double disturbance = 0.05;  // a run is disturbed when other processes used > this x wall CPU seconds
  bool volumeSingleThread = true;
  bool flows[3] = { true, true, true }; // table1: fixed, composed, naive
  std::vector<double> times{ 1, 4, 16, 64, 256, 1024, 4096 };
};

struct Config
{
  double time = 64;
  int flowMode = vtkShockAdvectionFilter::FIXED;
  int updates = 1;
  int tracing = vtkShockAdvectionFilter::FACE_CROSSING;
  int threads = 0;
  int smoothing = 1;
};

struct Measurement
{
  std::vector<double> wall; // seconds, per repetition
  double best = 0, median = 0;
  double flow = 0, advection = 0; // of the best repetition
  std::uint64_t steps = 0;
  std::uint64_t truncated = 0;
  bool failed = false;
  bool disturbed = false; // statistics include runs during which other processes used the CPU
};

const char* FlowName(int mode)
{
  return mode == vtkShockAdvectionFilter::FIXED ? "fixed"
    : (mode == vtkShockAdvectionFilter::COMPOSED ? "composed" : "naive");
}

/// Collects the filter's warnings (truncated traces) and errors.
struct MessageLog
{
  std::vector<std::string> warnings;
  std::vector<std::string> errors;
  static void Callback(vtkObject*, unsigned long event, void* clientData, void* callData)
  {
    auto* log = static_cast<MessageLog*>(clientData);
    const std::string text = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? log->errors : log->warnings).push_back(text);
  }
};

/// "N flow lines were cut at the step limit" -> N.
std::uint64_t TruncatedFromWarnings(const std::vector<std::string>& warnings)
{
  std::uint64_t total = 0;
  for (const std::string& w : warnings)
  {
    const auto at = w.find(" flow lines were cut");
    if (at == std::string::npos)
    {
      continue;
    }
    auto begin = at;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(w[begin - 1])))
    {
      --begin;
    }
    total = std::max<std::uint64_t>(total, std::strtoull(w.substr(begin, at - begin).c_str(), nullptr, 10));
  }
  return total;
}

Measurement Run(vtkImageData* input, const Config& config, const Options& options, const std::string& label)
{
  vtkNew<vtkImageShockAdvectionFilter> filter;
  filter->SetInputData(input);
  filter->SetFlowTime(config.time);
  filter->SetFlowMode(config.flowMode);
  filter->SetNumberOfFlowUpdates(config.updates);
  filter->SetTracingMode(config.tracing);
  filter->SetNumberOfThreads(config.threads);
  filter->SetSmoothingPasses(config.smoothing);
  MessageLog log;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(&MessageLog::Callback);
  callback->SetClientData(&log);
  filter->AddObserver(vtkCommand::WarningEvent, callback);
  filter->AddObserver(vtkCommand::ErrorEvent, callback);

  struct Rep
  {
    double wall, flow, advection, foreign;
    bool disturbed;
  };
  std::vector<Rep> runs;
  Measurement m;
  int clean = 0;
  const int maxRuns = options.reps + options.retries;
  double spent = 0.0;
  while (clean < options.reps && static_cast<int>(runs.size()) < maxRuns)
  {
    if (static_cast<int>(runs.size()) >= options.reps && spent > options.cellBudget)
    {
      std::cerr << "  (over " << options.cellBudget << " s spent on this measurement: no retries)\n";
      break;
    }
    log.warnings.clear();
    filter->Modified();
    const CpuClock cpuStart = CpuClock::Read();
    const double start = Now();
    filter->Update();
    const double wall = Now() - start;
    const double foreign = CpuClock::Read().OthersSince(cpuStart);
    spent += wall;
    if (!log.errors.empty())
    {
      m.failed = true;
      m.wall.push_back(wall);
      std::cerr << "  ERROR: " << log.errors.front() << "\n";
      return m;
    }
    // Other processes took a noticeable share of the machine during this run.
    const bool disturbed = foreign > options.disturbance * wall + 0.02;
    runs.push_back({ wall, filter->GetLastFlowSeconds(), filter->GetLastAdvectionSeconds(), foreign,
      disturbed });
    clean += disturbed ? 0 : 1;
    m.steps = filter->GetLastTraceSteps();
    m.truncated = TruncatedFromWarnings(log.warnings);
    std::cerr << "  " << label << "  run " << runs.size() << ": " << Seconds(wall) << " s (flow "
              << Seconds(runs.back().flow) << ", advection " << Seconds(runs.back().advection) << ", "
              << Count(static_cast<double>(m.steps)) << " steps"
              << (m.truncated ? ", " + std::to_string(m.truncated) + " truncated" : std::string())
              << ", other processes " << Fixed(foreign, 2) << " CPU s"
              << (disturbed ? ": DISTURBED" : "") << ")\n";
    if (runs.size() == 1 && wall > options.maxCellSeconds && options.reps > 1)
    {
      std::cerr << "  (first run over " << options.maxCellSeconds << " s: no more repetitions)\n";
      break;
    }
  }
  // Statistics over the undisturbed runs when there are enough, else over all runs.
  std::vector<Rep> used;
  for (const Rep& r : runs)
  {
    if (!r.disturbed || clean < options.reps)
    {
      used.push_back(r);
    }
  }
  m.disturbed = clean < options.reps && clean < static_cast<int>(runs.size());
  std::sort(used.begin(), used.end(), [](const Rep& a, const Rep& b) { return a.wall < b.wall; });
  for (const Rep& r : used)
  {
    m.wall.push_back(r.wall);
  }
  if (!used.empty())
  {
    m.best = used.front().wall;
    m.flow = used.front().flow;
    m.advection = used.front().advection;
    const size_t k = used.size();
    m.median = (k % 2) ? used[k / 2].wall : 0.5 * (used[k / 2 - 1].wall + used[k / 2].wall);
  }
  return m;
}

/// best (median), or best only when there was a single repetition.
std::string BestMedian(const Measurement& m)
{
  if (m.failed)
  {
    return m.wall.empty() ? "-" : "failed";
  }
  const std::string mark = m.disturbed ? " †" : "";
  if (m.wall.size() <= 1)
  {
    return Seconds(m.best) + " (1 run)" + mark;
  }
  return Seconds(m.best) + " (" + Seconds(m.median) + ")" + mark;
}

/// Number of traces per advection pass: every face is traced from each of its corners.
std::uint64_t TracesPerPass(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  std::uint64_t faces = 1, corners = 1;
  for (int d : dims)
  {
    if (d > 1)
    {
      faces *= static_cast<std::uint64_t>(d - 1);
      corners *= 2;
    }
  }
  return faces * corners;
}

// ----------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> PhotoImage()
{
  static vtkSmartPointer<vtkImageData> image;
  if (!image)
  {
    const double start = Now();
    image = MakePhotoImage(1368, 1824, 20150901);
    std::cerr << "generated the 1368 x 1824 RGB image in " << Seconds(Now() - start) << " s\n";
  }
  return image;
}

void Table1(const Options& options)
{
  vtkImageData* image = PhotoImage();
  const std::uint64_t traces = TracesPerPass(image);
  std::cerr << "[table1]\n";
  struct Row
  {
    double t;
    int updates;
    Measurement fixed, composed, naive;
  };
  std::vector<Row> rows;
  for (double t : options.times)
  {
    Row row;
    row.t = t;
    row.updates = std::max(1, std::min(options.cap, static_cast<int>(std::lround(t))));
    Config c;
    c.time = t;
    const std::string at = " t=" + Fixed(t, 0);
    row.fixed.failed = row.composed.failed = row.naive.failed = true; // "not run" unless run
    c.flowMode = vtkShockAdvectionFilter::FIXED;
    if (options.flows[0])
    {
      row.fixed = Run(image, c, options, "fixed" + at);
    }
    c.updates = row.updates;
    const std::string k = " K=" + std::to_string(row.updates);
    c.flowMode = vtkShockAdvectionFilter::COMPOSED;
    if (options.flows[1])
    {
      row.composed = Run(image, c, options, "composed" + at + k);
    }
    c.flowMode = vtkShockAdvectionFilter::NAIVE;
    if (options.flows[2])
    {
      row.naive = Run(image, c, options, "naive" + at + k);
    }
    rows.push_back(row);
  }

  std::cout << "\n### Table 1: time vs t, 1368 x 1824 RGB unsigned char image\n\n"
            << "1 smoothing pass, all threads (" << HardwareThreads() << "), linear sampling, "
            << "face-crossing tracing. Wall time of `Update()` in seconds, best of " << options.reps
            << " (median in parentheses). Composed and naive flows use K = min(t, " << options.cap
            << ") flow updates: **capped at " << options.cap
            << " updates** (the paper uses one update per unit time, K = t).\n\n";
  std::cout << "| t | fixed | composed | naive | K (composed/naive) |\n"
            << "|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows)
  {
    std::cout << "| " << r.t << " | " << BestMedian(r.fixed) << " | " << BestMedian(r.composed)
              << " | " << BestMedian(r.naive) << " | " << r.updates << " |\n";
  }
  std::cout << "\nBreakdown (best run): flow = smoothing + potential + flow computation, "
               "advection = back-tracing + sampling, both as measured by the kernel; "
               "other = the rest of `Update()`: the filter's conversion to and from double and the "
               "kernel's set-up outside its two timers (validity masks, range scan, copies; for "
               "composed, the initial trace positions). "
               "Steps/trace = trace steps / (traces per pass x K), "
            << traces << " traces per pass.\n\n";
  std::cout << "| t | flow mode | K | best s | flow s | advection s | other s | trace steps | steps/trace |\n"
            << "|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows)
  {
    const Measurement* ms[3] = { &r.fixed, &r.composed, &r.naive };
    const int modes[3] = { vtkShockAdvectionFilter::FIXED, vtkShockAdvectionFilter::COMPOSED,
      vtkShockAdvectionFilter::NAIVE };
    for (int i = 0; i < 3; ++i)
    {
      if (!options.flows[i])
      {
        continue;
      }
      const Measurement& m = *ms[i];
      const int k = i == 0 ? 1 : r.updates;
      std::cout << "| " << r.t << " | " << FlowName(modes[i]) << " | " << k << " | " << Seconds(m.best)
                << " | " << Seconds(m.flow) << " | " << Seconds(m.advection) << " | "
                << Seconds(std::max(0.0, m.best - m.flow - m.advection)) << " | " << Count(static_cast<double>(m.steps))
                << " | " << Fixed(static_cast<double>(m.steps) / (static_cast<double>(traces) * k), 2)
                << " |\n";
    }
  }
  std::cout.flush();
}

void Threads(const Options& options)
{
  vtkImageData* image = PhotoImage();
  std::cerr << "[threads]\n";
  const int hw = HardwareThreads();
  std::vector<int> counts{ 1 };
  for (int n = 2; n <= hw; n *= 2)
  {
    counts.push_back(n);
  }
  if (counts.back() != hw)
  {
    counts.push_back(hw);
  }
  std::vector<Measurement> ms;
  for (int n : counts)
  {
    Config c;
    c.time = 1024;
    c.threads = n;
    ms.push_back(Run(image, c, options, "fixed t=1024 threads=" + std::to_string(n)));
  }
  std::cout << "\n### Thread scaling: fixed flow, t = 1024, 1368 x 1824 RGB image\n\n"
            << "Best of " << options.reps << " (median); speed-up = best(1 thread) / best(n threads).\n\n"
            << "| threads | time s | flow s | advection s | speed-up | flow speed-up | advection speed-up |\n"
            << "|---:|---:|---:|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < counts.size(); ++i)
  {
    const Measurement& m = ms[i];
    std::cout << "| " << counts[i] << " | " << BestMedian(m) << " | " << Seconds(m.flow) << " | "
              << Seconds(m.advection) << " | " << Fixed(ms[0].best / m.best, 2) << " | "
              << Fixed(ms[0].flow / m.flow, 2) << " | " << Fixed(ms[0].advection / m.advection, 2)
              << " |\n";
  }
  std::cout.flush();
}

void Volume(const Options& options)
{
  std::cerr << "[volume]\n";
  const double start = Now();
  vtkSmartPointer<vtkImageData> volume = MakeVolume(256, 19990101);
  std::cerr << "generated the 256^3 float volume in " << Seconds(Now() - start) << " s\n";
  const std::uint64_t traces = TracesPerPass(volume);
  std::vector<int> counts{ 0 };
  if (options.volumeSingleThread)
  {
    counts.push_back(1);
  }
  std::vector<Measurement> ms;
  for (int n : counts)
  {
    Config c;
    c.time = 64;
    c.threads = n;
    ms.push_back(Run(volume, c, options,
      "volume fixed t=64 threads=" + (n ? std::to_string(n) : std::string("all"))));
  }
  std::cout << "\n### Volume: 256^3 float, fixed flow, t = 64\n\n"
            << "1 smoothing pass, face-crossing tracing, best of " << options.reps << " (median); "
            << traces << " traces per pass.\n\n"
            << "| threads | time s | flow s | advection s | trace steps | steps/trace |\n"
            << "|---:|---:|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < counts.size(); ++i)
  {
    const Measurement& m = ms[i];
    std::cout << "| " << (counts[i] ? std::to_string(counts[i]) : "all (" + std::to_string(HardwareThreads()) + ")")
              << " | " << BestMedian(m) << " | " << Seconds(m.flow) << " | " << Seconds(m.advection)
              << " | " << Count(static_cast<double>(m.steps)) << " | " << Fixed(static_cast<double>(m.steps) / traces, 2) << " |\n";
  }
  std::cout.flush();
}

void Tracing(const Options& options)
{
  vtkImageData* image = PhotoImage();
  const std::uint64_t traces = TracesPerPass(image);
  std::cerr << "[tracing]\n";
  const double times[] = { 16, 256, 1024 };
  struct Row
  {
    double t;
    Measurement face, stepped;
  };
  std::vector<Row> rows;
  for (double t : times)
  {
    Row row;
    row.t = t;
    Config c;
    c.time = t;
    c.tracing = vtkShockAdvectionFilter::FACE_CROSSING;
    row.face = Run(image, c, options, "face-crossing t=" + Fixed(t, 0));
    c.tracing = vtkShockAdvectionFilter::STEPPED;
    row.stepped = Run(image, c, options, "stepped t=" + Fixed(t, 0));
    rows.push_back(row);
  }
  std::cout << "\n### Tracing: face crossing (exact) vs stepped (delta = 0.1), fixed flow, 1368 x 1824 RGB image\n\n"
            << "All threads, best of " << options.reps << " (median). " << traces
            << " traces per run; truncated = traces cut at the kernel's step cap.\n\n"
            << "| t | tracing | time s | flow s | advection s | trace steps | steps/trace | truncated |\n"
            << "|---:|---|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows)
  {
    const Measurement* ms[2] = { &r.face, &r.stepped };
    const char* names[2] = { "face crossing", "stepped 0.1" };
    for (int i = 0; i < 2; ++i)
    {
      const Measurement& m = *ms[i];
      std::cout << "| " << r.t << " | " << names[i] << " | " << BestMedian(m) << " | " << Seconds(m.flow)
                << " | " << Seconds(m.advection) << " | " << Count(static_cast<double>(m.steps)) << " | "
                << Fixed(static_cast<double>(m.steps) / traces, 2) << " | " << m.truncated << " |\n";
    }
  }
  std::cout.flush();
}

/// Write an RGB unsigned char image as binary PPM (for checking the synthetic data).
bool WritePPM(vtkImageData* image, const std::string& path)
{
  int dims[3];
  image->GetDimensions(dims);
  auto* array = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!array || array->GetNumberOfComponents() != 3)
  {
    return false;
  }
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << dims[0] << " " << dims[1] << "\n255\n";
  // VTK rows go bottom-up in y; PPM rows top-down: write y = 0 first (image shown flipped, harmless).
  out.write(reinterpret_cast<const char*>(array->GetPointer(0)),
    static_cast<std::streamsize>(array->GetNumberOfValues()));
  return static_cast<bool>(out);
}

void Dump(const std::string& prefix)
{
  vtkImageData* image = PhotoImage();
  WritePPM(image, prefix + "-input.ppm");
  for (double t : { 16.0, 1024.0 })
  {
    vtkNew<vtkImageShockAdvectionFilter> filter;
    filter->SetInputData(image);
    filter->SetFlowTime(t);
    filter->Update();
    const std::string path = prefix + "-fixed-t" + Fixed(t, 0) + ".ppm";
    WritePPM(vtkImageData::SafeDownCast(filter->GetOutput()), path);
    std::cerr << "wrote " << path << "\n";
  }
}

/// --write-volume N PATH: the volume of the volume mode at N^3, as a .vti file (Benchmarks/userbench.sh).
int WriteVolume(const std::string& size, const std::string& path)
{
  const int n = std::atoi(size.c_str());
  if (n < 2 || n > 2048)
  {
    std::cerr << "--write-volume: size " << size << " not in 2..2048\n";
    return 2;
  }
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(MakeVolume(n, 19990101));
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  if (writer->Write() != 1)
  {
    std::cerr << "cannot write " << path << "\n";
    return 2;
  }
  std::cerr << "wrote " << path << "\n";
  return 0;
}

void Usage(const char* argv0)
{
  std::cerr
    << "usage: " << argv0 << " [table1|threads|volume|tracing|all]... [options]\n"
    << "  --reps N               repetitions per measurement (default 3); best and median reported\n"
    << "  --cap K                maximum flow updates for composed/naive in table1 (default 64)\n"
    << "  --times a,b,...        flow times of table1 (default 1,4,16,64,256,1024,4096)\n"
    << "  --flows a,b,...        table1 flow modes among fixed,composed,naive (default all three)\n"
    << "  --retries N            extra runs per measurement to replace runs disturbed by other\n"
    << "                         processes (default 3)\n"
    << "  --disturbance F        a run is disturbed when other processes used more than F x its\n"
    << "                         wall time in CPU seconds (+0.02 s) (default 0.05)\n"
    << "  --cell-budget S        no retries once a measurement has taken S seconds (default 240)\n"
    << "  --max-cell-seconds S   do not repeat a measurement whose first run took longer (default 60)\n"
    << "  --no-volume-single     volume mode: skip the 1-thread run\n"
    << "  --write-volume N FILE  write the volume mode's volume at N^3 (256: the measured one) as a\n"
    << "                         .vti file, then exit\n"
    << "  --dump PREFIX          write the image and its t = 16 and 1024 results as PREFIX-*.ppm, then exit\n"
    << "Markdown tables on stdout, progress on stderr.\n";
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  std::vector<std::string> modes;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc)
      {
        std::cerr << name << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--reps")
    {
      options.reps = std::max(1, std::atoi(value("--reps").c_str()));
    }
    else if (arg == "--cap")
    {
      options.cap = std::max(1, std::atoi(value("--cap").c_str()));
    }
    else if (arg == "--retries")
    {
      options.retries = std::max(0, std::atoi(value("--retries").c_str()));
    }
    else if (arg == "--disturbance")
    {
      options.disturbance = std::atof(value("--disturbance").c_str());
    }
    else if (arg == "--cell-budget")
    {
      options.cellBudget = std::atof(value("--cell-budget").c_str());
    }
    else if (arg == "--max-cell-seconds")
    {
      options.maxCellSeconds = std::atof(value("--max-cell-seconds").c_str());
    }
    else if (arg == "--times")
    {
      options.times.clear();
      std::stringstream list(value("--times"));
      std::string item;
      while (std::getline(list, item, ','))
      {
        options.times.push_back(std::atof(item.c_str()));
      }
    }
    else if (arg == "--flows")
    {
      const std::string list = "," + value("--flows") + ",";
      const char* names[3] = { ",fixed,", ",composed,", ",naive," };
      for (int f = 0; f < 3; ++f)
      {
        options.flows[f] = list.find(names[f]) != std::string::npos;
      }
    }
    else if (arg == "--dump")
    {
      Dump(value("--dump"));
      return 0;
    }
    else if (arg == "--write-volume")
    {
      const std::string size = value("--write-volume");
      return WriteVolume(size, value("--write-volume"));
    }
    else if (arg == "--no-volume-single")
    {
      options.volumeSingleThread = false;
    }
    else if (arg == "-h" || arg == "--help")
    {
      Usage(argv[0]);
      return 0;
    }
    else if (arg == "table1" || arg == "threads" || arg == "volume" || arg == "tracing" || arg == "all")
    {
      modes.push_back(arg);
    }
    else
    {
      std::cerr << "unknown argument '" << arg << "'\n";
      Usage(argv[0]);
      return 2;
    }
  }
  if (modes.empty())
  {
    Usage(argv[0]);
    return 2;
  }
  auto wanted = [&](const char* mode) {
    return std::find(modes.begin(), modes.end(), mode) != modes.end() ||
      std::find(modes.begin(), modes.end(), "all") != modes.end();
  };

  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M:%S %Z", std::localtime(&now));
  std::ostringstream command;
  for (int i = 0; i < argc; ++i)
  {
    command << (i ? " " : "") << argv[i];
  }
  std::cout << "## shockbench\n\n"
            << "- command: `" << command.str() << "`\n"
            << "- date: " << date << "\n"
            << "- CPU: " << ProcField("/proc/cpuinfo", "model name") << ", "
            << HardwareThreads() << " hardware threads\n"
            << "- RAM: " << ProcField("/proc/meminfo", "MemTotal") << "\n"
            << "- compiler: " << __VERSION__
#ifdef SHOCKBENCH_BUILD_TYPE
            << ", build type " << SHOCKBENCH_BUILD_TYPE
#endif
            << "\n"
            << "- load average at start (1, 5, 15 min): " << LoadAverages() << "\n"
            << "- repetitions per measurement: " << options.reps << " (best and median of "
            << options.reps << " runs undisturbed by other processes; up to " << options.retries
            << " extra runs replace disturbed ones, i.e. runs during which other processes used more "
               "than " << options.disturbance * 100 << "% of the run's wall time in CPU time, "
               "read from /proc/stat; † marks figures that still include disturbed runs)\n";
  std::cout.flush();

  const double start = Now();
  if (wanted("table1"))
  {
    Table1(options);
  }
  if (wanted("threads"))
  {
    Threads(options);
  }
  if (wanted("tracing"))
  {
    Tracing(options);
  }
  if (wanted("volume"))
  {
    Volume(options);
  }

  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::cout << "\n- peak RSS (getrusage ru_maxrss): " << Fixed(usage.ru_maxrss / 1024.0, 1) << " MiB\n"
            << "- load average at end (1, 5, 15 min): " << LoadAverages() << "\n"
            << "- total benchmark time: " << Seconds(Now() - start) << " s\n";
  return 0;
}
