#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/output/time_series.h>

#include <filesystem>
#include <iomanip>
#include <limits>

namespace mpm
{
  template <int dim>
  void
  TimeSeries<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Time series file", "time_series.csv",
                      Patterns::Anything(),
                      "CSV file (in the output directory) with time, "
                      "energies, momentum, mass, centre of mass, the "
                      "material's extent and volume, tracked points and "
                      "the forces on walls and obstacles.");
    prm.declare_entry("Time series interval", "0", Patterns::Double(0.),
                      "Simulated time between rows of the time series; 0 "
                      "writes every step.");
    prm.declare_entry("Tracked points", "", Patterns::Anything(),
                      "Positions, ';'-separated; the material point nearest "
                      "to each at the start is followed in the time series: "
                      "its position, velocity, stress and the diagonal of "
                      "F, with F_zz the thickness ratio h / h_0 in plane "
                      "stress and the hoop stretch in axisymmetry.");
    prm.leave_subsection();
  }



  template <int dim>
  TimeSeries<dim>::TimeSeries(
    ParameterHandler &                              prm,
    const std::string &                             directory,
    const Tensor<1, dim> &                          gravity,
    const MaterialPoints<dim> &                     points,
    const std::vector<const ForceReport *> &        reports,
    const bool                                      continued)
    : gravity(gravity)
    , communicator(points.get_communicator())
    , reports(reports)
  {
    prm.enter_subsection("Output");
    filename     = directory + "/" + prm.get("Time series file");
    row_interval = prm.get_double("Time series interval");
    const std::vector<Point<dim>> tracked_positions =
      parse_point_list<dim>(prm.get("Tracked points"), "Output/Tracked points");
    prm.leave_subsection();

    if (!tracked_positions.empty() && points.n_global_points() == 0)
      throw InputError("Output/Tracked points: no material point is in the "
                       "grid at the start (an inflow releases its first "
                       "points later), so there is none to track.");
    // The tracked point is the nearest one; ties go to the smaller id.
    for (const Point<dim> &target : tracked_positions)
      {
        std::pair<double, types::particle_index> best(
          std::numeric_limits<double>::max(),
          std::numeric_limits<types::particle_index>::max());
        for (const auto &particle : points.handler())
          best = std::min(best,
                          std::make_pair(particle.get_location().distance(target),
                                         particle.get_id()));
        const double distance = Utilities::MPI::min(best.first, communicator);
        const types::particle_index id = Utilities::MPI::min(
          best.first == distance ?
            best.second :
            std::numeric_limits<types::particle_index>::max(),
          communicator);
        tracked_ids.push_back(id);
      }

    if (continued)
      return;
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    if (is_root)
      file.open(filename);
    if (Utilities::MPI::logical_or(is_root && !file, communicator))
      throw InputError("Output/Time series file: cannot write '" + filename +
                       "'.");
    if (is_root)
      {
        const char *axes = "xyz";
        file << "time,step,dt,kinetic_energy,strain_energy,"
                "gravitational_energy,total_energy";
        for (unsigned int d = 0; d < dim; ++d)
          file << ",momentum_" << axes[d];
        file << ",mass";
        for (unsigned int d = 0; d < dim; ++d)
          file << ",centre_of_mass_" << axes[d];
        file << ",points,max_speed";
        for (unsigned int d = 0; d < dim; ++d)
          file << ",min_" << axes[d] << ",max_" << axes[d];
        file << ",volume";
        for (unsigned int k = 0; k < tracked_ids.size(); ++k)
          {
            for (unsigned int d = 0; d < dim; ++d)
              file << ",point" << k << "_" << axes[d];
            for (unsigned int d = 0; d < dim; ++d)
              file << ",point" << k << "_v" << axes[d];
            for (const auto &[i, j] : tracked_stress_components())
              file << ",point" << k << "_stress_" << axes[i] << axes[j];
            for (unsigned int d = 0; d < 3; ++d)
              file << ",point" << k << "_F_" << axes[d] << axes[d];
          }
        if (points.has_outflow())
          file << ",removed_mass,removed_points";
        for (const ForceReport *report : reports)
          for (const std::string &name : report->force_names())
            file << ',' << name;
        file << '\n';
        file << std::setprecision(12);
      }
  }



  template <int dim>
  void
  TimeSeries<dim>::continue_file(const std::uint64_t length)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(communicator) == 0;
    bool       ok      = true;
    if (is_root)
      {
        std::error_code error;
        const auto      size = std::filesystem::file_size(filename, error);
        if (!error && size >= length)
          std::filesystem::resize_file(filename, length, error);
        if (!error && size >= length)
          file.open(filename, std::ios::app);
        file << std::setprecision(12);
        ok = file.is_open() && file.good();
      }
    if (Utilities::MPI::logical_or(!ok, communicator))
      throw InputError("--restart: the time series '" + filename +
                       "' is missing, shorter than at the checkpoint, or "
                       "cannot be written.");
  }



  template <int dim>
  std::vector<std::pair<unsigned int, unsigned int>>
  TimeSeries<dim>::tracked_stress_components()
  {
    // In 2D sigma_xz = sigma_yz = 0.
    if (dim == 2)
      return {{0, 0}, {1, 1}, {2, 2}, {0, 1}};
    return {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  }



  template <int dim>
  Diagnostics<dim>
  TimeSeries<dim>::write_row(const double               time,
                             const unsigned int         step,
                             const double               dt,
                             const MaterialPoints<dim> &points)
  {
    using Layout = PointLayout<dim>;
    // Layout of the reduced buffer: 4 scalars, momentum, first moment of
    // mass, volume, then per tracked point (only its owner adds them) its
    // position, velocity, stress and the diagonal of its 3x3 F.
    const auto          components = tracked_stress_components();
    const unsigned int  n_tracked  = tracked_ids.size();
    const unsigned int  tracked    = 5 + 2 * dim;
    const unsigned int  per_point  = 2 * dim + components.size() + 3;
    std::vector<double> sums(tracked + per_point * n_tracked, 0.);
    // The largest speed, then -min and max of each coordinate: the extent
    // of the material (toe and height of a collapse).
    std::vector<double> largest(1 + 2 * dim,
                                -std::numeric_limits<double>::max());
    for (const auto &particle : points.handler())
      {
        const ArrayView<const double> p = particle.get_properties();
        const double                  m = p[Layout::mass];
        const Tensor<1, dim>          v = Layout::get_velocity(p);
        const Point<dim> &            x = particle.get_location();
        largest[0] = std::max(largest[0], v.norm());
        for (unsigned int d = 0; d < dim; ++d)
          {
            largest[1 + 2 * d] = std::max(largest[1 + 2 * d], -x[d]);
            largest[2 + 2 * d] = std::max(largest[2 + 2 * d], x[d]);
          }
        sums[0] += 0.5 * m * v.norm_square();
        sums[1] += p[Layout::work_density] * p[Layout::reference_volume];
        sums[2] -= m * (gravity * x);
        sums[3] += m;
        for (unsigned int d = 0; d < dim; ++d)
          {
            sums[4 + d] += m * v[d];
            sums[4 + dim + d] += m * x[d];
          }
        sums[4 + 2 * dim] += Layout::current_volume(p);
        for (unsigned int k = 0; k < n_tracked; ++k)
          if (particle.get_id() == tracked_ids[k])
            {
              double *values = &sums[tracked + per_point * k];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  values[d]       = x[d];
                  values[dim + d] = v[d];
                }
              const SymmetricTensor<2, 3> stress = Layout::get_stress(p);
              for (unsigned int c = 0; c < components.size(); ++c)
                values[2 * dim + c] =
                  stress[components[c].first][components[c].second];
              const Tensor<2, 3> F = Layout::get_deformation_gradient_3d(p);
              for (unsigned int d = 0; d < 3; ++d)
                values[2 * dim + components.size() + d] = F[d][d];
            }
      }
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM,
                  communicator);
    MPI_Allreduce(MPI_IN_PLACE, largest.data(), largest.size(), MPI_DOUBLE,
                  MPI_MAX, communicator);
    const types::particle_index n_points = points.n_global_points();

    Diagnostics<dim> result;
    result.kinetic_energy       = sums[0];
    result.strain_energy        = sums[1];
    result.gravitational_energy = sums[2];
    result.mass                 = sums[3];
    for (unsigned int d = 0; d < dim; ++d)
      result.momentum[d] = sums[4 + d];

    const double removed_mass =
      points.has_outflow() ? points.removed_mass() : 0.;
    const types::particle_index removed_points =
      points.has_outflow() ? points.removed_points() : 0;
    std::vector<double> forces;
    for (const ForceReport *report : reports)
      for (const double force : report->forces())
        forces.push_back(force);

    if (file.is_open())
      {
        file << time << ',' << step << ',' << dt << ','
             << result.kinetic_energy << ',' << result.strain_energy << ','
             << result.gravitational_energy << ',' << result.total_energy();
        for (unsigned int d = 0; d < dim; ++d)
          file << ',' << result.momentum[d];
        file << ',' << result.mass;
        for (unsigned int d = 0; d < dim; ++d)
          file << ',' << sums[4 + dim + d] / result.mass;
        file << ',' << n_points << ',' << largest[0];
        for (unsigned int d = 0; d < dim; ++d)
          file << ',' << -largest[1 + 2 * d] << ',' << largest[2 + 2 * d];
        for (unsigned int k = tracked - 1; k < sums.size(); ++k)
          file << ',' << sums[k];
        if (points.has_outflow())
          file << ',' << removed_mass << ',' << removed_points;
        for (const double force : forces)
          file << ',' << force;
        file << '\n';
        file.flush();
      }
    return result;
  }



  template class TimeSeries<2>;
  template class TimeSeries<3>;
} // namespace mpm
