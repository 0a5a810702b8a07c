#ifndef mpm_assembly_nodal_density_h
#define mpm_assembly_nodal_density_h

#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/assembly/grid_field.h>
#include <mpm/points/point_layout.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The density from the point positions (the grid field "Density from
   * positions"), Wieckowski (2004) eqs. 12-13 in their Q1 form: a nodal
   * density rho_i = m_i / V_i, the lumped nodal mass over the occupied nodal
   * volume V_i, the sum of int_c N_i dV over the cells c around node i that
   * hold at least one point; interpolated to a point, rho_P = sum_i
   * N_i(x_P) rho_i. On a lattice of points at the centres of a regular
   * subdivision of each cell the midpoint rule makes both sums exact, so
   * rho_P is the lattice's density everywhere, on a free surface along grid
   * lines too.
   *
   * The mass and the volume are those of the plane: the nodal mass is
   * sum_P N_i m_P / w(x_P), w the geometry's out-of-plane measure, which is
   * 1 in plane strain and 3D. In an axisymmetric scene (w = 2 pi x) that is
   * the rings' masses per radian and unit radius, over the plane nodal
   * areas. (The ring masses over the ring volumes would not be exact: N_i x
   * is quadratic, and next to the axis the midpoint rule is 12.5 % off with
   * 2 x 2 points per cell.)
   */
  template <int dim>
  class NodalDensity : public GridField<dim>
  {
  public:
    NodalDensity(const Grid<dim> &grid, const GridBasis<dim> &basis);

    /** No plane nodal mass yet. */
    void
    begin_projection() override;

    /** Add the plane mass m / w(x) of a point at x with this support. */
    void
    add_point(const Support<dim> &           support,
              const ArrayView<const double> &p,
              const Point<dim> &             x) override
    {
      const double plane = p[PointLayout<dim>::mass] /
                           grid.geometry().out_of_plane_measure(x);
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        plane_mass.local_element(support.nodes[i]) += support.N[i] * plane;
    }

    /**
     * The occupied nodal volumes of the cells that hold points of
     * `handler`, and the plane nodal masses, summed across ranks (owned and
     * ghost nodes).
     */
    void
    finish_projection(const Particles::ParticleHandler<dim> &handler) override;

    /** rho_P at a point with this support. */
    double
    value(const Support<dim> &support) const override
    {
      double density = 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const unsigned int node   = support.nodes[i];
          const double       volume = occupied_volume.local_element(node);
          if (volume > 0.)
            density +=
              support.N[i] * plane_mass.local_element(node) / volume;
        }
      return density;
    }

  private:
    const Grid<dim> &                          grid;
    const GridBasis<dim> &                     basis;
    LinearAlgebra::distributed::Vector<double> occupied_volume;
    /** sum_P N_i m_P / w(x_P) at each node. */
    LinearAlgebra::distributed::Vector<double> plane_mass;
  };
} // namespace mpm

#endif
