#ifndef mpm_bodies_body_h
#define mpm_bodies_body_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/base/shape.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A body of material: a shape filled with material points, the material
   * they are made of, and their initial velocity. Shapes: box, disk (2D),
   * sphere (3D), cylinder (3D) and polygon (2D).
   */
  template <int dim>
  class Body
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse the current subsection; `section_path` is for messages. */
    Body(const ParameterHandler &        prm,
         const std::string &             name,
         const std::string &             section_path,
         const std::vector<std::string> &material_names);

    bool
    contains(const Point<dim> &x) const
    {
      return shape->contains(x);
    }

    /** The region the body fills. */
    const Shape<dim> &
    region() const
    {
      return *shape;
    }

    Tensor<1, dim>
    initial_velocity(const Point<dim> &x) const;

    const std::string &
    name() const
    {
      return body_name;
    }

    unsigned int
    material_index() const
    {
      return material;
    }

    /**
     * Where the points of a cell go on the reference cell, and the share of
     * the cell's volume each stands for: centres of an n^dim subdivision,
     * or the n^dim Gauss points.
     */
    const Quadrature<dim> &
    point_placement() const
    {
      return placement;
    }

    /**
     * Whether the points sit at the placement's points in the cells of a
     * mesh of the body's own (region().fill_mesh()) rather than in the
     * background grid's cells.
     */
    bool
    placed_on_own_mesh() const
    {
      return own_mesh;
    }

    /**
     * The 1D weight in direction d of the k-th placement point: the share
     * of the cell's extent in d that the point stands for.
     */
    double
    placement_weight_1d(const unsigned int k, const unsigned int d) const
    {
      // The tensor-product ordering of deal.II: x runs fastest.
      unsigned int index = k;
      for (unsigned int e = 0; e < d; ++e)
        index /= placement_1d.size();
      return placement_1d.weight(index % placement_1d.size());
    }

    /** The bulk density of its points; 0: the material's Density. */
    double
    density() const
    {
      return bulk_density;
    }

    /** How many times the body is put into the grid (1: once). */
    unsigned int
    releases() const
    {
      return n_releases;
    }

    /** The time of the k-th release, k = 0, 1, ... */
    double
    release_time(const unsigned int k) const;

    /** Whether the body is put into the grid after the start. */
    bool
    is_inflow() const
    {
      return n_releases > 1 || first_release > 0.;
    }

    /** An inflow needs the explicit scheme (InputError). */
    void
    check_scene(const SceneChoices &choices) const
    {
      if (is_inflow() && !choices.explicit_steps())
        throw InputError("Bodies/" + body_name + ": an inflow (First release "
                         "> 0 or Releases > 1) needs Time stepping/Scheme "
                         "= explicit.");
    }

    /** Its contact group (FieldContact). */
    const std::string &
    contact_group() const
    {
      return group;
    }

    /** Whether the body starts under geostatic stress. */
    bool
    geostatic() const
    {
      return geostatic_k0 >= 0.;
    }

    /** Horizontal over vertical stress of the geostatic state. */
    double
    k0() const
    {
      return geostatic_k0;
    }

  private:
    std::string                 body_name;
    std::string                 group;
    std::unique_ptr<Shape<dim>> shape;
    unsigned int            material = 0;
    double                  bulk_density     = 0.;
    double                  first_release    = 0.;
    unsigned int            n_releases       = 1;
    double                  release_interval = 0.;
    /** K0 of the geostatic stress; negative: no initial stress. */
    double                  geostatic_k0 = -1.;
    bool                    own_mesh = false;
    Quadrature<1>           placement_1d;
    Quadrature<dim>         placement;
    std::unique_ptr<FunctionParser<dim>> velocity;
  };
} // namespace mpm

#endif
