#include <deal.II/base/mpi.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/base/input_error.h>
#include <mpm/base/shape_parameters.h>
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
      "Steps between two checks of the margin (and of cells to coarsen, "
      "and of the material that gets Finer levels); "
      "0: only when a point enters a cell coarser than Refinement "
      "levels, which is checked at every step. A check costs 3 Margin "
      "exchanges of the nodes on the ranks' boundaries.");
    prm.declare_entry(
      "Finer levels", "0", Patterns::Integer(0, 10),
      "Levels beyond Refinement levels for the material that Finer where "
      "names, and its Margin rings; the rest of the material stays at "
      "Refinement levels. The explicit time step follows the finest "
      "cells, so it shrinks with them; bodies seeded into finer cells get "
      "more, smaller points.");
    prm.declare_entry(
      "Finer where", "", Patterns::MultipleSelection("region|plastic flow"),
      "Which material gets the Finer levels: 'region', the points that "
      "lie in the shape of the subsection Finer region; 'plastic flow', "
      "the points whose equivalent plastic strain grew faster than Finer "
      "plastic strain rate since the last check; or both, comma-separated. "
      "Both are found at the periodic checks (Check interval above 0).");
    prm.declare_entry(
      "Finer plastic strain rate", "1", Patterns::Double(0.),
      "(1/s) With Finer where = plastic flow: the rate of the equivalent "
      "plastic strain above which a point gets the Finer levels.");
    prm.enter_subsection("Finer region");
    ShapeParameters<dim>::declare_parameters(
      prm, "whose material gets the Finer levels (Finer where = region).");
    prm.leave_subsection();
    prm.leave_subsection();
  }



  template <int dim>
  void
  GridAdaptation<dim>::request_point_slots(ParameterHandler &prm,
                                           PointSlots &      slots)
  {
    prm.enter_subsection("Adaptive grid");
    const std::string where = prm.get("Finer where");
    const bool        rate  = where.find("plastic flow") != std::string::npos &&
                      prm.get_integer("Finer levels") > 0;
    prm.leave_subsection();
    if (rate)
      slots.request("plastic_strain_at_last_check", 1, false);
  }



  template <int dim>
  GridAdaptation<dim>::GridAdaptation(ParameterHandler &         prm,
                                      Grid<dim> &                grid,
                                      MaterialPoints<dim> &      points,
                                      const Occupied &           reserved,
                                      const std::vector<bool> &  plastic_law,
                                      ConditionalOStream &       pcout)
    : grid(grid)
    , points(points)
    , reserved(reserved)
    , plastic_law(plastic_law)
    , pcout(pcout)
  {
    prm.enter_subsection("Adaptive grid");
    levels   = prm.get_integer("Refinement levels");
    margin   = prm.get_integer("Margin");
    interval = prm.get_integer("Check interval");
    const unsigned int finer_levels = prm.get_integer("Finer levels");
    const std::string  where        = prm.get("Finer where");
    const bool by_region = where.find("region") != std::string::npos;
    const bool by_flow   = where.find("plastic flow") != std::string::npos;
    if ((finer_levels > 0) != (by_region || by_flow))
      throw InputError(finer_levels > 0 ?
                         "Adaptive grid/Finer levels > 0 needs Finer where "
                         "(region, plastic flow, or both)." :
                         "Adaptive grid/Finer where = " + where +
                           " needs Finer levels > 0.");
    if ((by_region || by_flow) && interval == 0)
      throw InputError("Adaptive grid/Finer where: the material that gets "
                       "the Finer levels is found at the periodic checks "
                       "(and the plastic strain rate measured between "
                       "them), so Check interval must be above 0.");
    if (by_region)
      {
        prm.enter_subsection("Finer region");
        Point<dim> center;
        finer_region = ShapeParameters<dim>::create(
          prm, "Adaptive grid/Finer region", center);
        prm.leave_subsection();
      }
    if (by_flow)
      {
        finer_plastic_strain_rate = prm.get_double("Finer plastic strain rate");
        if (!(finer_plastic_strain_rate > 0.))
          throw InputError("Adaptive grid/Finer plastic strain rate must be "
                           "positive with Finer where = plastic flow.");
        if (std::none_of(plastic_law.begin(),
                         plastic_law.end(),
                         [](const bool plastic) { return plastic; }))
          throw InputError("Adaptive grid/Finer where = plastic flow needs a "
                           "material whose law flows plastically (its "
                           "points carry a plastic_strain).");
      }
    prm.leave_subsection();
    material_level = grid.base_level() + levels;
    finest_level   = material_level + finer_levels;
  }



  template <int dim>
  void
  GridAdaptation<dim>::refine_around(const Occupied &occupied)
  {
    if (!enabled())
      return;
    // Before the points: the material near the Finer region gets the
    // finest cells, so that its points are seeded into them.
    const Occupied near_finer_region = [&](const auto &cell) {
      return finer_region && occupied(cell) && finer_region->reaches_cell(cell);
    };
    adapt(occupied, near_finer_region, true);
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
  GridAdaptation<dim>::check(const unsigned int step, const double time)
  {
    if (!enabled())
      return false;
    const Occupied holding_material = [this](const auto &cell) {
      return holds_points(cell) || reserved(cell);
    };
    // An inflow's region in the Finer region gets the finest cells before
    // its releases, as a body there does at the start.
    const Occupied finer = [this, time](const auto &cell) {
      if (finer_region && reserved(cell) && finer_region->reaches_cell(cell))
        return true;
      for (const auto &point : points.handler().particles_in_cell(cell))
        if (gets_finer_levels(point, time))
          return true;
      return false;
    };
    bool point_in_coarse_cell = false;
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned() && cell->level() < material_level &&
          holds_points(cell))
        {
          point_in_coarse_cell = true;
          break;
        }
    bool changed = false;
    if (Utilities::MPI::logical_or(point_in_coarse_cell,
                                   grid.get_communicator()))
      changed = adapt(holding_material, finer, true);
    else if (interval > 0 && step % interval == 0)
      changed = adapt(holding_material, finer, false);
    else
      return false;
    record_plastic_strain(time);
    adaptations += changed;
    return changed;
  }



  template <int dim>
  bool
  GridAdaptation<dim>::gets_finer_levels(
    const Particles::ParticleAccessor<dim> &point,
    const double                            time) const
  {
    if (finer_region && finer_region->contains(point.get_location()))
      return true;
    if (finer_plastic_strain_rate == 0. || !(time > last_record_time))
      return false;
    using Layout                    = PointLayout<dim>;
    const ArrayView<const double> p = point.get_properties();
    if (!plastic_law[static_cast<unsigned int>(p[Layout::material_id])])
      return false;
    const double growth =
      p[Layout::internal_variables] -
      p[points.slot_index("plastic_strain_at_last_check")];
    return growth > finer_plastic_strain_rate * (time - last_record_time);
  }



  template <int dim>
  void
  GridAdaptation<dim>::record_plastic_strain(const double time)
  {
    if (finer_plastic_strain_rate == 0.)
      return;
    using Layout = PointLayout<dim>;
    const unsigned int record =
      points.slot_index("plastic_strain_at_last_check");
    for (auto &point : points.handler())
      {
        const ArrayView<double> p = point.get_properties();
        if (plastic_law[static_cast<unsigned int>(p[Layout::material_id])])
          p[record] = p[Layout::internal_variables];
      }
    last_record_time = time;
  }



  template <int dim>
  bool
  GridAdaptation<dim>::adapt(const Occupied &occupied,
                             const Occupied &finer,
                             bool            refine)
  {
    const auto &   triangulation = grid.get_triangulation();
    const MPI_Comm communicator  = grid.get_communicator();
    bool           changed       = false;
    // A check refines once material has come within Margin rings of a
    // coarser cell than it needs; the rounds of a refinement, one level
    // each, go on out to 2 Margin rings.
    for (unsigned int round = 0;; ++round)
      {
        const Rings        ring  = rings(occupied, finer, 2 * margin);
        const unsigned int reach = (refine || round > 0) ? 2 * margin : margin;
        bool coarse_nearby = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              cell->level() <
                wanted_level(ring, cell->active_cell_index(), reach))
            coarse_nearby = true;
        refine = Utilities::MPI::logical_or(coarse_nearby, communicator);
        if (!refine)
          break;
        changed |= grid.adapt([&](const auto &cell) {
          return cell->level() <
                     wanted_level(ring, cell->active_cell_index(), 2 * margin) ?
                   1 :
                   0;
        });
      }

    // Cells beyond 3 Margin rings coarsen once they are a tenth of the
    // grid, then as far as they go: a change of the grid costs some steps,
    // and each bit of material that moves would otherwise free a family or
    // two of cells at every check.
    const int coarsest = grid.base_level();
    for (int round = coarsest; round < finest_level; ++round)
      {
        const Rings ring     = rings(occupied, finer, 3 * margin);
        const auto  coarsens = [&](const auto &cell) {
          return cell->level() >
                 wanted_level(ring, cell->active_cell_index(), 3 * margin);
        };
        if (round == coarsest)
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
  typename GridAdaptation<dim>::Rings
  GridAdaptation<dim>::rings(const Occupied &   occupied,
                             const Occupied &   finer,
                             const unsigned int n_rings) const
  {
    Rings result;
    result.material = rings(occupied, n_rings);
    if (finest_level > material_level)
      result.finer = rings(finer, n_rings);
    return result;
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
    // Written and read by the same scene (a continued run keeps the
    // Adaptive grid entries), so the checkpoints of other scenes keep
    // their layout.
    if (finer_plastic_strain_rate > 0.)
      archive << last_record_time;
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
    if (finer_plastic_strain_rate > 0.)
      archive >> last_record_time;
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
