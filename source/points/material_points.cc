#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/base/input_error.h>
#include <mpm/points/material_points.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  std::vector<std::string>
  PointLayout<dim>::names(const unsigned int n_internal_variables)
  {
    std::vector<std::string> n(n_properties(n_internal_variables));
    n[mass]             = "mass";
    n[reference_volume] = "reference_volume";
    for (unsigned int d = 0; d < dim; ++d)
      n[reference_size + d] = "reference_size";
    for (unsigned int d = 0; d < dim; ++d)
      n[velocity + d] = "velocity";
    const char *axes = "xyz";
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        n[deformation_gradient + i * dim + j] =
          std::string("F_") + axes[i] + axes[j];
    if (dim == 2)
      n[out_of_plane_stretch] = "F_zz";
    const char *stress_names[6] = {
      "stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_xz",
      "stress_yz"};
    for (unsigned int k = 0; k < 6; ++k)
      n[stress + k] = stress_names[k];
    n[work_density] = "work_density";
    n[body_id]      = "body_id";
    n[material_id]  = "material_id";
    for (unsigned int k = 0; k < n_internal_variables; ++k)
      n[internal_variables + k] = "internal_" + std::to_string(k);
    return n;
  }



  template <int dim>
  MaterialPoints<dim>::MaterialPoints(
    const Grid<dim> &               grid,
    const std::vector<std::string> &internal_variable_names,
    const PointSlots &              slots,
    const bool                      far_moves)
    : grid(grid)
    , triangulation(grid.get_triangulation())
    , mapping(grid.get_mapping())
    , particle_handler(triangulation,
                       mapping,
                       Layout::n_properties(internal_variable_names.size()) +
                         slots.n_components_total())
    , cell_cache(triangulation, mapping)
    , internal_names(internal_variable_names)
    , slots(slots)
    , far_moves(far_moves)
  {
    particle_handler.signals.particle_lost.connect(
      [this](const typename Particles::ParticleIterator<dim> &particle,
             const typename Triangulation<dim>::active_cell_iterator &cell) {
        if (leaves_through_outflow(cell, particle->get_location()))
          {
            local_removed_mass += particle->get_properties()[Layout::mass];
            ++local_removed_points;
          }
        else
          lost_positions.push_back(particle->get_location());
      });
    // Carried into the refined cells by deal.II's transfer, before anything
    // else rebuilds on the new grid.
    before_grid_change = grid.before_change.connect([this]() {
      particle_handler.prepare_for_coarsening_and_refinement();
      grid_changing = true;
    });
    after_grid_change = grid.changed.connect(
      [this]() {
        if (!grid_changing)
          return;
        particle_handler.unpack_after_coarsening_and_refinement();
        particle_handler.update_cached_numbers();
        grid_changing = false;
      },
      boost::signals2::at_front);
  }



  template <int dim>
  std::vector<std::string>
  MaterialPoints<dim>::property_names() const
  {
    std::vector<std::string> names = Layout::names(n_internal_variables());
    std::copy(internal_names.begin(),
              internal_names.end(),
              names.begin() + Layout::internal_variables);
    for (const PointSlots::Slot &slot : slots.all())
      names.insert(names.end(), slot.n_components, slot.name);
    return names;
  }



  template <int dim>
  std::vector<unsigned int>
  MaterialPoints<dim>::vector_properties() const
  {
    std::vector<unsigned int> vectors = {Layout::reference_size,
                                         Layout::velocity};
    for (const PointSlots::Slot &slot : slots.all())
      if (slot.is_vector)
        vectors.push_back(slot_index(slot.name));
    return vectors;
  }



  template <int dim>
  void
  MaterialPoints<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("Outflow boundaries",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Named boundaries through which material leaves: a "
                      "point that crosses one is removed, and the time "
                      "series counts the removed mass and points "
                      "(removed_mass, removed_points). A boundary may be a "
                      "wall until some time and an outflow after it (a "
                      "silo's orifice). A point that leaves the grid "
                      "anywhere else stops the run.");
    prm.leave_subsection();
  }



  template <int dim>
  void
  MaterialPoints<dim>::parse_outflow(ParameterHandler &prm)
  {
    const std::string entry = "Boundary conditions/Outflow boundaries";
    prm.enter_subsection("Boundary conditions");
    const std::vector<std::string> names =
      Utilities::split_string_list(prm.get("Outflow boundaries"));
    prm.leave_subsection();
    const std::vector<types::boundary_id> present =
      triangulation.get_boundary_ids();
    for (const std::string &name : names)
      {
        const types::boundary_id id = grid.boundary_id(name, entry);
        if (std::find(present.begin(), present.end(), id) == present.end())
          throw InputError(entry + " names '" + name +
                           "', but no face of the grid has its boundary id " +
                           std::to_string(id) + ".");
        outflow_ids.push_back(id);
      }
  }



  template <int dim>
  bool
  MaterialPoints<dim>::leaves_through_outflow(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    const Point<dim> &                                       x) const
  {
    if (outflow_ids.empty())
      return false;
    for (const unsigned int f : cell->face_indices())
      if (cell->at_boundary(f) &&
          std::find(outflow_ids.begin(),
                    outflow_ids.end(),
                    cell->face(f)->boundary_id()) != outflow_ids.end())
        {
          // Beyond the face's plane, on the side away from the cell.
          if (Grid<dim>::face_normal(cell, f) * (x - cell->face(f)->center()) >
              0.)
            return true;
        }
    return false;
  }



  template <int dim>
  double
  MaterialPoints<dim>::removed_mass() const
  {
    return Utilities::MPI::sum(local_removed_mass, get_communicator());
  }



  template <int dim>
  types::particle_index
  MaterialPoints<dim>::removed_points() const
  {
    return Utilities::MPI::sum(local_removed_points, get_communicator());
  }



  template <int dim>
  template <class Archive>
  void
  MaterialPoints<dim>::save(Archive &archive, const unsigned int) const
  {
    const std::uint64_t n_points =
      particle_handler.n_locally_owned_particles();
    const unsigned int n_properties =
      particle_handler.n_properties_per_particle();
    archive << n_points << n_properties << local_removed_mass
            << local_removed_points;
    std::vector<double> properties(n_properties);
    for (auto particle = particle_handler.begin();
         particle != particle_handler.end();
         ++particle)
      {
        const auto cell = particle->get_surrounding_cell()
                            ->id()
                            .template to_binary<dim>();
        const types::particle_index   id = particle->get_id();
        const Point<dim>              x  = particle->get_location();
        const Point<dim>              X = particle->get_reference_location();
        const ArrayView<const double> p  = particle->get_properties();
        std::copy(p.begin(), p.end(), properties.begin());
        archive << cell << id << x << X << properties;
      }
  }



  template <int dim>
  template <class Archive>
  void
  MaterialPoints<dim>::load(Archive &archive, const unsigned int)
  {
    std::uint64_t n_points     = 0;
    unsigned int  n_properties = 0;
    archive >> n_points >> n_properties >> local_removed_mass >>
      local_removed_points;
    if (n_properties != particle_handler.n_properties_per_particle())
      throw InputError("--restart: the checkpoint's points carry " +
                       std::to_string(n_properties) +
                       " values each, this scene's " +
                       std::to_string(
                         particle_handler.n_properties_per_particle()) +
                       ": the materials or the scheme have changed.");
    particle_handler.clear_particles();
    CellId::binary_type               cell;
    types::particle_index             id;
    Point<dim>                        x, X;
    std::vector<double>               properties;
    for (std::uint64_t i = 0; i < n_points; ++i)
      {
        archive >> cell >> id >> x >> X >> properties;
        particle_handler.insert_particle(
          x,
          X,
          id,
          triangulation.create_cell_iterator(CellId(cell)),
          ArrayView<const double>(properties.data(), properties.size()));
      }
    particle_handler.update_cached_numbers();
  }



  template struct PointLayout<2>;
  template struct PointLayout<3>;
  template class MaterialPoints<2>;
  template class MaterialPoints<3>;

  template void
  MaterialPoints<2>::save(boost::archive::binary_oarchive &,
                          const unsigned int) const;
  template void
  MaterialPoints<3>::save(boost::archive::binary_oarchive &,
                          const unsigned int) const;
  template void
  MaterialPoints<2>::load(boost::archive::binary_iarchive &,
                          const unsigned int);
  template void
  MaterialPoints<3>::load(boost::archive::binary_iarchive &,
                          const unsigned int);
} // namespace mpm
