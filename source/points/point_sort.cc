#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/base/input_error.h>
#include <mpm/base/release_freed_memory.h>
#include <mpm/base/shared_position.h>
#include <mpm/points/material_points.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

// The sort of the material points into the cells (and ranks) they moved
// to: within a rank by a walk to the neighbouring cell, into a pool laid
// out again in cell order after enough moves, and across ranks through
// deal.II, with the points that moved far carried first.

namespace mpm
{
  template <int dim>
  void
  MaterialPoints<dim>::sort()
  {
    lost_positions.clear();
    const MPI_Comm              comm     = get_communicator();
    const types::particle_index n_before = Utilities::MPI::sum(
      particle_handler.n_locally_owned_particles(), comm);
    const types::particle_index removed_before = removed_points();
    if (far_moves)
      carry_far_points();
    if (!sort_within_rank())
      {
        particle_handler.sort_particles_into_subdomains_and_cells();
        moved_since_layout = 0;
        ++pool_layouts;
      }

    const unsigned int n_lost =
      Utilities::MPI::sum(static_cast<unsigned int>(lost_positions.size()),
                          comm);
    if (n_lost > 0)
      {
        Point<dim> first;
        if (!lost_positions.empty())
          first = *std::min_element(lost_positions.begin(),
                                    lost_positions.end(),
                                    lexicographically_less<dim>);
        const std::string where =
          shared_position(!lost_positions.empty(), first, comm);
        std::ostringstream message;
        message << n_lost << " material point(s) left the background grid, "
                << "the first at " << where;
        message << ". Make the grid cover every place the material can "
                   "reach, or fix the boundary there.";
        throw RunError(message.str());
      }
    // deal.II drops a point it sends towards an artificial cell without a
    // signal: every point must be accounted for.
    const types::particle_index n_after = Utilities::MPI::sum(
      particle_handler.n_locally_owned_particles(), comm);
    if (n_after + (removed_points() - removed_before) != n_before)
      throw RunError("Sorting the material points lost " +
                     std::to_string(n_before - n_after) +
                     " of them between ranks (an internal error).");
  }



  template <int dim>
  void
  MaterialPoints<dim>::make_room(const types::particle_index n_points)
  {
    // The pool itself: the handler's count of points is stale between
    // clear_particles() and the next update of its cached numbers.
    if (particle_handler.get_property_pool().n_registered_slots() == 0)
      particle_handler.reserve(n_points + 2 * moves_before_layout(n_points));
  }



  namespace
  {
    /**
     * Whether a reference location lies in the unit cell (deal.II's
     * mappings give infinity where they find none).
     */
    template <int dim>
    bool
    in_unit_cell(const Point<dim> &reference)
    {
      return reference[0] != std::numeric_limits<double>::infinity() &&
             GeometryInfo<dim>::is_inside_unit_cell(reference);
    }
  } // namespace



