// Shapes (box, disk/sphere, cylinder, polygon): the region of bodies and
// load boxes, and the surface that rigid obstacles will carry. Checked
// against closed forms and against each other:
// - at chosen points, the signed distance and the outward normal are the
//   geometry's (a point beyond a box corner is at the distance to the
//   corner, one beyond a cylinder's rim at sqrt(dr^2 + da^2), one inside
//   a triangle at the distance to its nearest edge, ...);
// - at 2000 random points each: contains(x) is signed_distance(x) <= 0;
//   x - d(x) n(x) lies on the surface (|d| below 1e-12); n is a unit
//   vector; outside these convex shapes, n is the gradient of d (central
//   differences, 1e-6);
// - an L-shaped (non-convex) polygon given clockwise: contains and the
//   distances agree with its two rectangles.

#include <deal.II/base/mpi.h>

#include <mpm/base/shape.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "tests.h"

using namespace dealii;
using namespace mpm;
using mpm_tests::check;

template <int dim>
void
consistent(const std::string &name,
           const Shape<dim> & shape,
           const Point<dim> & lower,
           const Point<dim> & upper,
           const bool         convex)
{
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> unit(0., 1.);
  unsigned int mismatched = 0, off_surface = 0, not_unit = 0, not_gradient = 0;
  for (unsigned int k = 0; k < 2000; ++k)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = lower[d] + (upper[d] - lower[d]) * unit(rng);
      const double         distance = shape.signed_distance(x);
      const Tensor<1, dim> n        = shape.outward_normal(x);
      if (std::abs(distance) > 1e-9 && shape.contains(x) != (distance < 0.))
        ++mismatched;
      if (std::abs(shape.signed_distance(x - distance * n)) > 1e-12)
        ++off_surface;
      if (std::abs(n.norm() - 1.) > 1e-12)
        ++not_unit;
      if (convex && distance > 1e-3)
        {
          Tensor<1, dim> gradient;
          for (unsigned int d = 0; d < dim; ++d)
            {
              Point<dim> plus = x, minus = x;
              plus[d] += 1e-7;
              minus[d] -= 1e-7;
              gradient[d] =
                (shape.signed_distance(plus) - shape.signed_distance(minus)) /
                2e-7;
            }
          if ((gradient - n).norm() > 1e-6)
            ++not_gradient;
        }
    }
  check(name + ": contains(x) is d(x) <= 0 at 2000 random points",
        mismatched == 0);
  check(name + ": x - d n lies on the surface, n a unit vector",
        off_surface == 0 && not_unit == 0);
  if (convex)
    check(name + ": outside, n is the gradient of d", not_gradient == 0);
}

