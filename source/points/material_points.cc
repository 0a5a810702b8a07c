#include <deal.II/base/mpi.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/core/input_error.h>
#include <mpm/core/shared_position.h>
#include <mpm/points/material_points.h>

#include <algorithm>
#include <cmath>
#include <sstream>

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
    const parallel::distributed::Triangulation<dim> &tria,
    const Mapping<dim> &                             mapping,
    const std::vector<std::string> &                 internal_variable_names,
    const bool                                       implicit_fields)
    : triangulation(tria)
    , mapping(mapping)
    , particle_handler(tria,
                       mapping,
                       Layout::n_properties(internal_variable_names.size()) +
                         (implicit_fields ? 2 * dim : 0))
    , internal_names(internal_variable_names)
    , implicit_fields(implicit_fields)
  {
    particle_handler.signals.particle_lost.connect(
      [this](const typename Particles::ParticleIterator<dim> &particle,
             const typename Triangulation<dim>::active_cell_iterator &) {
        lost_positions.push_back(particle->get_location());
      });
  }



  template <int dim>
  std::vector<std::string>
  MaterialPoints<dim>::property_names() const
  {
    std::vector<std::string> names = Layout::names(n_internal_variables());
    std::copy(internal_names.begin(),
              internal_names.end(),
              names.begin() + Layout::internal_variables);
    if (implicit_fields)
      {
        for (unsigned int d = 0; d < dim; ++d)
          names.emplace_back("acceleration");
        for (unsigned int d = 0; d < dim; ++d)
          names.emplace_back("point_load");
      }
    return names;
  }



  template <int dim>
  std::vector<unsigned int>
  MaterialPoints<dim>::vector_properties() const
  {
    std::vector<unsigned int> vectors = {Layout::reference_size,
                                         Layout::velocity};
    if (implicit_fields)
      {
        vectors.push_back(acceleration_index());
        vectors.push_back(point_load_index());
      }
    return vectors;
  }



  template <int dim>
  void
  MaterialPoints<dim>::seed(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<std::unique_ptr<Material>> &materials,
    const GridBasis<dim> &                        basis)
  {
    struct Candidate
    {
      Point<dim>                                       x;
      Point<dim>                                       reference;
      typename Triangulation<dim>::active_cell_iterator cell;
      double                                           volume;
      Tensor<1, dim>                                   size;
      unsigned int                                     body;
    };
    std::vector<Candidate> candidates;

    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            const Quadrature<dim> &placement = bodies[b].point_placement();
            for (unsigned int k = 0; k < placement.size(); ++k)
              {
                const Point<dim> &reference = placement.point(k);
                const Point<dim>  x =
                  mapping.transform_unit_to_real_cell(cell, reference);
                if (!bodies[b].contains(x))
                  continue;
                bool owned_by_earlier_body = false;
                for (unsigned int e = 0; e < b; ++e)
                  if (bodies[e].contains(x))
                    owned_by_earlier_body = true;
                if (owned_by_earlier_body)
                  continue;
                const double volume =
                  basis.volume_factor(cell->active_cell_index(), reference) *
                  placement.weight(k);
                // The cell's extent times the 1D weight in each direction,
                // scaled so that the edges multiply to the volume (exact on
                // a Cartesian cell).
                Tensor<1, dim> size;
                double         box = 1.;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    size[d] = cell->extent_in_direction(d) *
                              bodies[b].placement_weight_1d(k, d);
                    box *= size[d];
                  }
                size *= std::pow(volume / box, 1. / dim);
                candidates.push_back({x, reference, cell, volume, size, b});
              }
          }
      }

    const MPI_Comm comm = get_communicator();
    const std::uint64_t n_local  = candidates.size();
    std::uint64_t       first_id = 0;
    MPI_Exscan(&n_local, &first_id, 1, MPI_UINT64_T, MPI_SUM, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first_id = 0; // MPI_Exscan leaves rank 0's result undefined

    std::vector<double> properties(particle_handler.n_properties_per_particle(),
                                   0.);
    for (unsigned int i = 0; i < candidates.size(); ++i)
      {
        const Candidate &c        = candidates[i];
        const Material & material = *materials[bodies[c.body].material_index()];
        std::fill(properties.begin(), properties.end(), 0.);
        properties[Layout::mass]             = material.density() * c.volume;
        properties[Layout::reference_volume] = c.volume;
        for (unsigned int d = 0; d < dim; ++d)
          properties[Layout::reference_size + d] = c.size[d];
        const Tensor<1, dim> v               = bodies[c.body].initial_velocity(c.x);
        for (unsigned int d = 0; d < dim; ++d)
          {
            properties[Layout::velocity + d] = v[d];
            properties[Layout::deformation_gradient + d * dim + d] = 1.;
          }
        properties[Layout::body_id]     = c.body;
        properties[Layout::material_id] = bodies[c.body].material_index();
        Layout::set_stress(ArrayView<double>(properties.data(),
                                             properties.size()),
                           material.reference_stress());
        particle_handler.insert_particle(
          c.x,
          c.reference,
          first_id + i,
          c.cell,
          ArrayView<const double>(properties.data(), properties.size()));
      }
    particle_handler.update_cached_numbers();
  }



  template <int dim>
  void
  MaterialPoints<dim>::apply_geostatic_stress(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Tensor<1, dim> &                        gravity)
  {
    bool any = false;
    for (const Body<dim> &body : bodies)
      any = any || body.geostatic();
    if (!any)
      return;
    if (gravity.norm() == 0.)
      throw InputError("Bodies: Initial stress = geostatic needs a non-zero "
                       "Gravity.");
    const Tensor<1, dim> down = gravity / gravity.norm();

    // The top of each body: the largest height -down.x, plus half the
    // point's extent along gravity.
    std::vector<double> top(bodies.size(),
                            -std::numeric_limits<double>::max());
    for (const auto &particle : particle_handler)
      {
        const ArrayView<const double> p = particle.get_properties();
        double                        half_extent = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          half_extent += 0.5 * std::abs(down[d]) * p[Layout::reference_size + d];
        double &body_top = top[static_cast<unsigned int>(p[Layout::body_id])];
        body_top =
          std::max(body_top, -(down * particle.get_location()) + half_extent);
      }
    Utilities::MPI::max(top, get_communicator(), top);

    Tensor<1, 3> down_3d;
    for (unsigned int d = 0; d < dim; ++d)
      down_3d[d] = down[d];
    const SymmetricTensor<2, 3> vertical =
      symmetrize(outer_product(down_3d, down_3d));
    // A law can refuse the stress on one rank only: collect, then throw on
    // every rank.
    std::string refusal;
    for (auto &particle : particle_handler)
      {
        const ArrayView<double> p    = particle.get_properties();
        const unsigned int      body = static_cast<unsigned int>(p[Layout::body_id]);
        if (!bodies[body].geostatic() || !refusal.empty())
          continue;
        const Material &material =
          *materials[static_cast<unsigned int>(p[Layout::material_id])];
        const double depth = top[body] + down * particle.get_location();
        const double sigma_v = -material.density() * gravity.norm() * depth;
        const SymmetricTensor<2, 3> stress =
          bodies[body].k0() * sigma_v * (unit_symmetric_tensor<3>() - vertical) +
          sigma_v * vertical;
        Layout::set_stress(p, stress);
        try
          {
            p[Layout::work_density] = material.initialize_stress(
              stress,
              ArrayView<double>(&p[Layout::internal_variables],
                                material.n_internal_variables()),
              "Bodies/" + bodies[body].name() + "/Initial stress = geostatic");
          }
        catch (const std::exception &error)
          {
            refusal = error.what();
          }
      }
    throw_input_error_on_every_rank(refusal, get_communicator());
  }



  template <int dim>
  void
  MaterialPoints<dim>::sort()
  {
    lost_positions.clear();
    particle_handler.sort_particles_into_subdomains_and_cells();

    const MPI_Comm comm = get_communicator();
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
    archive << n_points << n_properties;
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
    archive >> n_points >> n_properties;
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