  template <int dim>
  bool
  MaterialPoints<dim>::sort_within_rank()
  {
    using particle_iterator =
      typename Particles::ParticleHandler<dim>::particle_iterator;
    // The reference location of every point as deal.II's sort finds it,
    // and the points outside their cells. The points are visited cell by
    // cell in the handler's order, so empty cells cost nothing; on a grid of
    // axis-aligned boxes the reference location is MappingCartesian's, in
    // its arithmetic (so to the bit), from the cell geometry the grid
    // keeps.
    const bool boxes =
      dynamic_cast<const MappingCartesian<dim> *>(&mapping) != nullptr;
    std::vector<particle_iterator> leavers;
    std::vector<Point<dim>>        leaver_references;
    std::vector<Point<dim>>        x, X;
    const auto classify = [&](particle_iterator &point,
                              const Point<dim> & reference) {
      if (!in_unit_cell(reference))
        {
          leavers.push_back(point);
          leaver_references.push_back(reference);
        }
      else
        point->set_reference_location(reference);
      ++point;
    };
    for (auto point = particle_handler.begin();
         point != particle_handler.end();)
      {
        const auto         cell = point->get_surrounding_cell();
        const unsigned int n    = particle_handler.n_particles_in_cell(cell);
        if (boxes)
          {
            const auto &nodes =
              grid.cell_geometry(cell->active_cell_index()).nodes;
            const Point<dim> &origin = grid.node_position(nodes[0]);
            Tensor<1, dim>    h;
            for (unsigned int d = 0; d < dim; ++d)
              h[d] = grid.node_position(nodes[1u << d])[d] - origin[d];
            for (unsigned int k = 0; k < n; ++k)
              {
                Point<dim> reference = point->get_location();
                for (unsigned int d = 0; d < dim; ++d)
                  reference[d] = (reference[d] - origin[d]) / h[d];
                classify(point, reference);
              }
            continue;
          }
        x.clear();
        for (auto p = point; x.size() < n; ++p)
          x.push_back(p->get_location());
        X.resize(n);
        mapping.transform_points_real_to_unit_cell(cell, x, X);
        for (const Point<dim> &reference : X)
          classify(point, reference);
      }

    std::vector<
      std::pair<typename Triangulation<dim>::active_cell_iterator, Point<dim>>>
      destinations;
    bool all_found = true;
    for (unsigned int k = 0; k < leavers.size() && all_found; ++k)
      {
        destinations.push_back(walk_to_cell(leavers[k]->get_surrounding_cell(),
                                            leaver_references[k],
                                            leavers[k]->get_location()));
        all_found = destinations.back().first.state() == IteratorState::valid;
      }
    moved_since_layout += leavers.size();
    const bool lay_out_again =
      moved_since_layout >
      moves_before_layout(particle_handler.n_locally_owned_particles());
    // One reduction for both collective decisions.
    const std::array<unsigned int, 2> local{{all_found ? 0u : 1u,
                                             lay_out_again ? 1u : 0u}};
    std::array<unsigned int, 2>       any;
    Utilities::MPI::max(ArrayView<const unsigned int>(local.data(), 2),
                        get_communicator(),
                        ArrayView<unsigned int>(any.data(), 2));
    if (any[0] != 0)
      return false;
    // Insert each point into its new cell, then remove it from its old one,
    // as deal.II does: the order of the points in every cell, and so of
    // every sum over them, is deal.II's. The copies take the free slots
    // first, then new ones: the room for them is made first, so that a
    // pool short of it grows by that, not by doubling (and a pool with
    // the room is not copied).
    const auto &pool = particle_handler.get_property_pool();
    particle_handler.reserve(
      std::max<std::size_t>(pool.n_slots(),
                            pool.n_registered_slots() + leavers.size()));
    std::vector<double> properties(
      particle_handler.n_properties_per_particle());
    for (unsigned int k = 0; k < leavers.size(); ++k)
      {
        const ArrayView<const double> p = leavers[k]->get_properties();
        std::copy(p.begin(), p.end(), properties.begin());
        particle_handler.insert_particle(leavers[k]->get_location(),
                                         destinations[k].second,
                                         leavers[k]->get_id(),
                                         destinations[k].first,
                                         properties);
      }
    // Also with no leavers here: it counts the points, with every rank.
    particle_handler.remove_particles(leavers);
    if (any[1] != 0)
      {
        if (lay_out_again)
          lay_out_pool();
        particle_handler.update_cached_numbers();
      }
    return true;
  }