void
test_2d()
{
  const BoxShape<2> box(Point<2>(0., 0.), Point<2>(2., 1.));
  check("box: beyond a corner, the distance to the corner, the normal "
        "along it",
        std::abs(box.signed_distance(Point<2>(3., 2.)) - std::sqrt(2.)) <
            1e-14 &&
          (box.outward_normal(Point<2>(3., 2.)) -
           Tensor<1, 2>({1. / std::sqrt(2.), 1. / std::sqrt(2.)}))
              .norm() < 1e-14);
  check("box: inside, minus the distance to the nearest face, its normal",
        std::abs(box.signed_distance(Point<2>(1.8, 0.5)) + 0.2) < 1e-14 &&
          (box.outward_normal(Point<2>(1.8, 0.5)) - Tensor<1, 2>({1., 0.}))
              .norm() < 1e-14);
  consistent<2>("box", box, Point<2>(-1., -1.), Point<2>(3., 2.), true);

  const BallShape<2> disk(Point<2>(1., 1.), 0.5);
  check("disk: |x - c| - r and (x - c) / |x - c|",
        std::abs(disk.signed_distance(Point<2>(1., 2.)) - 0.5) < 1e-14 &&
          std::abs(disk.signed_distance(Point<2>(1.3, 1.)) + 0.2) < 1e-14 &&
          (disk.outward_normal(Point<2>(1., 2.)) - Tensor<1, 2>({0., 1.}))
              .norm() < 1e-14);
  consistent<2>("disk", disk, Point<2>(0., 0.), Point<2>(2., 2.), true);

  // A triangle, counter-clockwise: (0,0), (2,0), (0,2).
  const PolygonShape<2> triangle(
    {Point<2>(0., 0.), Point<2>(2., 0.), Point<2>(0., 2.)});
  check("triangle: inside, minus the distance to the nearest edge",
        std::abs(triangle.signed_distance(Point<2>(0.5, 0.2)) + 0.2) <
            1e-14 &&
          (triangle.outward_normal(Point<2>(0.5, 0.2)) -
           Tensor<1, 2>({0., -1.}))
              .norm() < 1e-14);
  check("triangle: beyond the hypotenuse, the distance to it and its normal",
        std::abs(triangle.signed_distance(Point<2>(2., 2.)) -
                 std::sqrt(2.)) < 1e-14 &&
          (triangle.outward_normal(Point<2>(2., 2.)) -
           Tensor<1, 2>({1. / std::sqrt(2.), 1. / std::sqrt(2.)}))
              .norm() < 1e-14);
  check("triangle: on an edge, the edge's outward normal",
        (triangle.outward_normal(Point<2>(1., 0.)) - Tensor<1, 2>({0., -1.}))
            .norm() < 1e-14);
  consistent<2>("triangle", triangle, Point<2>(-1., -1.), Point<2>(3., 3.),
                true);

  // An L, clockwise: [0,2] x [0,1] and [0,1] x [0,2].
  const PolygonShape<2> l_shape({Point<2>(0., 0.),
                                 Point<2>(0., 2.),
                                 Point<2>(1., 2.),
                                 Point<2>(1., 1.),
                                 Point<2>(2., 1.),
                                 Point<2>(2., 0.)});
  const BoxShape<2> lower_arm(Point<2>(0., 0.), Point<2>(2., 1.));
  const BoxShape<2> upper_arm(Point<2>(0., 0.), Point<2>(1., 2.));
  std::mt19937                           rng(5);
  std::uniform_real_distribution<double> coordinate(-0.5, 2.5);
  unsigned int                           disagree = 0;
  for (unsigned int k = 0; k < 2000; ++k)
    {
      const Point<2> x(coordinate(rng), coordinate(rng));
      const double   union_distance =
        std::min(lower_arm.signed_distance(x), upper_arm.signed_distance(x));
      // The union's distance is exact outside, and its sign is right.
      if (l_shape.contains(x) != (lower_arm.contains(x) || upper_arm.contains(x)))
        ++disagree;
      else if (union_distance > 0. &&
               std::abs(l_shape.signed_distance(x) - union_distance) > 1e-12)
        ++disagree;
    }
  check("L-shaped polygon, clockwise: contains and the distance outside "
        "are those of its two rectangles",
        disagree == 0);
  consistent<2>("L-shaped polygon", l_shape, Point<2>(-0.5, -0.5),
                Point<2>(2.5, 2.5), false);
}

void
test_3d()
{
  const BallShape<3> sphere(Point<3>(0., 0., 0.), 1.);
  check("sphere: |x - c| - r",
        std::abs(sphere.signed_distance(Point<3>(1., 1., 1.)) -
                 (std::sqrt(3.) - 1.)) < 1e-14);
  consistent<3>("sphere", sphere, Point<3>(-2., -2., -2.),
                Point<3>(2., 2., 2.), true);

  const BoxShape<3> box(Point<3>(0., 0., 0.), Point<3>(1., 2., 3.));
  consistent<3>("box 3D", box, Point<3>(-1., -1., -1.), Point<3>(2., 3., 4.),
                true);

  // From (0,0,0) along z, length 2, radius 0.5.
  const CylinderShape<3> cylinder(Point<3>(0., 0., 0.),
                                  Tensor<1, 3>({0., 0., 2.}),
                                  0.5);
  check("cylinder: beyond the rim, sqrt(dr^2 + da^2)",
        std::abs(cylinder.signed_distance(Point<3>(1.5, 0., 3.)) -
                 std::sqrt(2.)) < 1e-14);
  check("cylinder: inside near the mantle, minus the radial gap, radial "
        "normal",
        std::abs(cylinder.signed_distance(Point<3>(0., 0.4, 1.)) + 0.1) <
            1e-14 &&
          (cylinder.outward_normal(Point<3>(0., 0.4, 1.)) -
           Tensor<1, 3>({0., 1., 0.}))
              .norm() < 1e-14);
  check("cylinder: inside near an end, minus the axial gap, axial normal",
        std::abs(cylinder.signed_distance(Point<3>(0.1, 0., 1.95)) + 0.05) <
            1e-14 &&
          (cylinder.outward_normal(Point<3>(0.1, 0., 1.95)) -
           Tensor<1, 3>({0., 0., 1.}))
              .norm() < 1e-14);
  consistent<3>("cylinder", cylinder, Point<3>(-1., -1., -1.),
                Point<3>(1., 1., 3.), true);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  test_2d();
  test_3d();
}
