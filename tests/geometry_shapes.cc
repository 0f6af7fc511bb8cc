// Test of the particles that are not spheres: ellipsoids and closed surfaces
// (STL) read from a particle file, meshed by gmsh (volume, orientation),
// their extents and their overlaps in check_particles().
#include <densify/geometry/particle_shape.h>
#include <densify/geometry/particles.h>
#include <densify/geometry/sphere_mesher.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::source_dir;
using densify::testing::write_file;
using densify::testing::yes;

namespace
{



  /// The volume of a tet mesh (sum of its cells' volumes, all positive?).
  double
  mesh_volume(const TetMesh &mesh, bool &all_positive)
  {
    double volume = 0;
    all_positive  = true;
    for (const auto &c : mesh.cells)
      {
        const Tensor<1, 3> e1 = mesh.vertices[c[1]] - mesh.vertices[c[0]],
                           e2 = mesh.vertices[c[2]] - mesh.vertices[c[0]],
                           e3 = mesh.vertices[c[3]] - mesh.vertices[c[0]];
        const double v        = e1 * cross_product_3d(e2, e3) / 6;
        all_positive          = all_positive && v > 0;
        volume += v;
      }
    return volume;
  }



  /// The message check_particles() throws, or "ok".
  std::string
  check(const std::vector<Particle> &particles, const Container &container)
  {
    try
      {
        check_particles(particles, container, 1e-9);
        return "ok";
      }
    catch (const std::runtime_error &e)
      {
        return e.what();
      }
  }
} // namespace



