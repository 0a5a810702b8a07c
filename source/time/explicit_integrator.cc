#include <mpm/base/input_error.h>
#include <mpm/points/point_state.h>
#include <mpm/time/explicit_integrator.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  typename ExplicitIntegrator<dim>::Scheme
  ExplicitIntegrator<dim>::parse_scheme(const std::string &name)
  {
    if (name == "USF")
      return Scheme::USF;
    if (name == "USL")
      return Scheme::USL;
    if (name == "MUSL")
      return Scheme::MUSL;
    throw InputError("Time stepping/Update scheme = '" + name +
                     "' is not one of USF, USL, MUSL.");
  }



  template <int dim>
  ExplicitIntegrator<dim>::ExplicitIntegrator(
    GridTransfer<dim> &                           transfer,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Scheme                                  scheme,
    const double                                  pic_fraction,
    const bool                                    average_dilatation,
    const Grid<dim> &                             grid,
    TimerOutput &                                 timer)
    : transfer(transfer)
    , materials(materials)
    , scheme(scheme)
    , pic_fraction(pic_fraction)
    , average_dilatation(average_dilatation)
    , grid(grid)
    , timer(timer)
  {}



  template <int dim>
  typename ExplicitIntegrator<dim>::StepReport
  ExplicitIntegrator<dim>::step(const double dt)
  {
    cell_size = grid.minimum_cell_size();
    transfer.begin_step(dt);
    StepReport report;
    auto       timed = [this](const char *section, const auto &work) {
      TimerOutput::Scope scope(timer, section);
      work();
    };
    PointUpdate stress_and_move, advance_and_move, all;
    stress_and_move.update_stress = stress_and_move.move = true;
    advance_and_move.advance_velocity = advance_and_move.move = true;
    all.advance_velocity = all.update_stress = all.move = true;

    switch (scheme)
      {
        case Scheme::MUSL:
          // [W] 3.5, points 2-5: nodal v^t (unconstrained, so that the
          // walls' correction of a sees it), forces, accelerations, and
          // v^t + dt a, which the PIC share of the point update needs.
          timed("P2G", [&] { transfer.project_mass_momentum(true); });
          timed("nodal solve", [&] {
            transfer.compute_nodal_velocity(false);
            transfer.compute_nodal_acceleration(dt);
          });
          // Point 6: V_p += dt N a (blended with PIC, if asked); point 7:
          // v^L from the new point velocities, in the same pass.
          timed("G2P and P2G", [&] {
            transfer.project_momentum(
              [&](Particle &particle, const Support<dim> &support) {
                advance_velocity(particle, support, dt);
              });
          });
          timed("nodal solve", [&] { transfer.compute_nodal_velocity(); });
          // Points 8-9: stress and positions from v^L.
          timed("G2P", [&] { update_points(dt, stress_and_move, report); });
          break;
        case Scheme::USL:
          timed("P2G", [&] { transfer.project_mass_momentum(true); });
          timed("nodal solve", [&] {
            transfer.compute_nodal_velocity(false);
            transfer.compute_nodal_acceleration(dt);
          });
          timed("G2P", [&] { update_points(dt, all, report); });
          break;
        case Scheme::USF:
          timed("P2G", [&] { transfer.project_mass_momentum(false); });
          timed("nodal solve", [&] { transfer.compute_nodal_velocity(); });
          // The stresses from v^t, and the forces from them, in one pass.
          timed("G2P and P2G", [&] {
            prepare_stress_update();
            transfer.project_force(
              [&](Particle &particle, const Support<dim> &support) {
                update_stress(particle, support, dt, report);
              });
          });
          timed("nodal solve",
                [&] { transfer.compute_nodal_acceleration(dt); });
          timed("G2P", [&] { update_points(dt, advance_and_move, report); });
          break;
      }
    return report;
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::update_points(const double       dt,
                                         const PointUpdate &update,
                                         StepReport &       report)
  {
    if (update.update_stress)
      prepare_stress_update();
    transfer.for_each_point(
      [&](Particle &particle, const Support<dim> &support) {
        if (update.advance_velocity)
          advance_velocity(particle, support, dt);
        if (update.update_stress)
          update_stress(particle, support, dt, report);
        if (update.move)
          move(particle, support, dt, report);
      });
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::prepare_stress_update()
  {
    transfer.solve_grid_fields();
    if (average_dilatation)
      average_dilatation_rates();
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::advance_velocity(Particle &          particle,
                                            const Support<dim> &support,
                                            const double        dt) const
  {
    // FLIP, v_p + dt N a, blended with PIC, N (v + dt a): the PIC share
    // damps point velocities that the grid cannot represent.
    const ArrayView<double> p     = particle->get_properties();
    const unsigned int      field = transfer.field_of(p);
    const Tensor<1, dim>    a =
      transfer.interpolate(support, field, NodalLayout::force);
    if (pic_fraction > 0.)
      {
        const Tensor<1, dim> v =
          transfer.interpolate(support, field, NodalLayout::velocity);
        for (unsigned int d = 0; d < dim; ++d)
          p[Layout::velocity + d] =
            (1. - pic_fraction) * (p[Layout::velocity + d] + dt * a[d]) +
            pic_fraction * v[d];
      }
    else
      for (unsigned int d = 0; d < dim; ++d)
        p[Layout::velocity + d] += dt * a[d];
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::update_stress(Particle &          particle,
                                         const Support<dim> &support,
                                         const double        dt,
                                         StepReport &        report)
  {
    const ArrayView<double> p = particle->get_properties();
    Tensor<2, 3>            L = velocity_gradient(particle, support);
    if (average_dilatation)
      {
        // The cell's mean dilatation rate in place of the point's own,
        // spread over the directions that can stretch (in plane strain
        // not zz).
        const unsigned int n = grid.geometry().n_stretching_directions();
        const double       shift =
          (cell_dilatation_rate[particle->get_surrounding_cell()
                                  ->active_cell_index()] -
           trace(L)) /
          n;
        for (unsigned int d = 0; d < n; ++d)
          L[d][d] += shift;
      }
    const Tensor<2, 3> F_old = Layout::get_deformation_gradient_3d(p);
    const Tensor<2, 3> F_new = (unit_symmetric_tensor<3>() + dt * L) * F_old;
    const double       J_new = determinant(F_new);
    if (!(J_new > 0.))
      {
        report.record_failure(particle->get_location(),
                              "a material point was inverted (det F = " +
                                std::to_string(J_new) + ")");
        return;
      }

    const Material &material =
      *materials[static_cast<unsigned int>(p[Layout::material_id])];
    StepKinematics kinematics;
    kinematics.F_old             = F_old;
    kinematics.F_new             = F_new;
    kinematics.velocity_gradient = L;
    kinematics.dt                = dt;
    kinematics.density = p[Layout::mass] / Layout::current_volume(p, F_new);
    transfer.read_grid_fields(static_cast<unsigned int>(p[Layout::material_id]),
                              support,
                              kinematics);
    if (!PointState<dim>::commit(materials,
                                 kinematics,
                                 p,
                                 grid.geometry().free_faces()))
      {
        report.record_failure(particle->get_location(),
                              "no out-of-plane stretch of a material point "
                              "gives sigma_zz = 0 (plane stress)");
        return;
      }
    report.max_signal_speed = std::max(
      report.max_signal_speed,
      material.signal_speed(Layout::get_stress(p),
                            ArrayView<const double>(
                              &p[Layout::internal_variables],
                              material.n_internal_variables()),
                            cell_size));
  }



  template <int dim>
  Tensor<2, 3>
  ExplicitIntegrator<dim>::velocity_gradient(const Particle &    particle,
                                             const Support<dim> &support) const
  {
    // In 3x3 form: in an axisymmetric scene L_tt = v_r / r, the hoop rate
    // ([W]'s d_tt); in plane strain L_zz = 0, and in plane stress the
    // point's law chooses it (PlaneStress) when the step is committed.
    const unsigned int field = transfer.field_of(particle->get_properties());
    return Layout::embed(
      transfer.velocity_gradient(support, field),
      grid.geometry().hoop_ratio(particle->get_location(), [&]() {
        return transfer.interpolate(support, field, NodalLayout::velocity)[0];
      }));
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::average_dilatation_rates()
  {
    // Only the cells that hold points are touched, so an empty grid costs
    // nothing.
    const unsigned int n_cells = grid.get_triangulation().n_active_cells();
    if (cell_volume.size() != n_cells)
      {
        cell_dilatation_rate.assign(n_cells, 0.);
        cell_volume.assign(n_cells, 0.);
        occupied_cells.clear();
      }
    for (const unsigned int cell : occupied_cells)
      cell_dilatation_rate[cell] = cell_volume[cell] = 0.;
    occupied_cells.clear();
    transfer.for_each_point(
      [&](Particle &particle, const Support<dim> &support) {
        const unsigned int cell =
          particle->get_surrounding_cell()->active_cell_index();
        const double volume =
          Layout::current_volume(particle->get_properties());
        if (cell_volume[cell] == 0.)
          occupied_cells.push_back(cell);
        cell_dilatation_rate[cell] +=
          volume * trace(velocity_gradient(particle, support));
        cell_volume[cell] += volume;
      });
    for (const unsigned int cell : occupied_cells)
      cell_dilatation_rate[cell] /= cell_volume[cell];
  }



  template <int dim>
  void
  ExplicitIntegrator<dim>::move(Particle &          particle,
                                const Support<dim> &support,
                                const double        dt,
                                StepReport &        report)
  {
    const ArrayView<const double> p = particle->get_properties();
    const Tensor<1, dim>          v =
      transfer.interpolate(support, transfer.field_of(p), NodalLayout::velocity);
    const Point<dim> x = particle->get_location();

    double speed_square = 0.;
    double fraction     = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      {
        speed_square += p[Layout::velocity + d] * p[Layout::velocity + d];
        fraction = std::max(fraction, std::abs(dt * v[d]) / cell_size);
      }
    if (!std::isfinite(speed_square) || !std::isfinite(fraction))
      {
        report.record_failure(x, "a material point has a non-finite velocity");
        return;
      }
    // Among points that move alike, report the lexicographically first, so
    // the message does not depend on the number of ranks.
    const double tie = 1e-12 * report.max_cell_fraction;
    if (fraction > report.max_cell_fraction + tie ||
        (fraction > report.max_cell_fraction - tie &&
         lexicographically_less(x, report.fastest_position)))
      {
        report.max_cell_fraction =
          std::max(fraction, report.max_cell_fraction);
        report.fastest_position = x;
      }
    report.max_speed = std::max(report.max_speed, std::sqrt(speed_square));
    particle->set_location(x + dt * v);
  }



  template class ExplicitIntegrator<2>;
  template class ExplicitIntegrator<3>;
} // namespace mpm
