/**
 * paperbench: the paper's Figure 2 and Figure 9 on a real photograph.
 *
 *   paperbench PHOTO OUTDIR [--threads N] [--kmax K] [--pde-kmax K]
 *                           [--size WxH] [--passes N] [--no-images]
 *
 * Reads PHOTO (any format VTK reads: JPEG, PNG, ...), cuts the centred
 * W x H window (default 2848 x 2136, the size of the paper's Figure 2/9 image;
 * native pixels, no resampling) and filters it with both methods of the
 * VTK-free grid kernels, same parameters (SmoothingPasses --passes, default 1):
 *
 *  - advection (AdvectGridSignal, fixed flow): one run per t = 2^k, k = 1..K
 *    (default 11), each timed on its own (wall time of the kernel call);
 *  - PDE (SolveGridShockPDE, Osher-Rudin, upwind/minmod at its CFL step): one
 *    run to 2^min(K, pde-kmax) with checkpoints at every 2^k; the time of a
 *    checkpoint is the wall time since the start of the run, minus the time
 *    spent in earlier checkpoint callbacks. Both methods work on doubles
 *    converted beforehand; neither timing includes I/O.
 *
 * For each method and t it reports the paper's convergence measure
 * |I_t - I_0| / |I_inf - I_0| with I_inf = I_{2^K} (L2 over all samples and
 * channels), the distance to that steady state |I_t - I_inf| / |I_inf - I_0|,
 * and the first t reaching 99 % with its time. With images on (default), it
 * writes OUTDIR/input.png and the t = 2^K results advection.png and pde.png
 * (for the Figure 2 zoom-ins) and reports their mean absolute difference
 * relative to the value range. Always writes OUTDIR/figure9_threads<N>.csv.
 * Markdown on stdout, progress on stderr.
 */
#include "GridShockAdvection.h"
#include "GridShockPDE.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Options
{
  std::string photo;
  std::string outdir;
  int threads = 0;
  int kmax = 11;
  int pdeKmax = -1; // -1: kmax
  int width = 2848;
  int height = 2136;
  int passes = 1;
  bool images = true;
};

[[noreturn]] void Usage(const std::string& problem)
{
  std::cerr << "paperbench: " << problem << "\n"
            << "usage: paperbench PHOTO OUTDIR [--threads N] [--kmax K] [--pde-kmax K]\n"
               "                  [--size WxH] [--passes N] [--no-images]\n";
  std::exit(2);
}

Options ParseOptions(int argc, char** argv)
{
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        Usage(a + " needs a value");
      }
      return argv[++i];
    };
    if (a == "--threads")
      o.threads = std::atoi(value().c_str());
    else if (a == "--kmax")
      o.kmax = std::atoi(value().c_str());
    else if (a == "--pde-kmax")
      o.pdeKmax = std::atoi(value().c_str());
    else if (a == "--passes")
      o.passes = std::atoi(value().c_str());
    else if (a == "--no-images")
      o.images = false;
    else if (a == "--size")
    {
      const std::string s = value();
      if (std::sscanf(s.c_str(), "%dx%d", &o.width, &o.height) != 2)
        Usage("--size wants WxH");
    }
    else if (!a.empty() && a[0] == '-')
      Usage("unknown option " + a);
    else
      positional.push_back(a);
  }
  if (positional.size() != 2)
    Usage("PHOTO and OUTDIR are required");
  o.photo = positional[0];
  o.outdir = positional[1];
  if (o.kmax < 1 || o.kmax > 16 || o.passes < 0 || o.threads < 0 || o.width < 2 || o.height < 2)
    Usage("an option is out of range");
  if (o.pdeKmax < 0 || o.pdeKmax > o.kmax)
    o.pdeKmax = o.kmax;
  return o;
}