int
main()
{
  const Container no_walls;

  // an ellipsoid of diameters 3, 2, 1.5 mm turned by 90 degrees about z:
  // its body x axis (the longest) along the global y axis
  write_file(
    "ellipsoid.csv",
    "x,y,z,diameter,material,shape,diameter_y,diameter_z,angle_x,angle_y,"
    "angle_z\n"
    "1,2,3,3,Sn,ellipsoid,2,1.5,0,0,90\n");
  const std::vector<Particle> ellipsoid =
    read_particle_csv("ellipsoid.csv", "Cu");
  const Particle &e = ellipsoid.at(0);
  std::cout << "ellipsoid read: semi-axes " << e.semi_axes
            << ", bounding diameter " << e.diameter << ", material "
            << e.material << std::endl;
  std::cout << "extents: along x " << support(e, Point<3>(1, 0, 0))
            << ", along y " << support(e, Point<3>(0, 1, 0)) << ", along z "
            << support(e, Point<3>(0, 0, -1)) << std::endl;

  SphereMeshSpec spec;
  spec.element_size  = 0.25;
  const TetMesh mesh = mesh_particle(e, spec);
  bool          positive;
  const double  exact  = 4. / 3. * numbers::PI * 1.5 * 1. * 0.75;
  const double  volume = mesh_volume(mesh, positive);
  std::cout << "ellipsoid mesh: every cell's Jacobian positive: "
            << yes(positive) << std::endl;
  std::cout << "ellipsoid mesh volume within 3 % below 4/3 pi a b c "
               "(inscribed facets): "
            << yes(volume < exact && volume > 0.97 * exact) << std::endl;
  std::cerr << "ellipsoid mesh volume / 4/3 pi a b c = " << volume / exact
            << std::endl;
  double q_max = 0, x_max = 0, y_max = 0;
  for (const Point<3> &v : mesh.vertices)
    {
      // the ellipsoid's equation in its body frame: x_b = R^T v
      const Tensor<1, 3> b = transpose(e.rotation) * v;
      q_max                = std::max(q_max,
                       std::pow(b[0] / 1.5, 2) + std::pow(b[1] / 1., 2) +
                         std::pow(b[2] / 0.75, 2));
      x_max                = std::max(x_max, std::abs(v[0]));
      y_max                = std::max(y_max, std::abs(v[1]));
    }
  std::cout << "mesh vertices on or inside the turned ellipsoid, surface "
               "vertices on it: "
            << yes(std::abs(q_max - 1) < 1e-6) << std::endl;
  std::cout << "the long axis along y after the turn: "
            << yes(y_max > 1.45 && y_max <= 1.5 + 1e-9 && x_max <= 1 + 1e-9)
            << std::endl;

  // refinement towards the lowest and highest points of the ellipsoid
  SphereMeshSpec refined        = spec;
  refined.refinement_directions = {Point<3>(0, 0, 1), Point<3>(0, 0, -1)};
  refined.refined_element_size  = 0.08;
  refined.growth                = 0.4;
  const TetMesh fine            = mesh_particle(e, refined);
  bool          has_top = false, has_bottom = false;
  for (const Point<3> &v : fine.vertices)
    {
      has_top    = has_top || std::abs(v[2] - 0.75) < 1e-9;
      has_bottom = has_bottom || std::abs(v[2] + 0.75) < 1e-9;
    }
  std::cout << "refined towards the punches: more cells ("
            << yes(fine.cells.size() > mesh.cells.size())
            << "), vertices at the top and the bottom ("
            << yes(has_top && has_bottom) << ")" << std::endl;

  // a 2 mm cube from an STL file, its centroid placed at (5, 0, 1)
  write_file("cube.csv",
             "5,0,1,,Fe," + source_dir() + "/tests/data/cube.stl,0,0,0\n");
  const Particle cube = read_particle_csv("cube.csv", "Fe").at(0);
  std::cout << "cube read: material " << cube.material << ", "
            << cube.surface->triangles.size()
            << " triangles, bounding diameter 2 sqrt 3: "
            << yes(std::abs(cube.diameter - 2 * std::sqrt(3.)) < 1e-12)
            << ", volume " << particle_volume(cube) << ", bottom at z "
            << cube.centre[2] - support(cube, Point<3>(0, 0, -1)) << std::endl;
  const TetMesh cube_mesh   = mesh_particle(cube, spec);
  const double  cube_volume = mesh_volume(cube_mesh, positive);
  std::cout << "cube mesh: Jacobians positive " << yes(positive)
            << ", volume 8 mm^3 exactly (plane faces): "
            << yes(std::abs(cube_volume - 8) < 1e-9) << ", finer than its "
            << "12 triangles: " << yes(cube_mesh.cells.size() > 100)
            << std::endl;
  std::cout << "cube inside test: centre " << yes(contains(cube, cube.centre))
            << ", corner region "
            << yes(contains(cube, Point<3>(5.9, 0.9, 1.9))) << ", outside "
            << yes(!contains(cube, Point<3>(6.1, 0, 1))) << std::endl;

  // a surface file that is not closed
  {
    std::ifstream     in(source_dir() + "/tests/data/cube.stl");
    const std::string text((std::istreambuf_iterator<char>(in)),
                           std::istreambuf_iterator<char>());
    // drop the last facet
    const std::size_t last = text.rfind("  facet");
    write_file("open.stl", text.substr(0, last) + "endsolid cube\n");
    write_file("open.csv", "0,0,0,,Fe,open.stl\n");
    try
      {
        read_particle_csv("open.csv", "Fe");
        std::cout << "open surface refused: " << yes(false) << std::endl;
      }
    catch (const std::runtime_error &error)
      {
        std::cout << error.what() << std::endl;
      }
  }

  // bad lines
  for (const std::string line : {"0,0,0,2,Sn,ellipsoid,1\n",
                                 "0,0,0,2,Sn,ellipsoid,1,0,0,0,0\n",
                                 "0,0,0,2,Sn,cube\n",
                                 "0,0,0,2,Sn,open.stl\n",
                                 "0,0,0,2,Sn,ellipsoid,1,x\n"})
    {
      write_file("bad.csv", line);
      try
        {
          read_particle_csv("bad.csv", "Fe");
          std::cout << "refused: " << yes(false) << std::endl;
        }
      catch (const std::runtime_error &error)
        {
          std::cout << error.what() << std::endl;
        }
    }

  // random orientations: reproducible from the seed, another seed others
  write_file("random.csv",
             "0,0,0,3,Sn,ellipsoid,2,1\n5,0,0,3,Sn,ellipsoid,2,1\n");
  const auto r1 = read_particle_csv("random.csv", "Sn", 7);
  const auto r2 = read_particle_csv("random.csv", "Sn", 7);
  const auto r3 = read_particle_csv("random.csv", "Sn", 8);
  std::cout << "random orientations: a rotation "
            << yes(std::abs(determinant(r1[0].rotation) - 1) < 1e-12 &&
                   (transpose(r1[0].rotation) * r1[0].rotation -
                    Tensor<2, 3>(unit_symmetric_tensor<3>()))
                       .norm() < 1e-12)
            << ", the same seed the same "
            << yes(r1[0].rotation == r2[0].rotation &&
                   r1[1].rotation == r2[1].rotation)
            << ", the particles differ "
            << yes((r1[0].rotation - r1[1].rotation).norm() > 1e-3)
            << ", another seed others "
            << yes((r1[0].rotation - r3[0].rotation).norm() > 1e-3)
            << std::endl;

  // overlaps: two long ellipsoids side by side, parallel, 1.2 mm apart:
  // their bounding spheres (diameter 4) overlap, they do not
  std::vector<Particle> pair(2);
  for (unsigned int i = 0; i < 2; ++i)
    {
      pair[i].centre = Point<3>(0, 1.2 * i, 0);
      make_ellipsoid(pair[i], {{4, 1, 1}}, unit_symmetric_tensor<3>());
    }
  std::cout << "parallel ellipsoids 1.2 mm apart: " << check(pair, no_walls)
            << std::endl;
  pair[1].centre = Point<3>(0, 0.9, 0);
  std::cout << "0.9 mm apart: " << check(pair, no_walls) << std::endl;
  // crossed: the second turned by 90 degrees about z, above the first at
  // x = 1 (where the first's top is at z = 0.433)
  pair[1].centre   = Point<3>(1, 0, 0.95);
  pair[1].rotation = rotation_from_angles({{0, 0, 90}});
  std::cout << "crossed, 0.017 mm apart: " << check(pair, no_walls)
            << std::endl;
  pair[1].centre = Point<3>(1, 0, 0.75);
  std::cout << "crossed, 0.18 mm into each other at x = 1: "
            << check(pair, no_walls) << std::endl;
  // an ellipsoid and a sphere, and the cube
  std::vector<Particle> mixed(3);
  mixed[0]          = pair[0];
  mixed[1].centre   = Point<3>(0, 0, 1.6);
  mixed[1].diameter = 2;
  mixed[2]          = cube;
  mixed[2].centre   = Point<3>(4.05, 0, 0);
  std::cout << "ellipsoid, sphere, cube apart: " << check(mixed, no_walls)
            << std::endl;
  mixed[2].centre = Point<3>(2.95, 0, 0);
  std::cout << "the cube into the ellipsoid's end: " << check(mixed, no_walls)
            << std::endl;
  mixed[2].centre = Point<3>(4.05, 0, 0);
  mixed[1].centre = Point<3>(0, 0, 1.4);
  std::cout << "the sphere onto the ellipsoid: " << check(mixed, no_walls)
            << std::endl;

  // the container: the extent of the turned ellipsoid, not its bounding
  // sphere
  Container die;
  die.has_die               = true;
  die.die_radius            = 1.6;
  die.has_lower             = true;
  die.lower_z               = 3 - 0.75;
  die.has_upper             = true;
  die.upper_z               = 3 + 0.75;
  std::vector<Particle> one = ellipsoid;
  one[0].centre             = Point<3>(0, 0, 3);
  std::cout << "the turned ellipsoid fits a die of radius 1.6 between "
               "punches 1.5 mm apart: "
            << check(one, die) << std::endl;
  // 0.7 mm off the axis: its farthest point 1.7698 mm from it (its
  // bounding sphere's 2.2 mm)
  one[0].centre = Point<3>(0.7, 0, 3);
  std::cout << check(one, die) << std::endl;
  die.die_radius = 2;
  die.upper_z    = 3 + 0.7;
  std::cout << check(one, die) << std::endl;

  return all_passed ? 0 : 1;
}
