#ifndef mpm_grid_geometry_h
#define mpm_grid_geometry_h

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * What the plane of a 2D scene stands for (Grid/Geometry), and the
   * measures that follow from it: a slice of unit depth (plane strain), a
   * plate of initial thickness h_0 free on both faces (plane stress), or a
   * body of revolution about the y axis, x the radius (axisymmetric); a
   * 3D scene is itself. Every part that turns a point's or a face's plane
   * measure into a volume, a mass or an area, or adds the hoop terms of a
   * ring, asks this class; only the parts that refuse a geometry read its
   * kind().
   */
  template <int dim>
  class Geometry
  {
  public:
    enum class Kind
    {
      plane_strain,
      plane_stress,
      axisymmetric,
      solid
    };

    /** `Geometry` and `Thickness`, in the current subsection (Grid). */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse them from the current subsection (Grid); InputError if bad. */
    explicit Geometry(const ParameterHandler &prm);

    Kind
    kind() const
    {
      return geometry_kind;
    }

    /**
     * In an axisymmetric scene gravity acts along the axis, y (InputError
     * otherwise).
     */
    void
    check_gravity(const Tensor<1, dim> &gravity) const;

    /** The prm name of the geometry, for messages. */
    std::string
    name() const;

    /**
     * What a unit of 2D area or length at x stands for: the ring it sweeps
     * about the axis, 2 pi x, in an axisymmetric scene; the plate's initial
     * thickness in plane stress; 1 otherwise (and in 3D).
     */
    double
    out_of_plane_measure(const Point<dim> &x) const
    {
      return geometry_kind == Kind::axisymmetric ? 2. * numbers::PI * x[0] :
                                                   thickness;
    }

    /**
     * The radius whose hoop terms a point at x carries (the internal
     * force's sigma_tt / r): x_0 in an axisymmetric scene, 0 (none)
     * otherwise.
     */
    double
    hoop_radius(const Point<dim> &x) const
    {
      return geometry_kind == Kind::axisymmetric ? x[0] : 0.;
    }

    /**
     * The hoop ratio of a radial quantity at x: radial() / x_0 in an
     * axisymmetric scene (the hoop rate v_r / r from the radial velocity,
     * the hoop strain u_r / r from the radial displacement), 0 otherwise,
     * where radial() is not called.
     */
    template <typename Radial>
    double
    hoop_ratio(const Point<dim> &x, const Radial &radial) const
    {
      return geometry_kind == Kind::axisymmetric ? radial() / x[0] : 0.;
    }

    /**
     * The directions a volumetric rate spreads over: the hoop direction
     * too in an axisymmetric scene, the plane's (or space's) otherwise.
     */
    unsigned int
    n_stretching_directions() const
    {
      return geometry_kind == Kind::axisymmetric ? 3 : dim;
    }

    /**
     * Whether every point's sigma_zz is zero (a plate free on both faces),
     * held by its law through the out-of-plane stretch.
     */
    bool
    free_faces() const
    {
      return geometry_kind == Kind::plane_stress;
    }

    /**
     * A 2D point's volume over the out-of-plane part of its stretch F_zz:
     * its volume at the plate's initial thickness in plane stress (V /
     * F_zz), its volume otherwise.
     */
    double
    volume_at_initial_thickness(const double volume,
                                const double out_of_plane_stretch) const
    {
      return volume / (geometry_kind == Kind::plane_stress ?
                         out_of_plane_stretch :
                         1.);
    }

  private:
    Kind   geometry_kind = Kind::plane_strain;
    /** The plate's initial thickness in plane stress, 1 otherwise. */
    double thickness = 1.;
  };
} // namespace mpm

#endif
