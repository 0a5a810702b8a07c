#ifndef mpm_base_shape_h
#define mpm_base_shape_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A region of space: whether a point lies in it, how far a point is from
   * its surface, and the surface's outward normal there. Bodies are filled
   * by shapes, load regions are shapes, and rigid obstacles act on the
   * nodes a shape's surface reaches. Shapes live in base/, below every
   * layer that uses them.
   */
  template <int dim>
  class Shape
  {
  public:
    virtual ~Shape() = default;

    /** Whether x lies in the shape (its surface included). */
    virtual bool
    contains(const Point<dim> &x) const = 0;

    /**
     * The distance from x to the surface, negative inside: exact, not a
     * bound.
     */
    virtual double
    signed_distance(const Point<dim> &x) const = 0;

    /** The outward unit normal of the surface point nearest to x. */
    virtual Tensor<1, dim>
    outward_normal(const Point<dim> &x) const = 0;

    /** Whether fill_mesh() can mesh the shape. */
    virtual bool
    has_mesh() const
    {
      return false;
    }

    /**
     * Fill `mesh` (empty) with cells that fit the shape, none larger than
     * `cell_size` across on average, with manifolds attached so that a
     * curved surface stays curved under a higher-order mapping. Only for
     * shapes with has_mesh().
     */
    virtual void
    fill_mesh(Triangulation<dim> &mesh, const double cell_size) const;

  protected:
    /** The most cells a body's own mesh may have. */
    static constexpr double max_mesh_cells = 2097152.;

    /** The input error of a body whose mesh would be too large. */
    [[noreturn]] static void
    throw_too_many_cells();

  public:
    /**
     * Whether the shape comes within half a grid cell's diameter of the
     * cell's centre: the cells that a body's or a region's refinement
     * counts as its own.
     */
    template <class CellIterator>
    bool
    reaches_cell(const CellIterator &cell) const
    {
      return signed_distance(cell->center()) <= 0.5 * cell->diameter();
    }
  };



  /** An axis-aligned box between two corners. */
  template <int dim>
  class BoxShape : public Shape<dim>
  {
  public:
    BoxShape(const Point<dim> &lower, const Point<dim> &upper);

    bool
    contains(const Point<dim> &x) const override
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (x[d] < lower[d] || x[d] > upper[d])
          return false;
      return true;
    }

    double
    signed_distance(const Point<dim> &x) const override;

    Tensor<1, dim>
    outward_normal(const Point<dim> &x) const override;

    bool
    has_mesh() const override
    {
      return true;
    }

    /** Cells of about cell_size along each edge. */
    void
    fill_mesh(Triangulation<dim> &mesh, const double cell_size) const override;

  private:
    /** Per direction, how far x is beyond the nearer face (< 0 inside). */
    Tensor<1, dim>
    beyond_faces(const Point<dim> &x) const;

    Point<dim> lower;
    Point<dim> upper;
  };



  /** A disk (2D) or sphere (3D). */
  template <int dim>
  class BallShape : public Shape<dim>
  {
  public:
    BallShape(const Point<dim> &center, const double radius);

    bool
    contains(const Point<dim> &x) const override
    {
      return x.distance_square(center) <= radius * radius;
    }

    double
    signed_distance(const Point<dim> &x) const override
    {
      return x.distance(center) - radius;
    }

    Tensor<1, dim>
    outward_normal(const Point<dim> &x) const override;

    bool
    has_mesh() const override
    {
      return true;
    }

    /** deal.II's ball, refined until its mean cell is cell_size^dim. */
    void
    fill_mesh(Triangulation<dim> &mesh, const double cell_size) const override;

  private:
    Point<dim> center;
    double     radius;
  };



  /**
   * A solid cylinder (3D) from the centre of one end, `start`, along
   * `axis`, whose length is the cylinder's.
   */
  template <int dim>
  class CylinderShape : public Shape<dim>
  {
  public:
    CylinderShape(const Point<dim> &    start,
                  const Tensor<1, dim> &axis,
                  const double          radius);

    bool
    contains(const Point<dim> &x) const override
    {
      const Tensor<1, dim> d = x - start;
      const double         t = d * axis / axis.norm_square();
      return t >= 0. && t <= 1. &&
             (d - t * axis).norm_square() <= radius * radius;
    }

    double
    signed_distance(const Point<dim> &x) const override;

    Tensor<1, dim>
    outward_normal(const Point<dim> &x) const override;

  private:
    /**
     * Distances beyond the mantle and beyond the nearer end (< 0 inside),
     * and the unit directions out through each.
     */
    void
    beyond(const Point<dim> &x,
           double &          radial,
           double &          axial,
           Tensor<1, dim> &  radial_direction,
           Tensor<1, dim> &  axial_direction) const;

    Point<dim>     start;
    Tensor<1, dim> axis;
    double         radius;
  };



  /** A simple polygon (2D), its vertices in either order. */
  template <int dim>
  class PolygonShape : public Shape<dim>
  {
  public:
    explicit PolygonShape(const std::vector<Point<dim>> &vertices);

    bool
    contains(const Point<dim> &x) const override;

    double
    signed_distance(const Point<dim> &x) const override;

    Tensor<1, dim>
    outward_normal(const Point<dim> &x) const override;

  private:
    /** The point of the boundary nearest to x, and the edge it is on. */
    Point<dim>
    nearest_boundary_point(const Point<dim> &x, unsigned int &edge) const;

    std::vector<Point<dim>> vertices;
    /** +1 if the vertices run counter-clockwise, -1 otherwise. */
    double orientation;
  };
} // namespace mpm

#endif
