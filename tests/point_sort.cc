// MaterialPoints::sort moves the points that left their cells itself when
// they stay on the rank, and leaves the rest to deal.II's sort. Its result
// must be deal.II's, to the bit: the same points in the same cells, in the
// same order (which fixes every sum over points), with the same reference
// locations and properties. Two copies of a block that fills the unit
// square (cube), on 5^dim cells (edges of 0.2, whose inverse is not a
// binary fraction), are moved alike by random displacements
// drawn from each point's id; one is sorted by sort(), the other by
// deal.II's sort_particles_into_subdomains_and_cells() alone. Three grids:
// boxes (MappingCartesian, whose arithmetic sort() repeats), boxes refined
// in the left half (points walk into finer and coarser neighbours) and a
// distorted grid (MappingQ). Rounds of small moves (at most 0.05 of the
// smallest cell per direction: a few points change cells), then of moves
// up to 0.2 of it (10-20 % of the points change cells, some diagonally:
// two or three faces).
// - after every round both copies agree exactly;
// - on one rank, the small rounds leave the pool alone (no call of
//   deal.II's sort), and of the larger ones some are sorted by sort()
//   alone and some, once a quarter of the points have moved since the
//   last layout, by deal.II.

#include <deal.II/base/mpi.h>

#include <mpm/grid/grid.h>
#include <mpm/points/material_points.h>

#include <cmath>
#include <random>

#include "small_scene.h"
#include "tests.h"

using namespace dealii;
using namespace mpm;

namespace
{
  /**
   * Move every point of `points` by up to `reach` of the smallest cell per
   * direction (an explicit step moves a point less than that, and deal.II's
   * sort follows a point only into the ghost cells).
   */
  template <int dim>
  void
  move(MaterialPoints<dim> &points,
       const double         reach,
       const unsigned int   round)
  {
    const double h = points.get_grid().minimum_cell_size();
    for (auto &particle : points.handler())
      {
        std::mt19937 rng(1000 * round + particle.get_id());
        std::uniform_real_distribution<double> step(-reach * h, reach * h);
        Point<dim>                             x = particle.get_location();
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = std::min(0.999, std::max(0.001, x[d] + step(rng)));
        particle.set_location(x);
      }
  }



  /** Whether a and b hold the same points in the same order, bit for bit. */
  template <int dim>
  bool
  identical(const MaterialPoints<dim> &a, const MaterialPoints<dim> &b)
  {
    bool same = a.handler().n_locally_owned_particles() ==
                b.handler().n_locally_owned_particles();
    auto q = b.handler().begin();
    for (auto p = a.handler().begin(); same && p != a.handler().end(); ++p, ++q)
      {
        same = p->get_id() == q->get_id() &&
               p->get_surrounding_cell() == q->get_surrounding_cell() &&
               p->get_location() == q->get_location() &&
               p->get_reference_location() == q->get_reference_location();
        const ArrayView<const double> pa = p->get_properties();
        const ArrayView<const double> pb = q->get_properties();
        for (unsigned int k = 0; same && k < pa.size(); ++k)
          same = pa[k] == pb[k];
      }
    return Utilities::MPI::min(same ? 1 : 0, MPI_COMM_WORLD) == 1;
  }


  /**
   * Whether the property pool holds the points of this rank one after the
   * other in the handler's order (as a layout leaves it). Local.
   */
  template <int dim>
  bool
  in_pool_order(const MaterialPoints<dim> &points)
  {
    const auto & handler = points.handler();
    const double *next    = nullptr;
    bool          ordered = true;
    for (const auto &point : handler)
      {
        const double *here = point.get_properties().data();
        ordered = ordered && (next == nullptr || here == next);
        next    = here + handler.n_properties_per_particle();
      }
    return ordered;
  }
} // namespace



template <int dim>
void
test(const std::string &kind)
{
  deallog << "dim = " << dim << ", " << kind << std::endl;
  const MPI_Comm   comm     = MPI_COMM_WORLD;
  const bool       one_rank = Utilities::MPI::n_mpi_processes(comm) == 1;
  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(
    prm,
    std::string("subsection Grid\n set Generator = subdivided_hyper_cube\n"
                " set Arguments = 5 : 0 : 1 : ") +
      (kind == "distorted" ? "false" : "true") +
      "\nend\nsubsection body\n set Shape = box\n" +
      (dim == 2 ? " set Lower corner = 0,0\n set Upper corner = 1,1\n" :
                  " set Lower corner = 0,0,0\n set Upper corner = 1,1,1\n") +
      " set Material = steel\n set Points per cell direction = 3\nend\n");
  Grid<dim> grid(prm, comm);
  grid.create();
  if (kind == "distorted")
    grid.transform(&mpm_tests::distort<dim>);
  if (kind == "refined left half")
    grid.adapt(
      [](const auto &cell) { return cell->center()[0] < 0.5 ? 1 : 0; });

  std::vector<std::unique_ptr<Material>> materials;
  MaterialPoints<dim>                    sorted(grid, {});
  MaterialPoints<dim>                    by_dealii(grid, {});
  mpm_tests::seed_small_scene(prm, grid, materials, sorted);
  mpm_tests::seed_small_scene(prm, grid, materials, by_dealii);
  const unsigned int layouts_at_start = sorted.n_pool_layouts();

  bool         always_identical = true;
  bool         laid_out_in_order = true;
  unsigned int round            = 0;
  const auto move_and_sort = [&](const double reach, const unsigned int until) {
    for (; round < until; ++round)
      {
        move(sorted, reach, round);
        move(by_dealii, reach, round);
        const unsigned int layouts_before = sorted.n_pool_layouts();
        sorted.sort();
        by_dealii.handler().sort_particles_into_subdomains_and_cells();
        always_identical = always_identical && identical(sorted, by_dealii);
        // Each rank checks its own pool, if it laid it out this round.
        const bool in_order =
          sorted.n_pool_layouts() == layouts_before || in_pool_order(sorted);
        laid_out_in_order =
          laid_out_in_order &&
          Utilities::MPI::min(in_order ? 1 : 0, MPI_COMM_WORLD) == 1;
      }
  };
  move_and_sort(0.05, 4);
  if (one_rank)
    mpm_tests::check("small moves: the pool is left alone",
                     sorted.n_pool_layouts() == layouts_at_start);
  // Moves of up to 0.2 of a cell take some 10-20 % of the points into
  // other cells, some across two or three faces: sort() moves them itself
  // until a quarter of the points have moved since the last layout.
  move_and_sort(0.2, 10);
  const unsigned int layouts = sorted.n_pool_layouts() - layouts_at_start;
  if (one_rank)
    mpm_tests::check("larger moves: sort() moves the points itself in some "
                     "rounds and lays the pool out again in others",
                     layouts > 0 && layouts < 6);
  mpm_tests::check("every round equals deal.II's sort, bit for bit",
                   always_identical);
  mpm_tests::check("after each layout the pool holds the points in order",
                   laid_out_in_order);
  deallog << "points: " << sorted.n_global_points() << std::endl;
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  for (const std::string kind : {"boxes", "refined left half", "distorted"})
    {
      test<2>(kind);
      test<3>(kind);
    }
}
