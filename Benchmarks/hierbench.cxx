/**
 * hierbench: does the coarse-to-fine tracing (hierarchyLevels, docs/hierarchy.md)
 * pay? On images with a known sharp original, blurred (Gaussian, sigma in
 * pixels) and noisy (Gaussian, standard deviation in % of the range), it finds
 * each method's best result over a grid of flow times: the single level (the
 * paper's filter) with 1 smoothing pass (the default) and at its best passes;
 * the hierarchy with 1 pass at its best number of levels, and at its best
 * levels and passes. It prints the error (root-mean-square difference to the
 * sharp original, % of the range) and the wall time of the single level and the
 * hierarchy, each at its best setting but both at the same flow time (the
 * single level's best), median of 3 runs. The originals are a synthetic scene of discs
 * and bars of several sizes, and photographs given on the command line (each
 * downscaled by area averaging to at most --photo-width pixels, then treated as
 * sharp). Side-by-side pictures (sharp | input | single | hierarchical) go to
 * --pictures DIR. Markdown on stdout.
 *
 *   hierbench [--threads N] [--photo-width W] [--pictures DIR] [photo.jpg ...]
 *   hierbench --cost [--threads N] [--photo-width W] photo.jpg
 *
 * --cost: the wall time of 1 to 4 levels (1 smoothing pass) at equal flow times
 * on the photograph (blurred with sigma 2, noise 2 %), runs interleaved, median of 5.
 *
 * Driven by Benchmarks/run_hierarchy.sh.
 */
#include "BenchmarkSupport.h"
#include "GridShockAdvection.h"

#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace
{

struct Image
{
  int nx = 0, ny = 0, c = 1;
  std::vector<double> v; // x-fastest, components interleaved, range [0, 1]
};

/// Discs and bars of several sizes and contrasts on a mid-grey background.
Image Scene(int n)
{
  Image im;
  im.nx = im.ny = n;
  im.v.assign(static_cast<size_t>(n) * n, 0.45);
  const double s = n / 384.0;
  struct Disc { double x, y, r, value; };
  const Disc discs[] = { { 70, 70, 48, 0.95 }, { 200, 80, 24, 0.05 }, { 290, 70, 12, 0.9 },
    { 340, 60, 6, 0.1 }, { 330, 120, 6, 0.9 }, { 90, 300, 30, 0.15 } };
  struct Bar { double x0, y0, x1, y1, value; };
  const Bar bars[] = { { 150, 170, 360, 234, 0.8 }, { 170, 260, 186, 370, 0.05 },
    { 210, 260, 218, 370, 0.95 }, { 240, 260, 244, 370, 0.1 }, { 270, 280, 370, 300, 0.2 } };
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double x = (i + 0.5) / s, y = (j + 0.5) / s;
      double& value = im.v[static_cast<size_t>(j) * n + i];
      for (const Bar& b : bars)
      {
        value = (x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1) ? b.value : value;
      }
      for (const Disc& d : discs)
      {
        value = std::hypot(x - d.x, y - d.y) < d.r ? d.value : value;
      }
    }
  }
  return im;
}

