#ifndef mpm_bodies_point_seeder_h
#define mpm_bodies_point_seeder_h

#include <deal.II/base/tensor.h>
#include <deal.II/particles/property_pool.h>

#include <boost/serialization/vector.hpp>

#include <mpm/basis/grid_basis.h>
#include <mpm/bodies/body.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Puts the material points of bodies into the grid, at any time of a run
   * (the bodies of a scene at its start; an inflow again later). Each rank
   * fills its own cells: with the grid's cells as placement, no point
   * needs a global search; a body on a mesh of its own is meshed whole on
   * every rank, and each keeps the points in its own cells. Ids continue
   * from `next_id`, which is the same on every rank and is saved in
   * checkpoints, so ids stay unique however often points are added.
   */
  template <int dim>
  class PointSeeder
  {
  public:
    explicit PointSeeder(const Grid<dim> &grid);

    /**
     * Put into the grid every body whose next release is due at `time`
     * (within `tolerance`): at the start, the bodies of the scene; later,
     * the inflows. Each release fills every locally owned cell with the
     * points of the released bodies that contain them (a point inside
     * several bodies goes to the first), at the positions of the body's
     * point placement (a quadrature on the reference cell), each with
     * volume det J times its weight (exact for bilinear cells), or at the
     * Gauss points of the body's own mesh with their JxW; mass from
     * the body's density, the law's seeded state and the body's initial
     * velocity. A release after the start into cells that hold material
     * is refused. Returns whether points were added.
     */
    bool
    release_due(const std::vector<Body<dim>> &                bodies,
                const std::vector<std::unique_ptr<Material>> &materials,
                MaterialPoints<dim> &                         points,
                const double                                  time,
                const double                                  tolerance);

    /**
     * Bad input of the bodies that is cheaper to find at the start than
     * when a body is due: a Density that the law does not follow, an
     * inflow whose region misses the grid. Throws on every rank.
     */
    void
    check_bodies(const std::vector<Body<dim>> &                bodies,
                 const std::vector<std::unique_ptr<Material>> &materials) const;

    /** The time of the next release due after the ones done (inf: none). */
    double
    next_release_time(const std::vector<Body<dim>> &bodies) const;

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

    /** The id the next point gets and the releases done, for Checkpoint. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &next_id &releases_done;
    }

  private:
    /** A point to be seeded. */
    struct Candidate
    {
      Point<dim>                                        x;
      Point<dim>                                        reference;
      typename Triangulation<dim>::active_cell_iterator cell;
      double                                            volume;
      Tensor<1, dim>                                    size;
      unsigned int                                      body;
    };

    /**
     * Visit the points of the bodies `which` in the locally owned cells,
     * in the order of the cells (then those of the bodies on meshes of
     * their own, body by body); with `present`, `occupied` is set if one
     * of their cells holds a point of it. They are visited, not collected:
     * a list of them would hold as much memory as the points themselves.
     */
    void
    for_each_candidate(
      const std::vector<Body<dim>> &                bodies,
      const std::vector<unsigned int> &             which,
      const Particles::ParticleHandler<dim> *       present,
      bool &                                        occupied,
      const std::function<void(const Candidate &)> &visit) const;

    /**
     * for_each_candidate() for body `b`, whose points sit at the Gauss
     * points of a mesh of its own: grouped by the grid cell they lie in,
     * each point seeded by one rank only, points outside the grid left
     * out.
     */
    void
    for_each_own_mesh_candidate(
      const std::vector<Body<dim>> &                bodies,
      const std::vector<unsigned int> &             which,
      const unsigned int                            b,
      const Particles::ParticleHandler<dim> *       present,
      bool &                                        occupied,
      const std::function<void(const Candidate &)> &visit) const;

    /**
     * Whether a body released with body `b` and before it in Bodies/Names
     * contains x: the point is that body's.
     */
    static bool
    claimed_earlier(const std::vector<Body<dim>> &   bodies,
                    const std::vector<unsigned int> &which,
                    const unsigned int               b,
                    const Point<dim> &               x);

    /** How many points the bodies `which` have in the locally owned cells. */
    std::uint64_t
    count_candidates(const std::vector<Body<dim>> &    bodies,
                     const std::vector<unsigned int> &which) const;

    /** Seed the bodies `which` (indices into `bodies`) at `time`. */
    void
    seed(const std::vector<Body<dim>> &                bodies,
         const std::vector<unsigned int> &             which,
         const std::vector<std::unique_ptr<Material>> &materials,
         MaterialPoints<dim> &                         points,
         const double                                  time);

    static std::string
    body_names(const std::vector<Body<dim>> &   bodies,
               const std::vector<unsigned int> &which);

    const Grid<dim>       &grid;
    const GridBasis<dim>   basis;
    types::particle_index next_id = 0;
    /** Per body, how many times it has been released. */
    std::vector<unsigned int> releases_done;
  };
} // namespace mpm

#endif