/// The photo's centred width x height window as interleaved doubles (3 channels).
std::vector<double> LoadWindow(const Options& o, int& channels)
{
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(o.photo.c_str()));
  if (!reader)
  {
    Usage("cannot read " + o.photo);
  }
  reader->SetFileName(o.photo.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  int dims[3];
  image->GetDimensions(dims);
  if (!scalars || dims[0] < o.width || dims[1] < o.height)
  {
    Usage(o.photo + " is smaller than the requested window");
  }
  channels = scalars->GetNumberOfComponents();
  const int x0 = (dims[0] - o.width) / 2, y0 = (dims[1] - o.height) / 2;
  std::vector<double> values(static_cast<size_t>(o.width) * o.height * channels);
  for (int y = 0; y < o.height; ++y)
  {
    for (int x = 0; x < o.width; ++x)
    {
      const vtkIdType source = static_cast<vtkIdType>(y0 + y) * dims[0] + (x0 + x);
      for (int c = 0; c < channels; ++c)
      {
        values[(static_cast<size_t>(y) * o.width + x) * channels + c] = scalars->GetComponent(source, c);
      }
    }
  }
  std::cerr << "photo " << o.photo << ": " << dims[0] << " x " << dims[1] << ", window " << o.width
            << " x " << o.height << " at (" << x0 << ", " << y0 << "), " << channels << " channels\n";
  return values;
}

void WritePng(const std::string& path, const std::vector<double>& values, int width, int height, int channels)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(width, height, 1);
  vtkNew<vtkUnsignedCharArray> array;
  array->SetNumberOfComponents(channels);
  array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  for (size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i),
      static_cast<unsigned char>(std::clamp(std::lround(values[i]), 0L, 255L)));
  }
  image->GetPointData()->SetScalars(array);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

/// A flow time for the report, whole (2048, not 2.05e+03) whatever the stream's precision.
std::string FlowTime(double t)
{
  std::ostringstream text;
  text << std::setprecision(10) << t;
  return text.str();
}

/// One sample of a convergence curve.
struct CurvePoint
{
  double t = 0.0;
  double seconds = 0.0;
  std::vector<float> values; // I_t, kept for the distance to I_inf
  double change = 0.0;       // |I_t - I_0|
};