  template <int dim>
  void
  MaterialPoints<dim>::lay_out_pool()
  {
    // Copy the points out in the handler's order and insert them back into
    // an empty pool, which then holds them in that order, as deal.II's sort
    // leaves it. That sort would also build the search structures of its
    // grid cache (a set of cells for every vertex), kept for the life of
    // the grid.
    {
      const unsigned int n_properties =
        particle_handler.n_properties_per_particle();
      const types::particle_index n =
        particle_handler.n_locally_owned_particles();
      std::vector<Point<dim>>            x, X;
      std::vector<types::particle_index> ids;
      std::vector<double>                properties;
      x.reserve(n);
      X.reserve(n);
      ids.reserve(n);
      properties.reserve(n * n_properties);
      std::vector<std::pair<typename Triangulation<dim>::active_cell_iterator,
                            types::particle_index>>
        cells;
      for (const auto &point : particle_handler)
        {
          const auto cell = point.get_surrounding_cell();
          if (cells.empty() || cells.back().first != cell)
            cells.emplace_back(cell, 0);
          ++cells.back().second;
          x.push_back(point.get_location());
          X.push_back(point.get_reference_location());
          ids.push_back(point.get_id());
          const ArrayView<const double> p = point.get_properties();
          properties.insert(properties.end(), p.begin(), p.end());
        }
      particle_handler.clear_particles();
      // The old pool's memory, before the new pool takes its place.
      release_freed_memory();
      make_room(n);
      types::particle_index k = 0;
      for (const auto &[cell, n_in_cell] : cells)
        for (types::particle_index i = 0; i < n_in_cell; ++i, ++k)
          particle_handler.insert_particle(
            x[k],
            X[k],
            ids[k],
            cell,
            ArrayView<const double>(properties.data() + k * n_properties,
                                    n_properties));
    }
    // The copy's memory.
    release_freed_memory();
    moved_since_layout = 0;
    ++pool_layouts;
  }



