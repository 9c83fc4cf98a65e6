// scan_cad: a CAD part as a scanner would sample it (sharpen_eval.py's scan
// set; built and run by Benchmarks/get_scan_meshes.sh, not part of the build).
//
// A CAD tessellation is made of long thin triangles that follow the part's
// faces; a scanned part is sampled evenly. This program remeshes the part's
// surface isotropically with CGAL (Polygon_mesh_processing::
// isotropic_remeshing): every new point lies on the original surface, the
// edges whose dihedral angle exceeds FEATURE_ANGLE (the part's creases) are
// kept as edges (split to the target length first, then protected), and the
// target edge length is chosen so that an equilateral mesh of the same area
// would have POINTS points.
//
//   scan_cad IN.off OUT.off POINTS FEATURE_ANGLE_DEGREES
//
// Exit 0 on success, 2 with a one-line message on bad arguments or input.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr unsigned RemeshingIterations = 5;

int Fail(const std::string& message)
{
  std::cerr << "scan_cad: " << message << "\n";
  return 2;
}

bool Positive(const char* text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(value) && value > 0;
}
} // namespace

int main(int argc, char** argv)
{
  if (argc != 5)
  {
    return Fail("usage: scan_cad IN.off OUT.off POINTS FEATURE_ANGLE_DEGREES");
  }
  double points = 0;
  double featureAngle = 0;
  if (!Positive(argv[3], points) || !Positive(argv[4], featureAngle) || featureAngle >= 180)
  {
    return Fail("POINTS must be positive and FEATURE_ANGLE_DEGREES in (0, 180)");
  }
  Mesh mesh;
  if (!PMP::IO::read_polygon_mesh(argv[1], mesh) || mesh.is_empty() || !CGAL::is_closed(mesh))
  {
    return Fail(std::string("cannot read a closed surface from ") + argv[1]);
  }
  PMP::triangulate_faces(mesh);

  // Equilateral triangles of side h have area sqrt(3)/4 h^2, and a closed
  // mesh of n points has about 2n of them.
  const double area = PMP::area(mesh);
  const double h = std::sqrt(area / (2.0 * points) * 4.0 / std::sqrt(3.0));

  auto crease = mesh.add_property_map<Mesh::Edge_index, bool>("e:crease", false).first;
  PMP::detect_sharp_edges(mesh, featureAngle, crease);
  std::vector<Mesh::Edge_index> creaseEdges;
  for (const auto e : edges(mesh))
  {
    if (get(crease, e))
    {
      creaseEdges.push_back(e);
    }
  }
  // Protected edges are never split by the remeshing, so they are brought to
  // the target length first (the split halves inherit the crease mark).
  PMP::split_long_edges(creaseEdges, h, mesh, CGAL::parameters::edge_is_constrained_map(crease));
  PMP::isotropic_remeshing(faces(mesh), h, mesh,
    CGAL::parameters::number_of_iterations(RemeshingIterations)
      .edge_is_constrained_map(crease)
      .protect_constraints(true));
  mesh.collect_garbage();

  if (!CGAL::IO::write_OFF(argv[2], mesh, CGAL::parameters::stream_precision(17)))
  {
    return Fail(std::string("cannot write ") + argv[2]);
  }
  std::cout << mesh.number_of_vertices() << " points, edge length " << h
            << ", " << creaseEdges.size() << " crease edges kept\n";
  return 0;
}
