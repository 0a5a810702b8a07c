#include <deal.II/base/mpi.h>

#include <mpm/base/gathered_csv.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/boundary/boundary_walls.h>
#include <mpm/boundary/coulomb_contact.h>
#include <mpm/boundary/friction_walls.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  FrictionWalls<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry(
      "Friction boundaries",
      "",
      Patterns::Anything(),
      "Named boundaries that are rigid walls with Coulomb friction, each "
      "with its friction coefficient: 'name: mu, name: mu'. The wall holds "
      "the material only while it presses (it may lift off) and resists "
      "sliding up to mu times the normal force. mu = 0 is a frictionless "
      "one-sided wall, mu = inf one on which the material cannot slide. "
      "Explicit, quasi-static and Newmark schemes, with MPM. The forces on each wall go into the time "
      "series, and its tractions into <name>_tractions_<step>.csv at each "
      "output time. 'name: mu until t' ends the wall at time t.");
    prm.leave_subsection();
  }



  template <int dim>
  FrictionWalls<dim>::FrictionWalls(ParameterHandler &prm,
                                    const Grid<dim> & grid)
    : RigidContact<dim>(grid)
  {
    const std::string entry = "Boundary conditions/Friction boundaries";
    prm.enter_subsection("Boundary conditions");
    const std::string text = prm.get("Friction boundaries");
    std::vector<std::string> other_walls;
    for (const char *other :
         {"Fixed boundaries", "Slip boundaries", "Contact boundaries"})
      for (const std::string &item :
           Utilities::split_string_list(prm.get(other)))
        other_walls.push_back(split_until(item, other).first);
    prm.leave_subsection();

    for (const std::string &listed : Utilities::split_string_list(text, ','))
      {
        const auto [item, until] = split_until(listed, entry);
        const std::vector<std::string> parts =
          Utilities::split_string_list(item, ':');
        if (parts.size() != 2 || parts[0].empty() || parts[1].empty())
          throw InputError(entry + ": '" + item +
                           "' must be 'boundary name: friction "
                           "coefficient', for example 'floor: 0.3'.");
        Wall wall;
        wall.name  = parts[0];
        wall.until = until;
        wall.friction = parse_friction_coefficient(
          parts[1],
          entry + ": the friction coefficient of '" + wall.name + "'");
        for (const Wall &earlier : walls)
          if (earlier.name == wall.name)
            throw InputError(entry + " names '" + wall.name + "' twice.");
        if (std::find(other_walls.begin(), other_walls.end(), wall.name) !=
            other_walls.end())
          throw InputError(entry + " names '" + wall.name +
                           "', which another entry of Boundary conditions "
                           "names too; a boundary has one condition.");
        wall.id = grid.boundary_id(wall.name, entry);
        walls.push_back(wall);
      }
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  void
  FrictionWalls<dim>::setup()
  {
    const auto &tria = grid.get_triangulation();
    const std::vector<types::boundary_id> present = tria.get_boundary_ids();
    for (const Wall &wall : walls)
      if (std::find(present.begin(), present.end(), wall.id) == present.end())
        throw InputError("Boundary conditions/Friction boundaries names '" +
                         wall.name +
                         "', but no face of the grid has its boundary id " +
                         std::to_string(wall.id) +
                         ". For subdivided_hyper_rectangle, set colorize = "
                         "true in Grid/Arguments.");

    std::vector<types::boundary_id> ids;
    for (const Wall &wall : walls)
      ids.push_back(wall.id);
    const BoundaryWalls<dim> found(grid, ids);
    for (unsigned int w = 0; w < walls.size(); ++w)
      {
        const Tensor<1, dim> sum =
          Utilities::MPI::sum(found.owned_normal_sum(w),
                              tria.get_communicator());
        if (!(sum.norm() > 1e-12 * grid.minimum_cell_size()))
          throw InputError("Boundary conditions/Friction boundaries: the "
                           "faces of '" + walls[w].name + "' have no mean "
                           "direction (a closed boundary?); give its parts "
                           "names of their own.");
        walls[w].mean_normal = sum / sum.norm();
      }

    first_contact.assign(grid.n_nodes() + 1, 0);
    contacts.clear();
    // Ordered by node, then wall: each node's walls in the order of the
    // entry.
    for (const auto &entry : found.nodes_on_walls())
      {
        Contact contact;
        contact.wall     = entry.wall;
        contact.outward  = entry.normal / entry.normal.norm();
        contact.area     = entry.share;
        contact.position = entry.position;
        contacts.push_back(contact);
        ++first_contact[entry.node + 1];
      }
    for (unsigned int k = 0; k < grid.n_nodes(); ++k)
      first_contact[k + 1] += first_contact[k];
    this->clear_reactions();
  }



  template <int dim>
  void
  FrictionWalls<dim>::constrain_velocity(const unsigned int node,
                                         double *           velocity) const
  {
    for (unsigned int c = first_contact[node]; c < first_contact[node + 1];
         ++c)
      {
        if (!(solve_time < walls[contacts[c].wall].until))
          continue;
        const Tensor<1, dim> &n   = contacts[c].outward;
        double                v_n = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          v_n += velocity[d] * n[d];
        if (v_n > 0.)
          for (unsigned int d = 0; d < dim; ++d)
            velocity[d] -= v_n * n[d];
      }
  }



  template <int dim>
  void
  FrictionWalls<dim>::constrain_initial_acceleration(
    const unsigned int node,
    const double *     velocity,
    double *           acceleration) const
  {
    for (unsigned int c = first_contact[node]; c < first_contact[node + 1];
         ++c)
      {
        const Tensor<1, dim> &n   = contacts[c].outward;
        double                v_n = 0., a_n = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            v_n += velocity[d] * n[d];
            a_n += acceleration[d] * n[d];
          }
        if (!(v_n < 0.) && a_n > 0.)
          for (unsigned int d = 0; d < dim; ++d)
            acceleration[d] -= a_n * n[d];
      }
  }



  template <int dim>
  void
  FrictionWalls<dim>::begin_explicit_solve(const double time,
                                           const double) const
  {
    solve_time = time;
    reset_reactions();
  }



  template <int dim>
  void
  FrictionWalls<dim>::constrain_explicit(const unsigned int node,
                                         const unsigned int slot,
                                         const double       mass,
                                         double *           velocity,
                                         double *           acceleration,
                                         const double       dt,
                                         const double       time) const
  {
    for (unsigned int c = first_contact[node]; c < first_contact[node + 1];
         ++c)
      {
        if (!(time < walls[contacts[c].wall].until))
          continue;
        // Where the node would end the step without this wall.
        Tensor<1, dim> trial;
        for (unsigned int d = 0; d < dim; ++d)
          trial[d] = velocity[d] + dt * acceleration[d];
        const CoulombContact<dim> &law =
          this->act(node,
                    slot,
                    c,
                    trial,
                    contacts[c].outward,
                    walls[contacts[c].wall].friction,
                    mass,
                    dt);
        if (!law.active)
          continue;
        for (unsigned int d = 0; d < dim; ++d)
          {
            velocity[d]     = law.end[d];
            acceleration[d] = 0.;
          }
      }
  }



  template <int dim>
  bool
  FrictionWalls<dim>::add_constraints(
    const unsigned int                              node,
    const std::array<types::global_dof_index, dim> &dofs,
    const Hold *                                    holds,
    AffineConstraints<double> &                     constraints) const
  {
    const unsigned int n_walls = n_unilateral_walls(node);
    bool               supported = true;
    for (unsigned int k = 0; k < n_walls; ++k)
      if (holds[k] == Hold::stick)
        this->hold_all(dofs, constraints);
      else if (holds[k] == Hold::slip)
        supported &= this->hold_along_normal(
          dofs, unilateral_normal(node, k), n_walls == 1, constraints);
    return supported;
  }



  template <int dim>
  std::vector<std::string>
  FrictionWalls<dim>::force_names() const
  {
    std::vector<std::string> names;
    for (const Wall &wall : walls)
      {
        names.push_back(wall.name + "_normal_force");
        names.push_back(wall.name + "_tangential_force");
      }
    return names;
  }



  template <int dim>
  std::vector<Tensor<1, dim>>
  FrictionWalls<dim>::local_wall_forces() const
  {
    std::vector<Tensor<1, dim>> totals(walls.size());
    for (const auto *reaction : this->owned_reactions_by_surface())
      {
        const Contact &contact = contacts[reaction->surface];
        totals[contact.wall] +=
          reaction->normal * contact.outward + reaction->tangential;
      }
    return totals;
  }



  template <int dim>
  Tensor<1, dim>
  FrictionWalls<dim>::tangent_of(const Tensor<1, dim> &normal)
  {
    Tensor<1, dim> t;
    if constexpr (dim == 2)
      t = cross_product_2d(-normal);
    return t;
  }



  template <int dim>
  std::vector<double>
  FrictionWalls<dim>::forces() const
  {
    std::vector<double>               values;
    const MPI_Comm                    comm  = grid.get_communicator();
    const std::vector<Tensor<1, dim>> local = local_wall_forces();
    for (unsigned int w = 0; w < walls.size(); ++w)
      {
        const Tensor<1, dim> total = Utilities::MPI::sum(local[w], comm);
        const Tensor<1, dim> &n      = walls[w].mean_normal;
        const double          normal = total * n;
        const Tensor<1, dim>  across = total - normal * n;
        values.push_back(normal);
        values.push_back(dim == 2 ? across * tangent_of(n) : across.norm());
      }
    return values;
  }



  template <int dim>
  void
  FrictionWalls<dim>::write_tractions(const std::string &directory,
                                      const unsigned int step) const
  {
    const MPI_Comm     comm = grid.get_communicator();
    const unsigned int n_owned =
      grid.node_partitioner()->locally_owned_size();
    // Per contact: the normal force and the tangential one, over fields.
    std::vector<std::pair<double, Tensor<1, dim>>> at_contact(contacts.size());
    for (const auto *reaction : this->owned_reactions_by_surface())
      {
        at_contact[reaction->surface].first += reaction->normal;
        at_contact[reaction->surface].second += reaction->tangential;
      }
    for (unsigned int w = 0; w < walls.size(); ++w)
      {
        // Rows of dim + 2 numbers: position, normal and tangential
        // traction.
        std::vector<std::array<double, dim + 2>> rows;
        for (unsigned int node = 0; node < n_owned; ++node)
          for (unsigned int c = first_contact[node];
               c < first_contact[node + 1];
               ++c)
            if (contacts[c].wall == w)
              {
                const Contact &          contact = contacts[c];
                const Tensor<1, dim> &   T       = at_contact[c].second;
                std::array<double, dim + 2> row;
                for (unsigned int d = 0; d < dim; ++d)
                  row[d] = contact.position[d];
                row[dim]     = at_contact[c].first / contact.area;
                row[dim + 1] = (dim == 2 ? T * tangent_of(contact.outward) :
                                           T.norm()) /
                               contact.area;
                rows.push_back(row);
              }
        write_gathered_csv(
          comm,
          rows,
          step_csv_name(directory, walls[w].name + "_tractions", step),
          coordinate_columns<dim>() + "normal_traction,tangential_traction");
      }
  }



  template class FrictionWalls<2>;
  template class FrictionWalls<3>;
} // namespace mpm
