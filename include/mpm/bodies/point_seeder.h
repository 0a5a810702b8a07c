#ifndef mpm_bodies_point_seeder_h
#define mpm_bodies_point_seeder_h

#include <deal.II/base/tensor.h>
#include <deal.II/particles/property_pool.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/bodies/body.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Puts the material points of bodies into the grid, at any time of a run
   * (the bodies of a scene at its start; an inflow again later). Each rank
   * fills its own cells, so no point needs a global search. Ids continue
   * from `next_id`, which is the same on every rank and is saved in
   * checkpoints, so ids stay unique however often points are added.
   */
  template <int dim>
  class PointSeeder
  {
  public:
    explicit PointSeeder(const Grid<dim> &grid);

    /**
     * Fill every locally owned cell with the points of the bodies that
     * contain them (a point inside several bodies goes to the first), at
     * the positions of the body's point placement (a quadrature on the
     * reference cell), each with volume det J times its weight (exact for
     * bilinear cells), the law's reference stress and the body's initial
     * velocity.
     */
    void
    seed(const std::vector<Body<dim>> &                bodies,
         const std::vector<std::unique_ptr<Material>> &materials,
         MaterialPoints<dim> &                         points);

    /**
     * Start the points of geostatic bodies under the K0 stress: vertical
     * stress -rho |g| depth along gravity, depth below the top of the body
     * (its highest point plus half that point's extent), K0 times it
     * across. Sets the stress, the law's internal state and the stored
     * energy of each point.
     */
    void
    apply_geostatic_stress(
      const std::vector<Body<dim>> &                bodies,
      const std::vector<std::unique_ptr<Material>> &materials,
      const Tensor<1, dim> &                        gravity,
      MaterialPoints<dim> &                         points) const;

    /** The id the next point will get, for Checkpoint. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &next_id;
    }

  private:
    const Grid<dim>       &grid;
    const GridBasis<dim>   basis;
    types::particle_index next_id = 0;
  };
} // namespace mpm

#endif
