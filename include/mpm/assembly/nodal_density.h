#ifndef mpm_assembly_nodal_density_h
#define mpm_assembly_nodal_density_h

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/basis/grid_basis.h>
#include <mpm/basis/support.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The density from the point positions, Wieckowski (2004) eqs. 12-13 in
   * their Q1 form: a nodal density rho_i = m_i / V_i, the lumped nodal mass
   * over the occupied nodal volume V_i, the sum of int_c N_i dV over the
   * cells c around node i that hold at least one point; interpolated to a
   * point, rho_P = sum_i N_i(x_P) rho_i. On a lattice of points at the
   * centres of a regular subdivision of each cell the midpoint rule makes
   * both sums exact, so rho_P is the lattice's density everywhere,
   * on a free surface along grid lines too.
   *
   * In an axisymmetric scene the same holds for the density in the r-z
   * plane: the nodal mass is then sum_P N_i m_P / (2 pi x_P), the rings'
   * masses per radian and unit radius, over the plane nodal areas. (The
   * ring masses over the ring volumes would not be exact: N_i x is
   * quadratic, and next to the axis the midpoint rule is 12.5 % off with
   * 2 x 2 points per cell.)
   */
  template <int dim>
  class NodalDensity
  {
  public:
    NodalDensity(const Grid<dim> &grid, const GridBasis<dim> &basis);

    /** Before a projection of the mass: no plane nodal mass yet. */
    void
    begin_projection();

    /**
     * During it, in an axisymmetric scene: add the plane mass m / (2 pi
     * x) of a point at x with this support.
     */
    void
    add_point(const Support<dim> &support,
              const double        mass,
              const Point<dim> &  x)
    {
      if (!grid.is_axisymmetric())
        return;
      const double plane = mass / grid.out_of_plane_measure(x);
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        plane_mass.local_element(support.nodes[i]) += support.N[i] * plane;
    }

    /**
     * After it: the occupied nodal volumes of the cells that hold points of
     * `handler`, and the plane nodal masses, summed across ranks (owned and
     * ghost nodes).
     */
    void
    compute_occupied_volumes(const Particles::ParticleHandler<dim> &handler);

    /**
     * rho_P at a point with this support, from the nodal masses of the
     * last projection.
     */
    double
    at(const Support<dim> &support, const GridNodes<dim> &nodes) const
    {
      double density = 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const unsigned int node   = support.nodes[i];
          const double       volume = occupied_volume.local_element(node);
          if (volume > 0.)
            density += support.N[i] *
                       (grid.is_axisymmetric() ?
                          plane_mass.local_element(node) :
                          nodes.mass_at(node)) /
                       volume;
        }
      return density;
    }

  private:
    const Grid<dim> &                          grid;
    const GridBasis<dim> &                     basis;
    LinearAlgebra::distributed::Vector<double> occupied_volume;
    /** Axisymmetric scenes: sum_P N_i m_P / (2 pi x_P) at each node. */
    LinearAlgebra::distributed::Vector<double> plane_mass;
  };
} // namespace mpm

#endif