  template <int dim>
  std::pair<typename Triangulation<dim>::active_cell_iterator, Point<dim>>
  MaterialPoints<dim>::walk_to_cell(
    typename Triangulation<dim>::active_cell_iterator cell,
    Point<dim>                                        reference,
    const Point<dim> &                                x) const
  {
    const typename Triangulation<dim>::active_cell_iterator nowhere =
      triangulation.end();
    for (unsigned int hop = 0; hop < 2 * dim; ++hop)
      {
        // Across the face beyond which x lies furthest.
        if (reference[0] == std::numeric_limits<double>::infinity())
          return {nowhere, reference};
        unsigned int face   = numbers::invalid_unsigned_int;
        double       beyond = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (-reference[d] > beyond)
              {
                beyond = -reference[d];
                face   = 2 * d;
              }
            if (reference[d] - 1. > beyond)
              {
                beyond = reference[d] - 1.;
                face   = 2 * d + 1;
              }
          }
        if (face == numbers::invalid_unsigned_int || cell->at_boundary(face))
          return {nowhere, reference};
        typename Triangulation<dim>::cell_iterator next = cell->neighbor(face);
        // A finer neighbour: the child on x's side in each direction (the
        // children of a hypercube are numbered so), down to an active one.
        Point<dim>                        X_in[1];
        const ArrayView<const Point<dim>> x_view(&x, 1);
        const ArrayView<Point<dim>>       X_view(X_in, 1);
        while (next->has_children())
          {
            mapping.transform_points_real_to_unit_cell(next, x_view, X_view);
            if (X_in[0][0] == std::numeric_limits<double>::infinity())
              return {nowhere, reference};
            unsigned int child = 0;
            for (unsigned int d = 0; d < dim; ++d)
              if (X_in[0][d] >= 0.5)
                child |= 1u << d;
            next = next->child(child);
          }
        if (!next->is_locally_owned())
          return {nowhere, reference};
        cell = next;
        mapping.transform_points_real_to_unit_cell(cell, x_view, X_view);
        reference = X_in[0];
        if (in_unit_cell(reference))
          return {cell, reference};
      }
    return {nowhere, reference};
  }



  template <int dim>
  void
  MaterialPoints<dim>::carry_far_points()
  {
    // Each far point as [id, x, properties], from every rank to every rank:
    // such points are few (only large implicit steps make them).
    const double h = grid.minimum_cell_size();
    const unsigned int n_properties =
      particle_handler.n_properties_per_particle();
    const unsigned int record = 1 + dim + n_properties;
    std::vector<double> own;
    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      far;
    for (auto particle = particle_handler.begin();
         particle != particle_handler.end();
         ++particle)
      {
        const Point<dim> old = mapping.transform_unit_to_real_cell(
          particle->get_surrounding_cell(), particle->get_reference_location());
        const Point<dim> x = particle->get_location();
        bool             is_far = false;
        for (unsigned int d = 0; d < dim; ++d)
          is_far = is_far || std::abs(x[d] - old[d]) > h;
        if (!is_far)
          continue;
        far.push_back(particle);
        own.push_back(static_cast<double>(particle->get_id()));
        for (unsigned int d = 0; d < dim; ++d)
          own.push_back(x[d]);
        const ArrayView<const double> p = particle->get_properties();
        own.insert(own.end(), p.begin(), p.end());
      }
    const MPI_Comm comm = get_communicator();
    if (Utilities::MPI::sum(far.size(), comm) == 0)
      return;

    // Every rank claims the far points in its own cells; the lowest rank
    // that claims a point takes it.
    const std::vector<std::vector<double>> all =
      Utilities::MPI::all_gather(comm, own);
    const unsigned int this_rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_ranks   = Utilities::MPI::n_mpi_processes(comm);
    std::vector<unsigned int> claims;
    std::vector<std::pair<typename Triangulation<dim>::active_cell_iterator,
                          Point<dim>>>
      found;
    for (const auto &records : all)
      for (unsigned int r = 0; r < records.size(); r += record)
        {
          Point<dim> x;
          for (unsigned int d = 0; d < dim; ++d)
            x[d] = records[r + 1 + d];
          claims.push_back(n_ranks);
          found.emplace_back();
          // An invalid cell where no cell this rank sees holds x.
          found.back() = GridTools::find_active_cell_around_point(cell_cache, x);
          if (found.back().first.state() == IteratorState::valid &&
              found.back().first->is_locally_owned())
            claims.back() = this_rank;
        }
    std::vector<unsigned int> owners(claims.size());
    Utilities::MPI::min(ArrayView<const unsigned int>(claims),
                        comm,
                        ArrayView<unsigned int>(owners));

    // This rank's far points: the unclaimed ones have left the grid.
    unsigned int first = 0;
    for (unsigned int rank = 0; rank < this_rank; ++rank)
      first += all[rank].size() / record;
    for (unsigned int k = 0; k < far.size(); ++k)
      if (owners[first + k] == n_ranks)
        particle_handler.signals.particle_lost(far[k],
                                               far[k]->get_surrounding_cell());
    particle_handler.remove_particles(far);

    unsigned int k = 0;
    for (const auto &records : all)
      for (unsigned int r = 0; r < records.size(); r += record, ++k)
        if (owners[k] == this_rank)
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = records[r + 1 + d];
            particle_handler.insert_particle(
              x,
              found[k].second,
              static_cast<types::particle_index>(records[r]),
              found[k].first,
              ArrayView<const double>(&records[r + 1 + dim], n_properties));
          }
    particle_handler.update_cached_numbers();
  }



  // The class is instantiated in material_points.cc; the members of this
  // file here.
#define MPM_INSTANTIATE(dim)                                                \
  template void MaterialPoints<dim>::sort();                                \
  template void MaterialPoints<dim>::make_room(                             \
    const types::particle_index);                                           \
  template bool MaterialPoints<dim>::sort_within_rank();                    \
  template void MaterialPoints<dim>::lay_out_pool();                        \
  template std::pair<typename Triangulation<dim>::active_cell_iterator,     \
                     Point<dim>>                                            \
  MaterialPoints<dim>::walk_to_cell(                                        \
    typename Triangulation<dim>::active_cell_iterator,                      \
    Point<dim>,                                                             \
    const Point<dim> &) const;                                              \
  template void MaterialPoints<dim>::carry_far_points();

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace mpm