/// A photograph (any format VTK reads), colours in [0, 1], downscaled by area averaging.
bool ReadPhoto(const std::string& path, int maxWidth, Image& im)
{
  vtkNew<vtkImageReader2Factory> factory;
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(factory->CreateImageReader2(path.c_str()));
  if (!reader)
  {
    return false;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  vtkDataArray* scalars = data->GetPointData()->GetScalars();
  if (!scalars)
  {
    return false;
  }
  const int* dims = data->GetDimensions();
  const int factor = std::max(1, (dims[0] + maxWidth - 1) / maxWidth);
  im.c = std::min(3, scalars->GetNumberOfComponents());
  im.nx = dims[0] / factor;
  im.ny = dims[1] / factor;
  im.v.assign(static_cast<size_t>(im.nx) * im.ny * im.c, 0.0);
  const double scale = 1.0 / (255.0 * factor * factor);
  for (int j = 0; j < im.ny * factor; ++j)
  {
    for (int i = 0; i < im.nx * factor; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * dims[0] + i;
      for (int k = 0; k < im.c; ++k)
      {
        im.v[(static_cast<size_t>(j / factor) * im.nx + i / factor) * im.c + k] +=
          scale * scalars->GetComponent(id, k);
      }
    }
  }
  return true;
}

/// Separable Gaussian blur (radius 4 sigma, clamped borders), then Gaussian noise.
Image Degrade(const Image& sharp, double sigma, double noise, unsigned seed)
{
  const int radius = static_cast<int>(std::ceil(4.0 * sigma));
  std::vector<double> kernel(2 * radius + 1);
  double total = 0.0;
  for (int k = -radius; k <= radius; ++k)
  {
    total += kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
  }
  for (double& w : kernel)
  {
    w /= total;
  }
  Image out = sharp;
  for (int axis = 0; axis < 2; ++axis)
  {
    const Image in = out;
    for (int j = 0; j < sharp.ny; ++j)
    {
      for (int i = 0; i < sharp.nx; ++i)
      {
        for (int c = 0; c < sharp.c; ++c)
        {
          double sum = 0.0;
          for (int k = -radius; k <= radius; ++k)
          {
            const int ii = axis == 0 ? std::clamp(i + k, 0, sharp.nx - 1) : i;
            const int jj = axis == 1 ? std::clamp(j + k, 0, sharp.ny - 1) : j;
            sum += kernel[k + radius] * in.v[(static_cast<size_t>(jj) * sharp.nx + ii) * sharp.c + c];
          }
          out.v[(static_cast<size_t>(j) * sharp.nx + i) * sharp.c + c] = sum;
        }
      }
    }
  }
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  for (double& x : out.v)
  {
    x += gauss(random);
  }
  return out;
}

double RmsPercent(const std::vector<double>& a, const std::vector<double>& b)
{
  double sum = 0.0;
  for (size_t s = 0; s < a.size(); ++s)
  {
    sum += (a[s] - b[s]) * (a[s] - b[s]);
  }
  return 100.0 * std::sqrt(sum / static_cast<double>(a.size()));
}

struct Setting
{
  int levels = 1, smoothing = 1;
  double time = 0.0;
};

std::vector<double> Run(const Image& in, const Setting& s, int threads, double* seconds = nullptr)
{
  shock::GridShape shape;
  shape.dimensions = { in.nx, in.ny, 1 };
  shock::AdvectionParameters p;
  p.time = s.time;
  p.smoothingPasses = s.smoothing;
  p.hierarchyLevels = s.levels;
  p.numberOfThreads = threads;
  std::vector<double> out(in.v.size());
  const double start = shockbench::Now();
  const shock::Status status = shock::AdvectGridSignal(shape, in.c, in.v.data(), out.data(), p);
  if (seconds)
  {
    *seconds = shockbench::Now() - start;
  }
  if (!status.Ok())
  {
    std::fprintf(stderr, "hierbench: %s\n", status.error.c_str());
    std::exit(2);
  }
  return out;
}

double MedianSeconds(const Image& in, const Setting& s, int threads)
{
  std::vector<double> times(3);
  for (double& t : times)
  {
    Run(in, s, threads, &t);
  }
  std::sort(times.begin(), times.end());
  return times[1];
}

/// The best setting (lowest error) over the flow times and the given levels and smoothing passes.
Setting Best(const Image& sharp, const Image& in, const std::vector<int>& levels,
  const std::vector<int>& smoothing, int threads, double& error, std::vector<double>& result)
{
  static const double times[] = { 1e2, 1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6, 1e7 };
  Setting best;
  error = 1e300;
  for (int l : levels)
  {
    for (int s : smoothing)
    {
      for (double t : times)
      {
        const Setting setting{ l, s, t };
        auto out = Run(in, setting, threads);
        const double e = RmsPercent(out, sharp.v);
        if (e < error)
        {
          error = e;
          best = setting;
          result = std::move(out);
        }
      }
    }
  }
  return best;
}

void WritePicture(const std::string& path, const std::vector<const std::vector<double>*>& panels,
  const Image& like)
{
  const int gap = 4, count = static_cast<int>(panels.size());
  const int width = count * like.nx + (count - 1) * gap;
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(width, like.ny, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(width) * like.ny);
  rgb->Fill(255);
  for (int p = 0; p < count; ++p)
  {
    for (int j = 0; j < like.ny; ++j)
    {
      for (int i = 0; i < like.nx; ++i)
      {
        // Rows in VTK's order, as the photographs were read (PNG shows them upright).
        const vtkIdType id = static_cast<vtkIdType>(j) * width + p * (like.nx + gap) + i;
        for (int k = 0; k < 3; ++k)
        {
          const double x = (*panels[p])[(static_cast<size_t>(j) * like.nx + i) * like.c + std::min(k, like.c - 1)];
          rgb->SetComponent(id, k, std::round(255.0 * std::clamp(x, 0.0, 1.0)));
        }
      }
    }
  }
  picture->GetPointData()->SetScalars(rgb);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(picture);
  writer->Write();
}

struct Case
{
  std::string name;
  Image sharp;
  double sigma, noise;
};

/// The --cost table: time of 1-4 levels at equal flow times, interleaved runs.
int Cost(const std::vector<std::string>& photos, int width, int threads)
{
  Image photo;
  if (photos.size() != 1 || !ReadPhoto(photos[0], width, photo))
  {
    std::fprintf(stderr, "hierbench --cost: give one readable photograph\n");
    return 2;
  }
  const Image input = Degrade(photo, 2.0, 0.02, 99u);
  std::printf("%d threads, load averages %s (a machine shared with other jobs).\n\n", threads,
    shockbench::LoadAverages().c_str());
  std::printf("| %dx%d RGB, t | 1 level | 2 levels | 3 levels | 4 levels | ratios to 1 level |\n",
    photo.nx, photo.ny);
  std::printf("|---|---|---|---|---|---|\n");
  for (double t : { 1e2, 1e3, 1e4, 1e5, 1e6 })
  {
    std::vector<std::vector<double>> times(4);
    for (int r = 0; r < 5; ++r)
    {
      for (int l = 1; l <= 4; ++l)
      {
        double seconds = 0.0;
        Run(input, Setting{ l, 1, t }, threads, &seconds);
        times[l - 1].push_back(seconds);
      }
    }
    double median[4];
    for (int l = 0; l < 4; ++l)
    {
      std::sort(times[l].begin(), times[l].end());
      median[l] = times[l][2];
    }
    std::printf("| %g | %.3f s | %.3f s | %.3f s | %.3f s | %.2f, %.2f, %.2f |\n", t, median[0],
      median[1], median[2], median[3], median[1] / median[0], median[2] / median[0],
      median[3] / median[0]);
    std::fflush(stdout);
  }
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  int threads = 2, photoWidth = 512;
  bool cost = false;
  std::string pictures;
  std::vector<std::string> photos;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if (arg == "--threads" && a + 1 < argc)
    {
      threads = std::atoi(argv[++a]);
    }
    else if (arg == "--photo-width" && a + 1 < argc)
    {
      photoWidth = std::atoi(argv[++a]);
    }
    else if (arg == "--cost")
    {
      cost = true;
    }
    else if (arg == "--pictures" && a + 1 < argc)
    {
      pictures = argv[++a];
    }
    else
    {
      photos.push_back(arg);
    }
  }

  if (cost)
  {
    return Cost(photos, photoWidth, threads);
  }
  std::vector<Case> cases;
  const Image scene = Scene(384);
  for (double sigma : { 2.0, 4.0, 6.0 })
  {
    for (double noise : { 0.01, 0.04, 0.08 })
    {
      cases.push_back({ "scene", scene, sigma, noise });
    }
  }
  for (const std::string& path : photos)
  {
    Image photo;
    if (!ReadPhoto(path, photoWidth, photo))
    {
      std::fprintf(stderr, "hierbench: cannot read %s\n", path.c_str());
      return 2;
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    for (double sigma : { 2.0, 4.0 })
    {
      for (double noise : { 0.02, 0.05 })
      {
        cases.push_back({ name, photo, sigma, noise });
      }
    }
  }

  std::printf("%d threads, load averages %s (a machine shared with other jobs).\n\n", threads,
    shockbench::LoadAverages().c_str());
  std::printf("| image | size | blur sigma | noise | input | single, 1 pass | single, best passes "
              "| hier., 1 pass, best levels | hier., best levels and passes | change | single "
              "time | hier. time | ratio |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int index = 0;
  for (const Case& c : cases)
  {
    const Image input = Degrade(c.sharp, c.sigma, c.noise, 1234u + index);
    double defaultError = 0.0, singleError = 0.0, levelsError = 0.0, hierError = 0.0;
    std::vector<double> unused, single, hier;
    const Setting d = Best(c.sharp, input, { 1 }, { 1 }, threads, defaultError, unused);
    const Setting s = Best(c.sharp, input, { 1 }, { 0, 1, 2, 4, 8, 16 }, threads, singleError, single);
    const Setting l = Best(c.sharp, input, { 2, 3, 4 }, { 1 }, threads, levelsError, unused);
    const Setting h = Best(c.sharp, input, { 2, 3 }, { 0, 1, 4, 16 }, threads, hierError, hier);
    // The cost of both at the same flow time: the single level's best.
    const double singleSeconds = MedianSeconds(input, s, threads);
    const double hierSeconds = MedianSeconds(input, Setting{ h.levels, h.smoothing, s.time }, threads);
    std::printf("| %s | %dx%d%s | %g | %g %% | %.2f | %.2f (t %g) | %.2f (%d, t %g) | %.2f (%d, t %g) "
                "| %.2f (%d, %d, t %g) | %+.1f %% | %.3f s | %.3f s | %.2f |\n",
      c.name.c_str(), c.sharp.nx, c.sharp.ny, c.sharp.c == 3 ? " RGB" : "", c.sigma,
      100.0 * c.noise, RmsPercent(input.v, c.sharp.v), defaultError, d.time, singleError,
      s.smoothing, s.time, levelsError, l.levels, l.time, hierError, h.levels, h.smoothing, h.time,
      100.0 * (hierError - singleError) / singleError, singleSeconds, hierSeconds,
      hierSeconds / singleSeconds);
    std::fflush(stdout);
    if (!pictures.empty())
    {
      char file[512];
      std::snprintf(file, sizeof(file), "%s/hierarchy_%02d.png", pictures.c_str(), index);
      WritePicture(file, { &c.sharp.v, &input.v, &single, &hier }, c.sharp);
    }
    ++index;
  }
  return 0;
}
