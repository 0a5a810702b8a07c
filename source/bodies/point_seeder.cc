#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>

#include <mpm/bodies/point_seeder.h>
#include <mpm/base/input_error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace mpm
{
  template <int dim>
  PointSeeder<dim>::PointSeeder(const Grid<dim> &grid)
    : grid(grid)
    , basis(grid)
  {}



  template <int dim>
  bool
  PointSeeder<dim>::release_due(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<std::unique_ptr<Material>> &materials,
    MaterialPoints<dim> &                         points,
    const double                                  time,
    const double                                  tolerance)
  {
    releases_done.resize(bodies.size(), 0);
    std::vector<unsigned int> due;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (releases_done[b] < bodies[b].releases() &&
          bodies[b].release_time(releases_done[b]) <= time + tolerance)
        due.push_back(b);
    if (due.empty())
      return false;
    seed(bodies, due, materials, points, time);
    for (const unsigned int b : due)
      ++releases_done[b];
    return true;
  }



  template <int dim>
  void
  PointSeeder<dim>::check_bodies(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<std::unique_ptr<Material>> &materials) const
  {
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const Material &material = *materials[bodies[b].material_index()];
        if (bodies[b].density() > 0. && !material.stress_follows_density())
          throw InputError("Bodies/" + bodies[b].name() +
                           "/Density: the stress of material '" +
                           material.name() +
                           "' does not follow the density, so its points "
                           "must have the material's Density (Density = "
                           "0).");
        if (!bodies[b].is_inflow())
          continue;
        const std::uint64_t n = count_candidates(bodies, {b});
        if (Utilities::MPI::sum(n, grid.get_communicator()) == 0)
          throw InputError("Bodies/" + bodies[b].name() +
                           ": the region of this inflow holds no point "
                           "placement of a grid cell, so its releases would "
                           "put no point into the grid.");
      }
  }



  template <int dim>
  void
  PointSeeder<dim>::seed(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<unsigned int> &             which,
    const std::vector<std::unique_ptr<Material>> &materials,
    MaterialPoints<dim> &                         points,
    const double                                  time)
  {
    using Layout = PointLayout<dim>;
    auto &handler = points.handler();
    // Bodies seeded together at the start may share cells; a later release
    // goes into empty ones.
    // The candidates are gathered once: a body on its own mesh would
    // otherwise be meshed twice, to count its points and to insert them.
    bool                   occupied = false;
    std::vector<Candidate> candidates;
    for_each_candidate(bodies,
                       which,
                       time > 0. ? &handler : nullptr,
                       occupied,
                       [&candidates](const Candidate &c) {
                         candidates.push_back(c);
                       });
    const std::uint64_t n_local = candidates.size();

    const MPI_Comm comm = grid.get_communicator();
    if (Utilities::MPI::logical_or(occupied, comm))
      {
        std::ostringstream message;
        message << "Bodies: a release of " << body_names(bodies, which)
                << " is due at t = " << time
                << ", but material still lies in the cells of its region. "
                   "Release less often (Release interval), or move the "
                   "region away from where the material gathers.";
        throw InputError(message.str());
      }
    std::uint64_t first_id = 0;
    MPI_Exscan(&n_local, &first_id, 1, MPI_UINT64_T, MPI_SUM, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first_id = 0; // MPI_Exscan leaves rank 0's result undefined
    first_id += next_id;
    next_id += Utilities::MPI::sum(n_local, comm);

    points.make_room(n_local);
    std::vector<double> properties(handler.n_properties_per_particle(), 0.);
    types::particle_index id = first_id;
    const auto insert = [&](const Candidate &c) {
      const Material & material = *materials[bodies[c.body].material_index()];
      std::fill(properties.begin(), properties.end(), 0.);
      const double density = bodies[c.body].density() > 0. ?
                               bodies[c.body].density() :
                               material.density();
      // An axisymmetric point is the ring its area sweeps: 2 pi x times
      // the area (Pappus), exact for a box centred at the point.
      const double volume =
        c.volume * grid.geometry().out_of_plane_measure(c.x);
      properties[Layout::mass]             = density * volume;
      properties[Layout::reference_volume] = volume;
      for (unsigned int d = 0; d < dim; ++d)
        properties[Layout::reference_size + d] = c.size[d];
      const Tensor<1, dim> v = bodies[c.body].initial_velocity(c.x);
      for (unsigned int d = 0; d < dim; ++d)
        {
          properties[Layout::velocity + d] = v[d];
          properties[Layout::deformation_gradient + d * dim + d] = 1.;
        }
      if (dim == 2)
        properties[Layout::out_of_plane_stretch] = 1.;
      properties[Layout::body_id]     = c.body;
      properties[Layout::material_id] = bodies[c.body].material_index();
      const ArrayView<double> p(properties.data(), properties.size());
      Layout::set_stress(
        p,
        material.seeded_state(
          density,
          ArrayView<double>(&p[Layout::internal_variables],
                            material.n_internal_variables())));
      handler.insert_particle(
        c.x,
        c.reference,
        id++,
        c.cell,
        ArrayView<const double>(properties.data(), properties.size()));
    };
    for (const Candidate &c : candidates)
      insert(c);
    handler.update_cached_numbers();
  }



  template <int dim>
  std::uint64_t
  PointSeeder<dim>::count_candidates(
    const std::vector<Body<dim>> &   bodies,
    const std::vector<unsigned int> &which) const
  {
    std::uint64_t n      = 0;
    bool          unused = false;
    for_each_candidate(bodies, which, nullptr, unused,
                       [&n](const Candidate &) { ++n; });
    return n;
  }



  template <int dim>
  void
  PointSeeder<dim>::for_each_candidate(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<unsigned int> &             which,
    const Particles::ParticleHandler<dim> *       present,
    bool &                                        occupied,
    const std::function<void(const Candidate &)> &visit) const
  {
    const Mapping<dim> &mapping = grid.get_mapping();
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int b : which)
          {
            if (bodies[b].placed_on_own_mesh())
              continue;
            const Quadrature<dim> &placement = bodies[b].point_placement();
            for (unsigned int k = 0; k < placement.size(); ++k)
              {
                const Point<dim> &reference = placement.point(k);
                const Point<dim>  x =
                  mapping.transform_unit_to_real_cell(cell, reference);
                if (!bodies[b].contains(x) || claimed_earlier(bodies, which, b, x))
                  continue;
                if (present != nullptr && present->n_particles_in_cell(cell) > 0)
                  occupied = true;
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
                visit({x, reference, cell, volume, size, b});
              }
          }
      }
    for (const unsigned int b : which)
      if (bodies[b].placed_on_own_mesh())
        for_each_own_mesh_candidate(bodies, which, b, present, occupied, visit);
  }



  template <int dim>
  void
  PointSeeder<dim>::for_each_own_mesh_candidate(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<unsigned int> &             which,
    const unsigned int                            b,
    const Particles::ParticleHandler<dim> *       present,
    bool &                                        occupied,
    const std::function<void(const Candidate &)> &visit) const
  {
    // Every rank meshes the whole body, the same way, and finds which of
    // the points lie in its own cells.
    Triangulation<dim> mesh;
    try
      {
        bodies[b].region().fill_mesh(mesh, grid.minimum_cell_size());
      }
    catch (const InputError &error)
      {
        throw InputError("Bodies/" + bodies[b].name() + "/" + error.what());
      }
    // A cubic mapping that follows the manifolds: the volumes add up to the
    // curved body's, not to its polygon's.
    const MappingQ<dim>    body_mapping(3);
    const FE_Q<dim>        fe(1);
    const Quadrature<dim> &placement = bodies[b].point_placement();
    FEValues<dim>          values(body_mapping,
                         fe,
                         placement,
                         update_quadrature_points | update_JxW_values);
    std::vector<Point<dim>> positions;
    std::vector<double>     volumes;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        values.reinit(cell);
        for (unsigned int k = 0; k < placement.size(); ++k)
          {
            positions.push_back(values.quadrature_point(k));
            volumes.push_back(values.JxW(k));
          }
      }

    // Each rank keeps the points it finds in its own cells. A point on a
    // face between cells (a box whose points fall on grid lines) could be
    // found in a different cell by each rank, which searches its own
    // ghost and artificial cells too: seeded twice or not at all. Every
    // rank looks for each point a tiny, uneven shift away instead, a
    // billionth of a cell, beyond the search's tolerance, which lies
    // inside one cell only.
    const double            shift = 1e-9 * grid.minimum_cell_size();
    std::vector<Point<dim>> shifted(positions);
    for (Point<dim> &x : shifted)
      for (unsigned int d = 0; d < dim; ++d)
        x[d] += shift * (1. + 0.1 * d);
    const GridTools::Cache<dim> cache(grid.get_triangulation(),
                                      grid.get_mapping());
    const auto located =
      GridTools::compute_point_locations_try_all(cache, shifted);
    const auto &cells      = std::get<0>(located);
    const auto &references = std::get<1>(located);
    const auto &indices    = std::get<2>(located);
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        if (!cells[c]->is_locally_owned())
          continue;
        for (unsigned int q = 0; q < indices[c].size(); ++q)
          {
            const unsigned int i = indices[c][q];
            const Point<dim>  &x = positions[i];
            if (claimed_earlier(bodies, which, b, x))
              continue;
            if (present != nullptr && present->n_particles_in_cell(cells[c]) > 0)
              occupied = true;
            // The point's domain: a cube of its volume.
            Tensor<1, dim> size;
            for (unsigned int d = 0; d < dim; ++d)
              size[d] = std::pow(volumes[i], 1. / dim);
            // Found a billionth of a cell away: clamped into the cell.
            Point<dim> reference = references[c][q];
            for (unsigned int d = 0; d < dim; ++d)
              reference[d] = std::clamp(reference[d], 0., 1.);
            visit({x, reference, cells[c], volumes[i], size, b});
          }
      }
  }



  template <int dim>
  bool
  PointSeeder<dim>::claimed_earlier(const std::vector<Body<dim>> &   bodies,
                                    const std::vector<unsigned int> &which,
                                    const unsigned int               b,
                                    const Point<dim> &               x)
  {
    for (const unsigned int e : which)
      if (e < b && bodies[e].contains(x))
        return true;
    return false;
  }



  template <int dim>
  double
  PointSeeder<dim>::next_release_time(const std::vector<Body<dim>> &bodies) const
  {
    double next = std::numeric_limits<double>::infinity();
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (b < releases_done.size() && releases_done[b] < bodies[b].releases())
        next = std::min(next, bodies[b].release_time(releases_done[b]));
    return next;
  }



  template <int dim>
  std::string
  PointSeeder<dim>::body_names(const std::vector<Body<dim>> &   bodies,
                               const std::vector<unsigned int> &which)
  {
    std::vector<std::string> names;
    for (const unsigned int b : which)
      names.push_back("'" + bodies[b].name() + "'");
    return comma_separated(names);
  }



  template <int dim>
  void
  PointSeeder<dim>::apply_geostatic_stress(
    const std::vector<Body<dim>> &                bodies,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Tensor<1, dim> &                        gravity,
    MaterialPoints<dim> &                         points) const
  {
    using Layout = PointLayout<dim>;
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
    for (const auto &particle : points.handler())
      {
        const ArrayView<const double> p = particle.get_properties();
        double                        half_extent = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          half_extent +=
            0.5 * std::abs(down[d]) * p[Layout::reference_size + d];
        double &body_top = top[static_cast<unsigned int>(p[Layout::body_id])];
        body_top =
          std::max(body_top, -(down * particle.get_location()) + half_extent);
      }
    Utilities::MPI::max(top, points.get_communicator(), top);

    Tensor<1, 3> down_3d;
    for (unsigned int d = 0; d < dim; ++d)
      down_3d[d] = down[d];
    const SymmetricTensor<2, 3> vertical =
      symmetrize(outer_product(down_3d, down_3d));
    // A law can refuse the stress on one rank only: collect, then throw on
    // every rank.
    std::string refusal;
    for (auto &particle : points.handler())
      {
        const ArrayView<double> p    = particle.get_properties();
        const unsigned int body =
          static_cast<unsigned int>(p[Layout::body_id]);
        if (!bodies[body].geostatic() || !refusal.empty())
          continue;
        const Material &material =
          *materials[static_cast<unsigned int>(p[Layout::material_id])];
        const double depth = top[body] + down * particle.get_location();
        const double sigma_v = -material.density() * gravity.norm() * depth;
        SymmetricTensor<2, 3> stress =
          bodies[body].k0() * sigma_v *
            (unit_symmetric_tensor<3>() - vertical) +
          sigma_v * vertical;
        // A plate's faces are free.
        if (points.get_grid().geometry().free_faces())
          stress[2][2] = 0.;
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
    throw_input_error_on_every_rank(refusal, points.get_communicator());
  }



  template class PointSeeder<2>;
  template class PointSeeder<3>;
} // namespace mpm
