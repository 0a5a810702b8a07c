#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/particles/data_out.h>

#include <mpm/base/input_error.h>
#include <mpm/output/vtu_output.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace mpm
{
  namespace
  {
    /**
     * The meshfree nodes as vertex patches: position, velocity,
     * acceleration, and which components a wall holds (1 held, 0 free).
     */
    template <int dim>
    class CloudDataOut : public DataOutInterface<0, dim>
    {
    public:
      /** `n_nodes`: how many of the cloud's nodes this rank writes. */
      CloudDataOut(const NodeCloud<dim> &cloud, const unsigned int n_nodes)
      {
        const unsigned int n_data = 3 * dim;
        for (unsigned int i = 0; i < n_nodes; ++i)
          {
            DataOutBase::Patch<0, dim> patch;
            patch.vertices[0] = cloud.positions[i];
            patch.patch_index = i;
            patch.data.reinit(n_data, 1);
            const std::array<bool, dim> held = cloud.held_components(i);
            for (unsigned int d = 0; d < dim; ++d)
              {
                patch.data(d, 0)           = cloud.velocities[i][d];
                patch.data(dim + d, 0)     = cloud.accelerations[i][d];
                patch.data(2 * dim + d, 0) = held[d] ? 1. : 0.;
              }
            patches.push_back(patch);
          }
        for (const std::string name : {"velocity", "acceleration", "held"})
          for (unsigned int d = 0; d < dim; ++d)
            names.push_back(name);
      }

    private:
      const std::vector<DataOutBase::Patch<0, dim>> &
      get_patches() const override
      {
        return patches;
      }

      std::vector<std::string>
      get_dataset_names() const override
      {
        return names;
      }

      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
      get_nonscalar_data_ranges() const override
      {
        std::vector<std::tuple<
          unsigned int,
          unsigned int,
          std::string,
          DataComponentInterpretation::DataComponentInterpretation>>
          ranges;
        for (unsigned int k = 0; k < 3; ++k)
          ranges.emplace_back(k * dim,
                              k * dim + dim - 1,
                              names[k * dim],
                              DataComponentInterpretation::
                                component_is_part_of_vector);
        return ranges;
      }

      std::vector<DataOutBase::Patch<0, dim>> patches;
      std::vector<std::string>                names;
    };
  } // namespace



  template <int dim>
  void
  VtuOutput<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Write ParaView output", "true", Patterns::Bool(),
                      "Write snapshots of points (and grid) for ParaView. "
                      "Off for throughput measurements.");
    prm.declare_entry("Interval", "0", Patterns::Double(0.),
                      "Simulated time between ParaView snapshots. 0 writes "
                      "the first and the last state only.");
    prm.declare_entry("Write grid", "true", Patterns::Bool(),
                      "Also write the background grid with nodal mass, "
                      "velocity and acceleration.");
    prm.leave_subsection();
  }



  template <int dim>
  VtuOutput<dim>::VtuOutput(ParameterHandler & prm,
                            const std::string &directory,
                            const double       end_time,
                            const MPI_Comm     communicator)
    : directory(directory.empty() || directory.back() == '/' ? directory :
                                                                 directory + "/")
    , communicator(communicator)
  {
    prm.enter_subsection("Output");
    write_paraview    = prm.get_bool("Write ParaView output");
    snapshot_interval = prm.get_double("Interval");
    write_grid        = prm.get_bool("Write grid");
    prm.leave_subsection();
    const double max_snapshots = 1e5;
    if (write_paraview && snapshot_interval > 0. &&
        end_time / snapshot_interval > max_snapshots)
      {
        std::ostringstream message;
        message << "Output/Interval = " << snapshot_interval
                << " would write " << end_time / snapshot_interval
                << " snapshots before End time = " << end_time
                << "; give at least End time / " << max_snapshots << " = "
                << end_time / max_snapshots
                << ", or 0 for the first and the last state only.";
        throw InputError(message.str());
      }
  }



  template <int dim>
  template <int patch_dim>
  void
  VtuOutput<dim>::write_snapshot(
    const DataOutInterface<patch_dim, dim> &      data_out,
    const std::string &                           name,
    const double                                  time,
    std::vector<std::pair<double, std::string>> &records) const
  {
    records.emplace_back(time,
                         data_out.write_vtu_with_pvtu_record(
                           directory, name, counter, communicator, 5));
    write_series(name, records);
  }



  template <int dim>
  void
  VtuOutput<dim>::write_series(
    const std::string &                                name,
    const std::vector<std::pair<double, std::string>> &records) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) == 0 && !records.empty())
      {
        std::ofstream pvd(directory + name + ".pvd");
        DataOutBase::write_pvd_record(pvd, records);
      }
  }



  template <int dim>
  void
  VtuOutput<dim>::write(const double               time,
                        const MaterialPoints<dim> &points,
                        const GridNodes<dim> &     nodes,
                        const Mapping<dim> &       mapping,
                        const NodeCloud<dim> *     cloud)
  {
    using Layout = PointLayout<dim>;

    {
      const std::vector<std::string> names = points.property_names();
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
        interpretation(names.size(),
                       DataComponentInterpretation::component_is_scalar);
      for (const unsigned int first : points.vector_properties())
        for (unsigned int d = 0; d < dim; ++d)
          interpretation[first + d] =
            DataComponentInterpretation::component_is_part_of_vector;

      Particles::DataOut<dim> data_out;
      data_out.build_patches(points.handler(), names, interpretation);
      write_snapshot(data_out, "points", time, point_records);
    }

    if (write_grid)
      {
        using NodalLayout = typename GridNodes<dim>::NodalLayout;
        std::vector<std::string> names(NodalLayout::n_components);
        std::vector<DataComponentInterpretation::DataComponentInterpretation>
          interpretation(
            NodalLayout::n_components,
            DataComponentInterpretation::component_is_part_of_vector);
        names[NodalLayout::mass] = "nodal_mass";
        interpretation[NodalLayout::mass] =
          DataComponentInterpretation::component_is_scalar;
        for (unsigned int d = 0; d < dim; ++d)
          {
            names[NodalLayout::velocity + d] = "nodal_velocity";
            names[NodalLayout::force + d]    = "nodal_acceleration";
          }

        // A ghost node that no local point touches holds the owner's raw
        // sums from the last projection; output_vector() fetches the
        // owner's solved values.
        DataOut<dim> data_out;
        data_out.attach_dof_handler(nodes.output_dof_handler());
        data_out.add_data_vector(nodes.output_vector(),
                                 names,
                                 DataOut<dim>::type_dof_data,
                                 interpretation);
        Vector<float> subdomain(
          nodes.output_dof_handler().get_triangulation().n_active_cells());
        subdomain = Utilities::MPI::this_mpi_process(communicator);
        data_out.add_data_vector(subdomain, "subdomain");
        data_out.build_patches(mapping);
        write_snapshot(data_out, "grid", time, grid_records);
      }

    if (cloud != nullptr)
      {
        // Every rank holds the whole cloud; the first writes it.
        const bool first_rank =
          Utilities::MPI::this_mpi_process(communicator) == 0;
        write_snapshot(CloudDataOut<dim>(*cloud, first_rank ? cloud->size() : 0),
                       "nodes",
                       time,
                       cloud_records);
      }
    ++counter;
  }



  template class VtuOutput<2>;
  template class VtuOutput<3>;
} // namespace mpm
