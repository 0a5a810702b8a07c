#include <deal.II/base/mpi.h>

#include <mpm/base/gathered_csv.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/base/shape_parameters.h>
#include <mpm/boundary/coulomb_contact.h>
#include <mpm/boundary/rigid_obstacles.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  RigidObstacles<dim>::declare_parameters(ParameterHandler &              prm,
                                          const std::vector<std::string> &names)
  {
    prm.enter_subsection("Obstacles");
    for (const std::string &name : names)
      {
        prm.enter_subsection(name);
        ShapeParameters<dim>::declare_parameters(
          prm,
          "of the rigid obstacle, at t = 0. It acts on the grid nodes on "
          "or inside it that carry material.");
        prm.declare_entry("Displacement",
                          "0; 0; 0",
                          Patterns::Anything(),
                          "The obstacle's displacement as a function of t, "
                          "one expression per component, ';'-separated: "
                          "'0; -0.01*t' moves it down at 0.01 m/s. Extra "
                          "trailing components beyond the dimension are "
                          "ignored if zero.");
        prm.declare_entry("Friction coefficient",
                          "0",
                          Patterns::Anything(),
                          "Coulomb friction between the obstacle and the "
                          "material: 0 or more, inf for no sliding.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }



  template <int dim>
  RigidObstacles<dim>::RigidObstacles(ParameterHandler &              prm,
                                      const std::vector<std::string> &names,
                                      const Grid<dim> &               grid)
    : RigidContact<dim>(grid)
  {
    prm.enter_subsection("Obstacles");
    for (const std::string &name : names)
      {
        const std::string path = "Obstacles/" + name;
        prm.enter_subsection(name);
        Obstacle   obstacle;
        Point<dim> center;
        obstacle.name  = name;
        obstacle.shape = ShapeParameters<dim>::create(prm, path, center);

        std::vector<std::string> expressions =
          Utilities::split_string_list(prm.get("Displacement"), ';');
        while (expressions.size() > dim && expressions.back() == "0")
          expressions.pop_back();
        if (expressions.size() != dim)
          throw InputError(path + "/Displacement = '" +
                           prm.get("Displacement") + "' must have " +
                           std::to_string(dim) +
                           " ';'-separated components.");
        if (grid.geometry().kind() == Geometry<dim>::Kind::axisymmetric &&
            expressions[0] != "0")
          throw InputError(path + "/Displacement = '" +
                           prm.get("Displacement") +
                           "': in an axisymmetric scene an obstacle is a "
                           "body of revolution and moves along the axis "
                           "only, so its x component must be 0.");
        obstacle.displacement = parse_function<1>(
          expressions, "t", Point<1>(), path + "/Displacement");

        obstacle.friction =
          parse_friction_coefficient(prm.get("Friction coefficient"),
                                     path + "/Friction coefficient");
        prm.leave_subsection();
        obstacles.push_back(std::move(obstacle));
      }
    prm.leave_subsection();
    offsets.resize(obstacles.size());
    velocities.resize(obstacles.size());
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  Tensor<1, dim>
  RigidObstacles<dim>::Obstacle::displacement_at(const double t) const
  {
    Tensor<1, dim> u;
    for (unsigned int d = 0; d < dim; ++d)
      u[d] = displacement->value(Point<1>(t), d);
    return u;
  }



  template <int dim>
  void
  RigidObstacles<dim>::setup()
  {
    // An obstacle must reach into the grid: some node of some rank within
    // one cell of it at t = 0. Checked on the first grid only (see
    // reach_checked).
    if (!reach_checked)
      {
        const double h = grid.minimum_cell_size();
        const unsigned int n_owned =
          grid.node_partitioner()->locally_owned_size();
        for (const Obstacle &obstacle : obstacles)
          {
            const Tensor<1, dim> u0   = obstacle.displacement_at(0.);
            bool                 near = false;
            for (unsigned int node = 0; node < n_owned && !near; ++node)
              near = obstacle.shape->signed_distance(
                       grid.node_position(node) - u0) <= h;
            if (!Utilities::MPI::logical_or(near, grid.get_communicator()))
              throw InputError("Obstacles/" + obstacle.name +
                               ": the obstacle lies outside the grid at t = "
                               "0 (no grid node within a cell of it); check "
                               "its shape against Grid/Arguments.");
          }
        reach_checked = true;
      }
    // Where the obstacles stand before the first step (the first output).
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      offsets[k] = obstacles[k].displacement_at(0.);
    this->clear_reactions();
  }



  template <int dim>
  double
  RigidObstacles<dim>::distance(const unsigned int k,
                                const unsigned int node) const
  {
    return obstacles[k].shape->signed_distance(grid.node_position(node) -
                                               offsets[k]);
  }



  template <int dim>
  Tensor<1, dim>
  RigidObstacles<dim>::contact_normal(const unsigned int    k,
                                      const unsigned int    node,
                                      const Tensor<1, dim> &relative) const
  {
    // A node on an edge or a corner, or on a face that lies on a grid line
    // through another face, is as near to several faces: take the face
    // the material comes through, seen a little way back along its
    // motion relative to the obstacle.
    const Point<dim> x = grid.node_position(node) - offsets[k];
    const double     speed = relative.norm();
    if (speed > 0.)
      {
        const Point<dim> behind =
          x - (1e-3 * grid.minimum_cell_size() / speed) * relative;
        if (obstacles[k].shape->signed_distance(behind) > 0.)
          return obstacles[k].shape->outward_normal(behind);
      }
    return obstacles[k].shape->outward_normal(x);
  }



  template <int dim>
  bool
  RigidObstacles<dim>::acts_on(const unsigned int node) const
  {
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      if (distance(k, node) <= 0.)
        return true;
    return false;
  }



  template <int dim>
  void
  RigidObstacles<dim>::begin_explicit_solve(const double time,
                                            const double dt) const
  {
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      {
        const Tensor<1, dim> start = obstacles[k].displacement_at(time);
        offsets[k]    = obstacles[k].displacement_at(time + dt);
        velocities[k] = (offsets[k] - start) / dt;
      }
    this->clear_reactions();
  }



  template <int dim>
  void
  RigidObstacles<dim>::constrain_velocity(const unsigned int node,
                                          double *           velocity) const
  {
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      if (distance(k, node) <= 0.)
        {
          Tensor<1, dim> relative;
          for (unsigned int d = 0; d < dim; ++d)
            relative[d] = velocity[d] - velocities[k][d];
          const Tensor<1, dim> into = -contact_normal(k, node, relative);
          const double         v_n  = relative * into;
          if (v_n > 0.)
            for (unsigned int d = 0; d < dim; ++d)
              velocity[d] -= v_n * into[d];
        }
  }



  template <int dim>
  void
  RigidObstacles<dim>::constrain_explicit(const unsigned int node,
                                          const unsigned int slot,
                                          const double       mass,
                                          double *           velocity,
                                          double *           acceleration,
                                          const double       dt,
                                          const double) const
  {
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      if (distance(k, node) <= 0.)
        {
          // Relative to the obstacle, where the node would end the step.
          Tensor<1, dim> relative;
          for (unsigned int d = 0; d < dim; ++d)
            relative[d] =
              velocity[d] + dt * acceleration[d] - velocities[k][d];
          const CoulombContact<dim> &law =
            this->act(node,
                      slot,
                      k,
                      relative,
                      -contact_normal(k, node, relative),
                      obstacles[k].friction,
                      mass,
                      dt);
          if (!law.active)
            continue;
          for (unsigned int d = 0; d < dim; ++d)
            {
              velocity[d]     = velocities[k][d] + law.end[d];
              acceleration[d] = 0.;
            }
        }
  }



  template <int dim>
  std::vector<std::string>
  RigidObstacles<dim>::force_names() const
  {
    const char *             axes = "xyz";
    std::vector<std::string> names;
    for (const Obstacle &obstacle : obstacles)
      {
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back(obstacle.name + "_force_" + axes[d]);
        names.push_back(obstacle.name + "_normal_force");
        names.push_back(obstacle.name + "_tangential_force");
      }
    return names;
  }



  template <int dim>
  std::vector<double>
  RigidObstacles<dim>::forces() const
  {
    // Per obstacle: the force vector, the normal and tangential sums.
    const unsigned int  n_values = dim + 2;
    std::vector<double> values(obstacles.size() * n_values, 0.);
    for (const auto *reaction : this->owned_reactions())
      {
        double *v = &values[reaction->surface * n_values];
        for (unsigned int d = 0; d < dim; ++d)
          v[d] += reaction->force[d];
        v[dim] += reaction->normal;
        v[dim + 1] += reaction->tangential.norm();
      }
    Utilities::MPI::sum(values, grid.get_communicator(), values);
    return values;
  }



  template <int dim>
  void
  RigidObstacles<dim>::write_tractions(const std::string &directory,
                                       const unsigned int step) const
  {
    const MPI_Comm comm = grid.get_communicator();
    for (unsigned int k = 0; k < obstacles.size(); ++k)
      {
        std::vector<std::array<double, dim + 2>> rows;
        for (const auto *reaction : this->owned_reactions())
          if (reaction->surface == k && reaction->normal > 0.)
            {
              std::array<double, dim + 2> row;
              for (unsigned int d = 0; d < dim; ++d)
                row[d] = grid.node_position(reaction->node)[d];
              row[dim]     = reaction->normal;
              row[dim + 1] = reaction->tangential.norm();
              rows.push_back(row);
            }
        write_gathered_csv(
          comm,
          rows,
          step_csv_name(directory, obstacles[k].name + "_forces", step),
          coordinate_columns<dim>() + "normal_force,tangential_force");
      }
  }



  template class RigidObstacles<2>;
  template class RigidObstacles<3>;
} // namespace mpm
