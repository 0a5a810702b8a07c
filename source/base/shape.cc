#include <deal.II/base/exceptions.h>

#include <deal.II/grid/grid_generator.h>

#include <mpm/base/input_error.h>
#include <mpm/base/shape.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm
{
  template <int dim>
  void
  Shape<dim>::fill_mesh(Triangulation<dim> &, const double) const
  {
    AssertThrow(false, ExcMessage("This shape has no mesh of its own."));
  }



  template <int dim>
  void
  Shape<dim>::throw_too_many_cells()
  {
    throw InputError("Point placement = body mesh: the body would need more "
                     "than 2^21 cells of the grid's smallest size; use a "
                     "coarser grid or Point placement = centres.");
  }



  template <int dim>
  BoxShape<dim>::BoxShape(const Point<dim> &lower, const Point<dim> &upper)
    : lower(lower)
    , upper(upper)
  {}



  template <int dim>
  Tensor<1, dim>
  BoxShape<dim>::beyond_faces(const Point<dim> &x) const
  {
    Tensor<1, dim> q;
    for (unsigned int d = 0; d < dim; ++d)
      q[d] = std::max(lower[d] - x[d], x[d] - upper[d]);
    return q;
  }



  template <int dim>
  double
  BoxShape<dim>::signed_distance(const Point<dim> &x) const
  {
    // Outside: the length of the positive parts; inside: the nearest face.
    const Tensor<1, dim> q = beyond_faces(x);
    double outside = 0., inside = -std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < dim; ++d)
      {
        outside += std::max(q[d], 0.) * std::max(q[d], 0.);
        inside = std::max(inside, q[d]);
      }
    return outside > 0. ? std::sqrt(outside) : inside;
  }



  template <int dim>
  Tensor<1, dim>
  BoxShape<dim>::outward_normal(const Point<dim> &x) const
  {
    const Tensor<1, dim> q = beyond_faces(x);
    Tensor<1, dim>       n;
    unsigned int         nearest = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double side = x[d] - lower[d] < upper[d] - x[d] ? -1. : 1.;
        n[d]              = side * std::max(q[d], 0.);
        if (q[d] > q[nearest])
          nearest = d;
      }
    if (n.norm() > 0.)
      return n / n.norm();
    // Inside (or on the surface): the normal of the nearest face.
    n[nearest] = x[nearest] - lower[nearest] < upper[nearest] - x[nearest] ?
                   -1. :
                   1.;
    return n;
  }



  template <int dim>
  void
  BoxShape<dim>::fill_mesh(Triangulation<dim> &mesh,
                           const double        cell_size) const
  {
    std::vector<unsigned int> repetitions(dim);
    double                    n_cells = 1.;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double n =
          std::max(1., std::ceil((upper[d] - lower[d]) / cell_size - 1e-9));
        n_cells *= n;
        if (n_cells > Shape<dim>::max_mesh_cells)
          Shape<dim>::throw_too_many_cells();
        repetitions[d] = static_cast<unsigned int>(n);
      }
    GridGenerator::subdivided_hyper_rectangle(mesh, repetitions, lower, upper);
  }



  template <int dim>
  BallShape<dim>::BallShape(const Point<dim> &center, const double radius)
    : center(center)
    , radius(radius)
  {}



  template <int dim>
  Tensor<1, dim>
  BallShape<dim>::outward_normal(const Point<dim> &x) const
  {
    Tensor<1, dim> n = x - center;
    if (!(n.norm() > 0.))
      n[0] = 1.; // the centre: every direction is as near
    return n / n.norm();
  }



  template <int dim>
  CylinderShape<dim>::CylinderShape(const Point<dim> &    start,
                                    const Tensor<1, dim> &axis,
                                    const double          radius)
    : start(start)
    , axis(axis)
    , radius(radius)
  {}



  template <int dim>
  void
  CylinderShape<dim>::beyond(const Point<dim> &x,
                             double &          radial,
                             double &          axial,
                             Tensor<1, dim> &  radial_direction,
                             Tensor<1, dim> &  axial_direction) const
  {
    const double         length = axis.norm();
    const Tensor<1, dim> e      = axis / length;
    const Tensor<1, dim> d      = x - start;
    const double         s      = d * e;
    const Tensor<1, dim> r      = d - s * e;
    radial                      = r.norm() - radius;
    if (r.norm() > 0.)
      radial_direction = r / r.norm();
    else
      {
        // On the axis: every direction normal to it is as near.
        Tensor<1, dim> any;
        any[std::abs(e[0]) < 0.9 ? 0 : 1] = 1.;
        radial_direction = any - (any * e) * e;
        radial_direction /= radial_direction.norm();
      }
    axial            = std::max(-s, s - length);
    axial_direction  = (s < 0.5 * length ? -1. : 1.) * e;
  }



  template <int dim>
  double
  CylinderShape<dim>::signed_distance(const Point<dim> &x) const
  {
    double         radial, axial;
    Tensor<1, dim> radial_direction, axial_direction;
    beyond(x, radial, axial, radial_direction, axial_direction);
    if (radial > 0. || axial > 0.)
      return std::sqrt(std::max(radial, 0.) * std::max(radial, 0.) +
                       std::max(axial, 0.) * std::max(axial, 0.));
    return std::max(radial, axial);
  }



  template <int dim>
  Tensor<1, dim>
  CylinderShape<dim>::outward_normal(const Point<dim> &x) const
  {
    double         radial, axial;
    Tensor<1, dim> radial_direction, axial_direction;
    beyond(x, radial, axial, radial_direction, axial_direction);
    if (radial > 0. || axial > 0.)
      {
        const Tensor<1, dim> n = std::max(radial, 0.) * radial_direction +
                                 std::max(axial, 0.) * axial_direction;
        return n / n.norm();
      }
    return radial > axial ? radial_direction : axial_direction;
  }



  template <int dim>
  PolygonShape<dim>::PolygonShape(const std::vector<Point<dim>> &vertices)
    : vertices(vertices)
  {
    // Twice the signed area (shoelace).
    double area = 0.;
    for (unsigned int i = 0, j = vertices.size() - 1; i < vertices.size();
         j = i++)
      area += vertices[j][0] * vertices[i][1] - vertices[i][0] * vertices[j][1];
    orientation = area > 0. ? 1. : -1.;
  }



  template <int dim>
  bool
  PolygonShape<dim>::contains(const Point<dim> &x) const
  {
    // Even-odd rule with a ray in +x direction.
    bool               inside = false;
    const unsigned int n      = vertices.size();
    for (unsigned int i = 0, j = n - 1; i < n; j = i++)
      {
        const Point<dim> &a = vertices[i];
        const Point<dim> &b = vertices[j];
        if ((a[1] > x[1]) != (b[1] > x[1]) &&
            x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0])
          inside = !inside;
      }
    return inside;
  }



  template <int dim>
  Point<dim>
  PolygonShape<dim>::nearest_boundary_point(const Point<dim> &x,
                                            unsigned int &    edge) const
  {
    Point<dim> nearest;
    double     best = std::numeric_limits<double>::max();
    for (unsigned int i = 0, j = vertices.size() - 1; i < vertices.size();
         j = i++)
      {
        const Tensor<1, dim> ab = vertices[i] - vertices[j];
        const double         t =
          std::clamp((x - vertices[j]) * ab / ab.norm_square(), 0., 1.);
        const Point<dim> p = vertices[j] + t * ab;
        if (x.distance_square(p) < best)
          {
            best    = x.distance_square(p);
            nearest = p;
            edge    = j;
          }
      }
    return nearest;
  }



  template <int dim>
  double
  PolygonShape<dim>::signed_distance(const Point<dim> &x) const
  {
    unsigned int edge;
    const double distance = x.distance(nearest_boundary_point(x, edge));
    return contains(x) ? -distance : distance;
  }



  template <int dim>
  Tensor<1, dim>
  PolygonShape<dim>::outward_normal(const Point<dim> &x) const
  {
    unsigned int         edge;
    const Point<dim>     p = nearest_boundary_point(x, edge);
    const Tensor<1, dim> d = x - p;
    if (d.norm() > 1e-12 * (vertices[0] - vertices[1]).norm())
      return (contains(x) ? -1. : 1.) * d / d.norm();
    // On an edge: its outward normal, from the orientation of the vertices.
    const Tensor<1, dim> along =
      vertices[(edge + 1) % vertices.size()] - vertices[edge];
    Tensor<1, dim> n;
    n[0] = orientation * along[1];
    n[1] = -orientation * along[0];
    return n / n.norm();
  }



  template <int dim>
  void
  BallShape<dim>::fill_mesh(Triangulation<dim> &mesh,
                            const double        cell_size) const
  {
    // deal.II's balanced ball (cells of even size), with a spherical
    // manifold on its surface: refinement keeps the surface round.
    GridGenerator::hyper_ball_balanced(mesh, center, radius);
    const double volume = dim == 2 ? numbers::PI * radius * radius :
                                     4. / 3. * numbers::PI * std::pow(radius, 3);
    while (volume / mesh.n_active_cells() > std::pow(cell_size, dim))
      {
        if (mesh.n_active_cells() * std::pow(2., dim) > Shape<dim>::max_mesh_cells)
          Shape<dim>::throw_too_many_cells();
        mesh.refine_global(1);
      }
  }



  template class Shape<2>;
  template class Shape<3>;
  template class BoxShape<2>;
  template class BoxShape<3>;
  template class BallShape<2>;
  template class BallShape<3>;
  template class CylinderShape<2>;
  template class CylinderShape<3>;
  template class PolygonShape<2>;
  template class PolygonShape<3>;
} // namespace mpm
