#include "GridShape.h"

#include <algorithm>

namespace shock
{

std::int64_t GridShape::NumberOfSamples() const
{
  return static_cast<std::int64_t>(this->dimensions[0]) * this->dimensions[1] *
    this->dimensions[2];
}

std::int64_t GridShape::NumberOfFaces() const
{
  std::int64_t faces = 1;
  for (int d : this->dimensions)
  {
    faces *= std::max(d - 1, 1);
  }
  return faces;
}

int GridShape::ActiveAxes() const
{
  return static_cast<int>(
    std::count_if(this->dimensions.begin(), this->dimensions.end(), [](int d) { return d > 1; }));
}

double GridShape::MeanEdgeLength() const
{
  // Edges along axis a: (n_a - 1) * product of the other dimensions.
  double edges = 0.0;
  double length = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (this->dimensions[a] < 2)
    {
      continue;
    }
    double count = this->WholeDimension(a) - 1.0;
    for (int b = 0; b < 3; ++b)
    {
      count *= (b == a) ? 1.0 : this->WholeDimension(b);
    }
    edges += count;
    length += count * this->spacing[a];
  }
  return edges > 0.0 ? length / edges : 0.0;
}

} // namespace shock
