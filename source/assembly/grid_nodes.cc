#include <deal.II/fe/fe_q.h>

#include <mpm/assembly/grid_nodes.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <map>

namespace mpm
{
  namespace
  {
    /** One slot's values on the wire, with the global index of its node. */
    template <unsigned int n_components>
    struct SlotRecord
    {
      types::global_dof_index node;
      unsigned int            field;
      double                  values[n_components];

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &node &field &values;
      }
    };
  } // namespace



  template <int dim>
  GridNodes<dim>::GridNodes(const Grid<dim> &grid, const unsigned int n_fields)
    : grid(grid)
    , n_field_count(n_fields)
    , system_element(FE_Q<dim>(1), NodalLayout::n_components)
  {
    AssertThrow(n_fields >= 1, ExcInternalError());
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  void
  GridNodes<dim>::setup()
  {
    // Value c of node i sits at n_components i + c: the grid's node
    // partition with each index widened to its components keeps the nodes'
    // order, owned and ghost. A DoFHandler of the FESystem would number
    // them so too, and cost as much memory as the points' positions.
    constexpr unsigned int n = NodalLayout::n_components;
    const Utilities::MPI::Partitioner &nodes = *grid.node_partitioner();
    IndexSet owned(n * nodes.size()), ghosts(n * nodes.size());
    for (auto range = nodes.locally_owned_range().begin_intervals();
         range != nodes.locally_owned_range().end_intervals();
         ++range)
      owned.add_range(n * *range->begin(), n * (range->last() + 1));
    std::vector<types::global_dof_index> ghost_values;
    ghost_values.reserve(n * nodes.n_ghost_indices());
    for (const auto g : nodes.ghost_indices())
      for (unsigned int c = 0; c < n; ++c)
        ghost_values.push_back(n * g + c);
    ghosts.add_indices(ghost_values.begin(), ghost_values.end());
    values.reinit(owned, ghosts, grid.get_communicator());
    combined_values.reinit(0);
    system_dof_handler.reset();

    n_grid_nodes = grid.n_nodes();
    active_flag.assign(n_grid_nodes, false);
    active_nodes.clear();
    solve_slots.clear();
    extra_slot_of.assign((n_field_count - 1) * n_grid_nodes, no_slot);
    extra_nodes.clear();
    extra_fields.clear();
    extra_values.clear();
    ghost_owner.clear();
    unsigned int ghost = nodes.locally_owned_size();
    ghost_owner.resize(ghost);
    for (const auto &[rank, count] : nodes.ghost_targets())
      ghost_owner.insert(ghost_owner.end(), count, rank);

    imported_in_order.clear();
    for (const auto &range : grid.node_partitioner()->import_indices())
      for (unsigned int i = range.first; i < range.second; ++i)
        imported_in_order.push_back(i);
    imported_nodes = imported_in_order;
    std::sort(imported_nodes.begin(), imported_nodes.end());
    imported_nodes.erase(std::unique(imported_nodes.begin(),
                                     imported_nodes.end()),
                         imported_nodes.end());
  }



  template <int dim>
  void
  GridNodes<dim>::begin_projection(const unsigned int first_component,
                                   const unsigned int n_components)
  {
    values.zero_out_ghost_values();
    for (const unsigned int node : active_nodes)
      {
        double *v = values_of(node);
        for (unsigned int c = first_component;
             c < first_component + n_components;
             ++c)
          v[c] = 0.;
      }
    for (const unsigned int node : imported_nodes)
      {
        double *v = values_of(node);
        for (unsigned int c = first_component;
             c < first_component + n_components;
             ++c)
          v[c] = 0.;
      }

    full_projection = (n_components == NodalLayout::n_components);
    if (full_projection)
      {
        for (const unsigned int node : active_nodes)
          active_flag[node] = false;
        active_nodes.clear();
        // The other fields' slots are made anew by each full projection.
        for (unsigned int s = 0; s < extra_nodes.size(); ++s)
          extra_slot_of[(extra_fields[s] - 1) * n_grid_nodes + extra_nodes[s]] =
            no_slot;
        extra_nodes.clear();
        extra_fields.clear();
        extra_values.clear();
      }
    else
      {
        // As for field 0: a ghost slot starts empty, so that what it sends
        // its owner is this rank's part alone.
        const unsigned int n_owned =
          grid.node_partitioner()->locally_owned_size();
        for (unsigned int s = 0; s < extra_nodes.size(); ++s)
          {
            double *v = extra_values.data() + s * NodalLayout::n_components;
            if (extra_nodes[s] >= n_owned)
              std::fill_n(v, NodalLayout::n_components, 0.);
            else
              std::fill_n(v + first_component, n_components, 0.);
          }
      }
  }



  template <int dim>
  unsigned int
  GridNodes<dim>::make_slot(const unsigned int node, const unsigned int field)
  {
    extra_nodes.push_back(node);
    extra_fields.push_back(field);
    extra_values.resize(extra_values.size() + NodalLayout::n_components, 0.);
    return n_grid_nodes + extra_nodes.size() - 1;
  }



  template <int dim>
  void
  GridNodes<dim>::finish_projection()
  {
    values.compress(VectorOperation::add);
    values.update_ghost_values();
    if (n_field_count > 1 &&
        Utilities::MPI::n_mpi_processes(grid.get_communicator()) > 1)
      exchange_extra_fields();

    // A partial projection fills the same slots as the full one before it.
    if (!full_projection)
      return;
    solve_slots = active_nodes;
    for (const unsigned int node : imported_nodes)
      if (!active_flag[node] && values_of(node)[NodalLayout::mass] > 0.)
        solve_slots.push_back(node);
    // A ghost node where this rank has another field's points but field 0
    // has mass only from other ranks: field 0 is solved there too, so that
    // the fields meet at the node on every rank that has it.
    const unsigned int n_owned = grid.node_partitioner()->locally_owned_size();
    for (unsigned int s = 0; s < extra_nodes.size(); ++s)
      {
        const unsigned int node = extra_nodes[s];
        if (node >= n_owned && !active_flag[node] &&
            values_of(node)[NodalLayout::mass] > 0.)
          {
            active_flag[node] = true;
            active_nodes.push_back(node);
            solve_slots.push_back(node);
          }
      }
    for (unsigned int s = n_grid_nodes; s < n_slots(); ++s)
      solve_slots.push_back(s);
  }



  template <int dim>
  void
  GridNodes<dim>::exchange_extra_fields()
  {
    using Record = SlotRecord<NodalLayout::n_components>;
    constexpr unsigned int             n = NodalLayout::n_components;
    const Utilities::MPI::Partitioner &partitioner = *grid.node_partitioner();
    const MPI_Comm                     comm        = grid.get_communicator();
    const unsigned int n_owned = partitioner.locally_owned_size();
    const auto         record  = [&](const unsigned int s) {
      Record r;
      r.node  = partitioner.local_to_global(extra_nodes[s]);
      r.field = extra_fields[s];
      std::copy_n(extra_values.data() + s * n, n, r.values);
      return r;
    };

    // Ghost slots' parts to their owners, which add them.
    std::map<unsigned int, std::vector<Record>> to_owners;
    for (unsigned int s = 0; s < extra_nodes.size(); ++s)
      if (extra_nodes[s] >= n_owned)
        {
          to_owners[ghost_owner[extra_nodes[s]]].push_back(record(s));
          std::fill_n(extra_values.data() + s * n, n, 0.);
        }
    for (const auto &[rank, records] :
         Utilities::MPI::some_to_some(comm, to_owners))
      for (const Record &r : records)
        {
          const unsigned int s = claim(partitioner.global_to_local(r.node),
                                       r.field);
          double *v = values_of(s);
          for (unsigned int c = 0; c < n; ++c)
            v[c] += r.values[c];
        }

    // The totals back to every rank that has the node as a ghost.
    std::map<unsigned int, std::vector<Record>> to_ghosts;
    auto next = imported_in_order.begin();
    for (const auto &[rank, count] : partitioner.import_targets())
      for (unsigned int i = 0; i < count; ++i)
        {
          const unsigned int node = *next++;
          for (unsigned int field = 1; field < n_field_count; ++field)
            {
              const unsigned int s = slot(node, field);
              if (s != no_slot)
                to_ghosts[rank].push_back(record(s - n_grid_nodes));
            }
        }
    for (const auto &[rank, records] :
         Utilities::MPI::some_to_some(comm, to_ghosts))
      for (const Record &r : records)
        std::copy_n(r.values,
                    n,
                    values_of(claim(partitioner.global_to_local(r.node),
                                    r.field)));
  }



  template <int dim>
  std::vector<unsigned int>
  GridNodes<dim>::shared_nodes() const
  {
    std::vector<unsigned int> shared;
    if (n_field_count == 1)
      return shared;
    std::vector<unsigned int> n_with_mass(n_grid_nodes, 0);
    for (const unsigned int s : solve_slots)
      if (values_of(s)[NodalLayout::mass] > 0. &&
          ++n_with_mass[node_of_slot(s)] == 2)
        shared.push_back(node_of_slot(s));
    return shared;
  }



  template <int dim>
  void
  GridNodes<dim>::combine_over_ranks(const std::vector<unsigned int> &nodes,
                                     std::vector<double> &            values,
                                     const unsigned int               width,
                                     const bool largest) const
  {
    const MPI_Comm comm = grid.get_communicator();
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      return;
    AssertThrow(values.size() == nodes.size() * width, ExcInternalError());
    const Utilities::MPI::Partitioner &partitioner = *grid.node_partitioner();
    const unsigned int n_owned = partitioner.locally_owned_size();
    std::map<unsigned int, unsigned int> entry_of;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      entry_of[nodes[k]] = k;
    // A record: the node's global index, then its values.
    const auto append = [&](std::vector<double> &out, const unsigned int k) {
      out.push_back(partitioner.local_to_global(nodes[k]));
      out.insert(out.end(),
                 values.begin() + k * width,
                 values.begin() + (k + 1) * width);
    };
    const auto for_each_record = [&](const std::vector<double> &in,
                                     const auto &               f) {
      for (std::size_t r = 0; r < in.size(); r += width + 1)
        {
          const auto found = entry_of.find(partitioner.global_to_local(
            static_cast<types::global_dof_index>(in[r])));
          if (found != entry_of.end())
            f(values.data() + found->second * width, in.data() + r + 1);
        }
    };

    std::map<unsigned int, std::vector<double>> to_owners;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (nodes[k] >= n_owned)
        append(to_owners[ghost_owner[nodes[k]]], k);
    for (const auto &[rank, records] :
         Utilities::MPI::some_to_some(comm, to_owners))
      for_each_record(records, [&](double *own, const double *part) {
        for (unsigned int c = 0; c < width; ++c)
          own[c] = largest ? std::max(own[c], part[c]) : own[c] + part[c];
      });

    std::map<unsigned int, std::vector<double>> to_ghosts;
    auto next = imported_in_order.begin();
    for (const auto &[rank, count] : partitioner.import_targets())
      for (unsigned int i = 0; i < count; ++i)
        {
          const auto found = entry_of.find(*next++);
          if (found != entry_of.end())
            append(to_ghosts[rank], found->second);
        }
    for (const auto &[rank, records] :
         Utilities::MPI::some_to_some(comm, to_ghosts))
      for_each_record(records, [&](double *own, const double *total) {
        std::copy_n(total, width, own);
      });
  }



  template <int dim>
  const DoFHandler<dim> &
  GridNodes<dim>::output_dof_handler() const
  {
    if (system_dof_handler)
      return *system_dof_handler;
    system_dof_handler =
      std::make_unique<DoFHandler<dim>>(grid.get_triangulation());
    system_dof_handler->distribute_dofs(system_element);
    for (const auto &cell : grid.node_numbering().active_cell_iterators())
      if (!cell->is_artificial())
        {
          const typename DoFHandler<dim>::active_cell_iterator system_cell(
            &grid.get_triangulation(),
            cell->level(),
            cell->index(),
            system_dof_handler.get());
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < NodalLayout::n_components; ++c)
              AssertThrow(system_cell->vertex_dof_index(v, c) ==
                            NodalLayout::n_components *
                                cell->vertex_dof_index(v, 0) +
                              c,
                          ExcInternalError());
        }
    return *system_dof_handler;
  }



  template <int dim>
  const LinearAlgebra::distributed::Vector<double> &
  GridNodes<dim>::output_vector() const
  {
    constexpr unsigned int n = NodalLayout::n_components;
    values.update_ghost_values();
    LinearAlgebra::distributed::Vector<double> *out = &values;
    if (n_field_count > 1)
      {
        combined_values.reinit(values, true);
        out = &combined_values;
        for (unsigned int node = 0; node < n_grid_nodes; ++node)
          combine_fields(node, combined_values.get_values() + n * node);
      }
    // No point reaches a hanging vertex, so the projection leaves it
    // empty; no step reads what is written here.
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto &geometry = grid.cell_geometry(cell->active_cell_index());
          if (geometry.n_hanging == 0)
            continue;
          for (const auto &entry : grid.hanging_vertices(geometry))
            std::fill_n(out->get_values() + n * geometry.nodes[entry.vertex],
                        n,
                        0.);
          for (const auto &entry : grid.hanging_vertices(geometry))
            {
              double *hanging =
                out->get_values() + n * geometry.nodes[entry.vertex];
              const double *master = out->get_values() + n * entry.master;
              for (unsigned int c = 0; c < n; ++c)
                hanging[c] += entry.weight * master[c];
            }
        }
    return *out;
  }



  template <int dim>
  void
  GridNodes<dim>::combine_fields(const unsigned int node, double *out) const
  {
    double mass = 0.;
    std::fill_n(out, NodalLayout::n_components, 0.);
    for (unsigned int field = 0; field < n_field_count; ++field)
      {
        const unsigned int s = slot(node, field);
        if (s == no_slot)
          continue;
        const double *v = values_of(s);
        mass += v[NodalLayout::mass];
        for (unsigned int c = 1; c < NodalLayout::n_components; ++c)
          out[c] += v[NodalLayout::mass] * v[c];
      }
    out[NodalLayout::mass] = mass;
    for (unsigned int c = 1; c < NodalLayout::n_components; ++c)
      out[c] = mass > 0. ? out[c] / mass : 0.;
  }



  template class GridNodes<2>;
  template class GridNodes<3>;
} // namespace mpm
