#include <mpm/base/input_error.h>
#include <mpm/time/explicit_scheme.h>
#include <mpm/time/implicit_scheme.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  void
  ImplicitScheme<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry("Load steps", "10", Patterns::Integer(1),
                      "Quasi-static: number of equal load steps.");
    prm.leave_subsection();
    ImplicitIntegrator<dim>::declare_parameters(prm);
  }



  template <int dim>
  ImplicitScheme<dim>::ImplicitScheme(
    ParameterHandler &                      prm,
    const typename TimeScheme<dim>::Scene & scene,
    const bool                              dynamic,
    const GridBasis<dim> &                  basis,
    const DirichletConditions<dim> &        dirichlet,
    const Tensor<1, dim> &                  gravity,
    std::unique_ptr<MeshfreeBasis<dim>>     meshfree)
    : TimeScheme<dim>(prm, scene)
    , dynamic(dynamic)
    , n_load_steps(static_cast<unsigned int>(
        TimeScheme<dim>::time_stepping_number(prm, "Load steps")))
    , integrator(dynamic,
                 prm,
                 scene.points,
                 scene.grid,
                 basis,
                 scene.nodal_conditions,
                 dirichlet,
                 scene.materials,
                 gravity,
                 scene.pcout,
                 scene.timer,
                 std::move(meshfree))
  {
    if (dynamic && !(this->fixed_time_step > 0.))
      throw InputError("Time stepping/Scheme = Newmark needs a Time step "
                       "above 0.");
    const std::vector<std::string> ignored =
      ExplicitScheme<dim>::entries_set(prm);
    if (!ignored.empty())
      {
        scene.pcout << "mpm: note: Time stepping/" << comma_separated(ignored)
                    << (ignored.size() == 1 ? " applies" : " apply")
                    << " to the explicit scheme only; this "
                    << (dynamic ? "Newmark" : "quasi-static")
                    << " run ignores " << (ignored.size() == 1 ? "it" : "them")
                    << "." << std::endl;
      }
    next_step = step_size();
  }



  template <int dim>
  double
  ImplicitScheme<dim>::step_size() const
  {
    return dynamic ? this->fixed_time_step : this->end_time() / n_load_steps;
  }



  template <int dim>
  void
  ImplicitScheme<dim>::start()
  {
    if (!dynamic)
      return;
    GridTransfer<dim> &transfer = this->scene.transfer;
    MaterialPoints<dim> &points = this->scene.points;
    transfer.set_load_factor(this->scene.loads.load_factor(0.));
    transfer.project_mass_momentum(true);
    transfer.compute_initial_acceleration();
    transfer.for_each_point([&](auto &particle, const Support<dim> &support) {
      const Tensor<1, dim> a =
        transfer.interpolate(support,
                             transfer.field_of(particle->get_properties()),
                             GridNodes<dim>::NodalLayout::force);
      for (unsigned int d = 0; d < dim; ++d)
        particle->get_properties()[points.slot_index("acceleration") + d] = a[d];
    });
  }



  template <int dim>
  double
  ImplicitScheme<dim>::advance(const double time, const unsigned int step)
  {
    double dt = this->step_to_end(time, next_step);

    ConditionalOStream &pcout    = this->scene.pcout;
    const unsigned int  max_cuts = 4;
    for (unsigned int cut = 0;; ++cut)
      {
        try
          {
            const double load_factor =
              this->scene.loads.load_factor(time + dt);
            pcout << (dynamic ? "  time step " : "  load step ") << step + 1
                  << ": t = " << time + dt << ", load factor " << load_factor
                  << std::endl;
            integrator.step(load_factor, dt);
            break;
          }
        catch (const RunError &e)
          {
            if (!e.smaller_step_helps)
              throw RunError(std::string(e.what()) +
                               " The last good state is in the output "
                               "written so far.",
                             false);
            if (cut == max_cuts)
              throw RunError(std::string(e.what()) + " Cut " +
                             std::to_string(max_cuts) +
                             " times; giving up. The last good state is in "
                             "the output written so far.");
            dt /= 2.;
            pcout << "  " << e.what() << " Cutting the step to " << dt << "."
                  << std::endl;
          }
      }
    next_step = std::min(step_size(), 2. * dt);
    return dt;
  }



  template <int dim>
  void
  ImplicitScheme<dim>::prepare_grid_output()
  {
    this->scene.transfer.project_mass_momentum(false);
    this->scene.transfer.compute_nodal_velocity();
  }



  template <int dim>
  void
  ImplicitScheme<dim>::print_statistics() const
  {
    if (const MeshfreeBasis<dim> *meshfree = integrator.meshfree_basis())
      {
        // Each rank counts its own evaluations.
        const auto &   counts = meshfree->statistics();
        const MPI_Comm comm   = this->scene.points.get_communicator();
        this->scene.pcout << "meshfree: " << integrator.node_cloud()->size()
                          << " nodes, "
                          << Utilities::MPI::sum(counts.evaluations, comm)
                          << " shape-function evaluations, "
                          << Utilities::MPI::sum(counts.radius_growths, comm)
                          << " of them with a larger radius (nodes added), "
                          << Utilities::MPI::sum(counts.retries, comm)
                          << " retries" << std::endl;
      }
  }



  template <int dim>
  std::vector<std::string>
  ImplicitScheme<dim>::entries_that_may_change() const
  {
    // The quasi-static loads ramp over End time, so there only the number
    // of load steps may change.
    if (dynamic)
      return {"Time stepping/End time", "Time stepping/Time step"};
    return {"Time stepping/Load steps"};
  }



  template <int dim>
  void
  ImplicitScheme<dim>::save(boost::archive::binary_oarchive &archive) const
  {
    archive << next_step << integrator;
  }



  template <int dim>
  void
  ImplicitScheme<dim>::load(boost::archive::binary_iarchive &archive)
  {
    archive >> next_step >> integrator;
    // The step size may have been lowered.
    next_step = std::min(next_step, step_size());
  }



  template class ImplicitScheme<2>;
  template class ImplicitScheme<3>;
} // namespace mpm