/// L2 distance between two signals of the same size (float or double samples).
template <typename A, typename B>
double Distance(const std::vector<A>& a, const std::vector<B>& b)
{
  double sum = 0.0;
#pragma omp parallel for reduction(+ : sum)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(b.size()); ++i)
  {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

CurvePoint MakePoint(double t, double seconds, const double* values, const std::vector<double>& input)
{
  CurvePoint p;
  p.t = t;
  p.seconds = seconds;
  p.values.assign(values, values + input.size());
  p.change = Distance(p.values, input);
  return p;
}

/// Prints the curve's table (and the first t reaching 99 %) and appends it to the CSV.
void Report(const char* method, const std::vector<CurvePoint>& curve, int threads, std::ofstream& csv)
{
  const CurvePoint& steady = curve.back();
  const double total = steady.change;
  std::cout << "\n#### " << method << ", " << threads << " thread(s); I_inf = I_" << FlowTime(steady.t) << "\n\n"
            << "| t | seconds | \\|I_t - I_0\\| / \\|I_inf - I_0\\| | \\|I_t - I_inf\\| / \\|I_inf - I_0\\| |\n"
            << "|---:|---:|---:|---:|\n";
  const CurvePoint* first99 = nullptr;
  for (const CurvePoint& p : curve)
  {
    const double ratio = total > 0.0 ? p.change / total : 1.0;
    const double distance = total > 0.0 ? Distance(p.values, steady.values) / total : 0.0;
    if (!first99 && ratio >= 0.99)
    {
      first99 = &p;
    }
    std::cout << "| " << FlowTime(p.t) << " | " << std::fixed << std::setprecision(3) << p.seconds << " | "
              << std::setprecision(4) << ratio << " | " << distance << " |\n"
              << std::defaultfloat;
    csv << method << "," << threads << "," << p.t << "," << p.seconds << "," << ratio << ","
        << distance << "\n";
  }
  if (first99)
  {
    std::cout << "\n99 % of the steady state (by the paper's measure) first at t = " << FlowTime(first99->t)
              << ", after " << std::fixed << std::setprecision(3) << first99->seconds << " s\n"
              << std::defaultfloat;
  }
}

} // namespace

int main(int argc, char** argv)
{
  const Options o = ParseOptions(argc, argv);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  int channels = 0;
  const std::vector<double> input = LoadWindow(o, channels);
  shock::GridShape shape;
  shape.dimensions = { o.width, o.height, 1 };
  const auto [low, high] = std::minmax_element(input.begin(), input.end());
  const double range = *high - *low;
  std::error_code error;
  std::filesystem::create_directories(o.outdir, error);
  if (error)
  {
    Usage("cannot create " + o.outdir + ": " + error.message());
  }
  std::ofstream csv(o.outdir + "/figure9_threads" + std::to_string(threads) + ".csv");
  csv << "method,threads,t,seconds,ratio,distance_to_steady\n";
  std::cout << "### Figure 9: " << o.width << " x " << o.height << " x " << channels
            << " photo, smoothing passes " << o.passes << ", " << threads << " thread(s)\n";

  // Advection: one timed run per t.
  std::vector<CurvePoint> advection;
  std::vector<double> output(input.size());
  for (int k = 1; k <= o.kmax; ++k)
  {
    shock::AdvectionParameters p;
    p.time = std::ldexp(1.0, k);
    p.smoothingPasses = o.passes;
    p.numberOfThreads = threads;
    const auto start = Clock::now();
    const shock::Status status =
      shock::AdvectGridSignal(shape, channels, input.data(), output.data(), p);
    const double seconds = SecondsSince(start);
    if (!status.Ok())
    {
      std::cerr << "advection failed: " << status.error << "\n";
      return 1;
    }
    advection.push_back(MakePoint(p.time, seconds, output.data(), input));
    std::cerr << "advection t = " << p.time << ": " << seconds << " s\n";
  }
  Report("advection", advection, threads, csv);
  if (o.images)
  {
    WritePng(o.outdir + "/input.png", input, o.width, o.height, channels);
    WritePng(o.outdir + "/advection.png", output, o.width, o.height, channels);
  }
  const std::vector<double> advected = output;

  // PDE: one run, checkpoints at every 2^k.
  shock::PDEParameters p;
  p.time = std::ldexp(1.0, o.pdeKmax);
  p.smoothingPasses = o.passes;
  p.numberOfThreads = threads;
  for (int k = 1; k <= o.pdeKmax; ++k)
  {
    p.checkpointTimes.push_back(std::ldexp(1.0, k));
  }
  std::vector<CurvePoint> pde;
  double callbackSeconds = 0.0;
  const auto start = Clock::now();
  shock::PDEReport report;
  const shock::Status status = shock::SolveGridShockPDE(shape, channels, input.data(),
    output.data(), p, &report, nullptr, shock::ProgressFunction(),
    [&](double t, double, const double* values) {
      const auto entered = Clock::now();
      const double seconds = std::chrono::duration<double>(entered - start).count() - callbackSeconds;
      pde.push_back(MakePoint(t, seconds, values, input));
      std::cerr << "pde t = " << t << ": " << seconds << " s\n";
      callbackSeconds += SecondsSince(entered);
    });
  if (!status.Ok())
  {
    std::cerr << "pde failed: " << status.error << "\n";
    return 1;
  }
  Report("pde", pde, threads, csv);
  std::cout << "\nPDE: " << report.iterations << " explicit steps, CFL step from "
            << report.largestStep << " down to " << report.smallestStep << "; flow "
            << std::fixed << std::setprecision(2) << report.flowSeconds << " s, updates "
            << report.updateSeconds << " s\n" << std::defaultfloat;

  if (o.pdeKmax == o.kmax)
  {
    double difference = 0.0;
    for (size_t i = 0; i < output.size(); ++i)
    {
      difference += std::abs(output[i] - advected[i]);
    }
    std::cout << "\n### Figure 2: steady states (t = " << FlowTime(p.time) << ")\n\n"
              << "Mean absolute difference between the PDE and the advection: " << std::setprecision(4)
              << 100.0 * difference / static_cast<double>(output.size()) / range
              << " % of the value range (" << range << ")\n";
    if (o.images)
    {
      WritePng(o.outdir + "/pde.png", output, o.width, o.height, channels);
    }
  }
  return 0;
}
