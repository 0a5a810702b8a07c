#include <mpm/assembly/nodal_density.h>

namespace mpm
{
  template <int dim>
  NodalDensity<dim>::NodalDensity(const Grid<dim> &     grid,
                                  const GridBasis<dim> &basis)
    : grid(grid)
    , basis(basis)
  {}



  template <int dim>
  void
  NodalDensity<dim>::begin_projection()
  {
    // The grid may have changed since the last step.
    if (plane_mass.get_partitioner() != grid.node_partitioner())
      plane_mass.reinit(grid.node_partitioner());
    else
      plane_mass = 0.;
  }



  template <int dim>
  void
  NodalDensity<dim>::finish_projection(
    const Particles::ParticleHandler<dim> &handler)
  {
    // The grid may have changed since the last step.
    if (occupied_volume.get_partitioner() != grid.node_partitioner())
      occupied_volume.reinit(grid.node_partitioner());
    else
      occupied_volume = 0.;
    Support<dim> volumes;
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned() && handler.n_particles_in_cell(cell) > 0)
        {
          basis.cell_integrals(cell->active_cell_index(), volumes);
          for (unsigned int i = 0; i < volumes.n_nodes; ++i)
            occupied_volume.local_element(volumes.nodes[i]) += volumes.N[i];
        }
    occupied_volume.compress(VectorOperation::add);
    occupied_volume.update_ghost_values();

    plane_mass.compress(VectorOperation::add);
    plane_mass.update_ghost_values();
  }



  template class NodalDensity<2>;
  template class NodalDensity<3>;

  MPM_REGISTER_GRID_FIELD(NodalDensity, "Density from positions")
} // namespace mpm
