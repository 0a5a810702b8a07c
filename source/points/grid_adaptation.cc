#include <deal.II/base/mpi.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/base/input_error.h>
#include <mpm/points/grid_adaptation.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <set>

namespace mpm
{
  template <int dim>
  void
  GridAdaptation<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptive grid");
    prm.declare_entry(
      "Refinement levels", "0", Patterns::Integer(0, 10),
      "Times the cells near the material are refined beyond the grid of "
      "the scene (Generator and Global refinements), which is the "
      "coarsest the grid gets; 0: the grid stays as the scene gives it. "
      "MPM with linear shape functions, every scheme. The explicit time "
      "step follows the finest cells.");
    prm.declare_entry(
      "Margin", "2", Patterns::Integer(0, 20),
      "Rings of cells at the finest level kept around every cell that "
      "holds material; a refinement reaches out to twice as many, and "
      "cells beyond three times as many coarsen again. With 1 or more the "
      "material's cells have no hanging vertices, and a run gives the "
      "results of the uniform grid of the finest cells (implicit runs: "
      "with Newton/Integration = material points, which they use on an "
      "adapted grid); 0 refines the "
      "cells that hold material only, whose outer vertices may then hang "
      "on coarser cells (and the grid changes whenever material enters a "
      "new cell).");
    prm.declare_entry(
      "Check interval", "10", Patterns::Integer(0),
      "Steps between two checks of the margin (and of cells to coarsen); "
      "0: only when a point enters a cell that is not at the finest "
      "level, which is checked at every step. A check costs 3 Margin "
      "exchanges of the nodes on the ranks' boundaries.");
    prm.leave_subsection();
  }



  template <int dim>
  GridAdaptation<dim>::GridAdaptation(ParameterHandler &         prm,
                                      Grid<dim> &                grid,
                                      const MaterialPoints<dim> &points,
                                      const Occupied &           reserved,
                                      ConditionalOStream &       pcout)
    : grid(grid)
    , points(points)
    , reserved(reserved)
    , pcout(pcout)
  {
    prm.enter_subsection("Adaptive grid");
    levels   = prm.get_integer("Refinement levels");
    margin   = prm.get_integer("Margin");
    interval = prm.get_integer("Check interval");
    prm.leave_subsection();
    finest_level = grid.base_level() + levels;
  }



  template <int dim>
  void
  GridAdaptation<dim>::refine_around(const Occupied &occupied)
  {
    if (!enabled())
      return;
    adapt(occupied, true);
    pcout << "mpm: adaptive grid, "
          << grid.get_triangulation().n_global_active_cells()
          << " cells at the start (the uniform grid of the finest cells "
          << "would have "
          << grid.get_triangulation().n_global_coarse_cells() *
               (1ull << (dim * finest_level))
          << ")" << std::endl;
  }



  template <int dim>
  bool
  GridAdaptation<dim>::check(const unsigned int step)
  {
    if (!enabled())
      return false;
    const Occupied holding_material = [this](const auto &cell) {
      return holds_points(cell) || reserved(cell);
    };
    bool point_in_coarse_cell = false;
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned() && cell->level() < finest_level &&
          holds_points(cell))
        {
          point_in_coarse_cell = true;
          break;
        }
    bool changed = false;
    if (Utilities::MPI::logical_or(point_in_coarse_cell,
                                   grid.get_communicator()))
      changed = adapt(holding_material, true);
    else if (interval > 0 && step % interval == 0)
      changed = adapt(holding_material, false);
    adaptations += changed;
    return changed;
  }



  template <int dim>
  bool
  GridAdaptation<dim>::adapt(const Occupied &occupied, bool refine)
  {
    const auto &   triangulation = grid.get_triangulation();
    const MPI_Comm communicator  = grid.get_communicator();
    bool           changed       = false;
    // A check refines once material has come within Margin rings of a
    // coarser cell; the rounds of a refinement, one level each, go on out
    // to 2 Margin rings.
    for (unsigned int round = 0;; ++round)
      {
        const std::vector<unsigned int> ring = rings(occupied, 2 * margin);
        const unsigned int reach = (refine || round > 0) ? 2 * margin : margin;
        bool coarse_nearby = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              ring[cell->active_cell_index()] <= reach &&
              cell->level() < finest_level)
            coarse_nearby = true;
        refine = Utilities::MPI::logical_or(coarse_nearby, communicator);
        if (!refine)
          break;
        changed |= grid.adapt([&](const auto &cell) {
          return ring[cell->active_cell_index()] <= 2 * margin &&
                     cell->level() < finest_level ?
                   1 :
                   0;
        });
      }

    // Cells beyond 3 Margin rings coarsen once they are a tenth of the
    // grid, then as far as they go: a change of the grid costs some steps,
    // and each bit of material that moves would otherwise free a family or
    // two of cells at every check.
    const int base = grid.base_level();
    for (unsigned int round = 0; round < levels; ++round)
      {
        const std::vector<unsigned int> ring = rings(occupied, 3 * margin);
        const auto coarsens = [&](const auto &cell) {
          return ring[cell->active_cell_index()] == beyond &&
                 cell->level() > base;
        };
        if (round == 0)
          {
            unsigned int n_candidates = 0;
            for (const auto &cell : triangulation.active_cell_iterators())
              if (cell->is_locally_owned() && coarsens(cell))
                ++n_candidates;
            if (Utilities::MPI::sum(n_candidates, communicator) <
                0.1 * triangulation.n_global_active_cells())
              break;
          }
        const auto n_cells = triangulation.n_global_active_cells();
        if (!grid.adapt(
              [&](const auto &cell) { return coarsens(cell) ? -1 : 0; }))
          break;
        changed = true;
        if (triangulation.n_global_active_cells() == n_cells)
          break;
      }
    return changed;
  }



  template <int dim>
  std::vector<unsigned int>
  GridAdaptation<dim>::rings(const Occupied &   occupied,
                             const unsigned int n_rings) const
  {
    const auto &triangulation = grid.get_triangulation();
    std::vector<unsigned int> ring(triangulation.n_active_cells(), beyond);
    // Per node: whether a cell of the last ring has it. Ranks share the
    // nodes on their boundary, so a ring crosses to the neighbour rank.
    LinearAlgebra::distributed::Vector<float> marked(grid.node_partitioner());
    std::vector<unsigned int> last_ring;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && occupied(cell))
        {
          ring[cell->active_cell_index()] = 0;
          last_ring.push_back(cell->active_cell_index());
        }
    for (unsigned int r = 1; r <= n_rings; ++r)
      {
        marked.zero_out_ghost_values();
        for (const unsigned int c : last_ring)
          for (unsigned int v = 0; v < Grid<dim>::n_vertices; ++v)
            marked.local_element(grid.node_of(c, v)) = 1.f;
        marked.compress(VectorOperation::max);
        marked.update_ghost_values();
        last_ring.clear();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              ring[cell->active_cell_index()] == beyond)
            for (unsigned int v = 0; v < Grid<dim>::n_vertices; ++v)
              if (marked.local_element(
                    grid.node_of(cell->active_cell_index(), v)) > 0.f)
                {
                  ring[cell->active_cell_index()] = r;
                  last_ring.push_back(cell->active_cell_index());
                  break;
                }
      }
    return ring;
  }



  template <int dim>
  template <class Archive>
  void
  GridAdaptation<dim>::save(Archive &archive, const unsigned int) const
  {
    std::vector<CellId::binary_type> cells;
    if (enabled())
      for (const auto &cell : grid.get_triangulation().active_cell_iterators())
        if (cell->is_locally_owned())
          cells.push_back(cell->id().template to_binary<dim>());
    archive << cells;
  }



  template <int dim>
  template <class Archive>
  void
  GridAdaptation<dim>::load(Archive &archive, const unsigned int)
  {
    std::vector<CellId::binary_type> own_cells;
    archive >> own_cells;
    const bool saved_adaptive =
      Utilities::MPI::logical_or(!own_cells.empty(), grid.get_communicator());
    if (saved_adaptive != enabled())
      throw InputError("--restart: the checkpoint was written " +
                       std::string(saved_adaptive ? "with" : "without") +
                       " an adaptive grid, and this scene's Adaptive "
                       "grid/Refinement levels says otherwise.");
    if (!saved_adaptive)
      return;
    // The saved cells, and every cell that is an ancestor of one.
    std::set<CellId> cells, ancestors;
    for (const auto &rank_cells :
         Utilities::MPI::all_gather(grid.get_communicator(), own_cells))
      for (const auto &binary : rank_cells)
        {
          const CellId id(binary);
          cells.insert(id);
          const auto path = id.get_child_indices();
          for (unsigned int n = 0; n < path.size(); ++n)
            ancestors.emplace(id.get_coarse_cell_id(), n, path.data());
        }
    // Each round changes the cells by one level at most.
    for (unsigned int round = 0; grid.adapt([&](const auto &cell) {
           if (cells.count(cell->id()) > 0)
             return 0;
           return ancestors.count(cell->id()) > 0 ? 1 : -1;
         });
         ++round)
      AssertThrow(static_cast<int>(round) < 2 * (finest_level + 1),
                  ExcInternalError());
  }



  template class GridAdaptation<2>;
  template class GridAdaptation<3>;

  template void
  GridAdaptation<2>::save(boost::archive::binary_oarchive &,
                          const unsigned int) const;
  template void
  GridAdaptation<3>::save(boost::archive::binary_oarchive &,
                          const unsigned int) const;
  template void
  GridAdaptation<2>::load(boost::archive::binary_iarchive &,
                          const unsigned int);
  template void
  GridAdaptation<3>::load(boost::archive::binary_iarchive &,
                          const unsigned int);
} // namespace mpm
