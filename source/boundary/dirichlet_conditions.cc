#include <deal.II/base/mpi.h>

#include <mpm/boundary/boundary_walls.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>

#include <algorithm>
#include <map>

namespace mpm
{
  template <int dim>
  void
  DirichletConditions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("Fixed boundaries",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Named boundaries (see Grid/Boundary names) whose "
                      "nodes have zero velocity. 'name until t' ends the "
                      "wall at time t (explicit scheme), e.g. an orifice "
                      "that opens.");
    prm.declare_entry("Slip boundaries",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Named boundaries whose nodes have zero normal "
                      "velocity and slide freely along the boundary. "
                      "'name until t' ends the wall at time t (explicit "
                      "scheme).");
    prm.declare_entry("Contact boundaries",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Named boundaries that hold the material without slip "
                      "where it presses on them and let it go where it "
                      "pulls away (unilateral contact with full friction), "
                      "so that a body can roll or lift off. Implicit "
                      "schemes only: each step finds the contact nodes "
                      "by an active set, releasing nodes whose wall force "
                      "pulls and engaging nodes that move into the wall.");
    prm.leave_subsection();
  }



  template <int dim>
  DirichletConditions<dim>::DirichletConditions(ParameterHandler &prm,
                                                const Grid<dim> & grid)
    : grid(grid)
  {
    prm.enter_subsection("Boundary conditions");
    const auto read = [&](const std::string &               entry,
                          std::vector<std::string> &        names,
                          std::vector<types::boundary_id> &ids) {
      for (const std::string &item :
           Utilities::split_string_list(prm.get(entry)))
        {
          const std::string path = "Boundary conditions/" + entry;
          const auto [name, until] = split_until(item, path);
          names.push_back(name);
          ids.push_back(grid.boundary_id(name, path));
          if (until < std::numeric_limits<double>::infinity())
            end_times[ids.back()] = until;
        }
    };
    read("Fixed boundaries", fixed_names, fixed_ids);
    read("Slip boundaries", slip_names, slip_ids);
    contact_names =
      Utilities::split_string_list(prm.get("Contact boundaries"));
    prm.leave_subsection();
    for (const auto &name : contact_names)
      contact_ids.push_back(
        grid.boundary_id(name, "Boundary conditions/Contact boundaries"));
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  void
  DirichletConditions<dim>::check_scene(const SceneChoices &choices) const
  {
    if (has_contact() && choices.explicit_steps())
      throw InputError("Boundary conditions/Contact boundaries are handled by "
                       "the quasi-static and Newmark schemes only; with Time "
                       "stepping/Scheme = explicit use Fixed, Slip or "
                       "Friction boundaries.");
    if (has_end_times() && !choices.explicit_steps())
      throw InputError("Boundary conditions: a wall that ends ('name until "
                       "t') needs Time stepping/Scheme = explicit.");
  }



  template <int dim>
  void
  DirichletConditions<dim>::check_axis() const
  {
    // A boundary face on x = 0 lies on the axis: the material there may
    // move along it but not across it.
    bool unheld = false;
    BoundaryWalls<dim>::for_each_boundary_face(
      grid, true, [&](const auto &cell, const unsigned int f) {
        const auto face    = cell->face(f);
        bool       on_axis = true;
        for (const unsigned int v : face->vertex_indices())
          on_axis =
            on_axis && std::abs(face->vertex(v)[0]) <= 1e-12 * cell->diameter();
        const WallKind kind = kind_of(face->boundary_id());
        if (on_axis &&
            ((kind != WallKind::slip && kind != WallKind::fixed) ||
             ends(face->boundary_id())))
          unheld = true;
      });
    if (Utilities::MPI::logical_or(unheld, grid.get_communicator()))
      throw InputError("Grid/Geometry = axisymmetric: the grid's boundary "
                       "on the axis (x = 0) is not held for the whole "
                       "run. Name it in Boundary conditions/Slip "
                       "boundaries (the axis of symmetry: v_r = 0), or in "
                       "Fixed boundaries, without 'until'.");
  }



  template <int dim>
  void
  DirichletConditions<dim>::find_nodes() const
  {
    const auto &tria = grid.get_triangulation();

    // Every named boundary must exist somewhere in the grid.
    const std::vector<types::boundary_id> present = tria.get_boundary_ids();
    auto check = [&](const std::vector<types::boundary_id> &ids,
                     const std::vector<std::string> &       names,
                     const std::string &                    entry) {
      for (unsigned int i = 0; i < ids.size(); ++i)
        if (std::find(present.begin(), present.end(), ids[i]) ==
            present.end())
          {
            std::string list;
            for (const auto id : present)
              list += (list.empty() ? "" : ", ") + std::to_string(id);
            throw InputError(entry + " names '" + names[i] + "' (boundary id " +
                             std::to_string(ids[i]) +
                             "), but no face of the grid has that id; the "
                             "grid has ids " +
                             list +
                             ". For subdivided_hyper_rectangle, set colorize "
                             "= true in Grid/Arguments.");
          }
    };
    check(fixed_ids, fixed_names, "Boundary conditions/Fixed boundaries");
    check(slip_ids, slip_names, "Boundary conditions/Slip boundaries");
    check(contact_ids,
          contact_names,
          "Boundary conditions/Contact boundaries");

    constraint_of_node.assign(grid.n_nodes(), -1);
    constraints.clear();

    // Per boundary node: is it on a fixed face, and the sum of the outward
    // normals (weighted by face size) of its slip faces, per boundary id.
    // Faces of one id are one wall, curved or not: their normals are
    // averaged. Different ids meet at corners and each removes a direction,
    // in the order of their ids.
    const auto in = [](const std::vector<types::boundary_id> &ids,
                       const types::boundary_id               id) {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    };
    std::vector<types::boundary_id> in_force;
    for (const auto *ids : {&fixed_ids, &slip_ids, &contact_ids})
      for (const types::boundary_id id : *ids)
        {
          const auto ends = end_times.find(id);
          if (ends == end_times.end() || found_at < ends->second)
            in_force.push_back(id);
        }
    std::sort(in_force.begin(), in_force.end());
    in_force.erase(std::unique(in_force.begin(), in_force.end()),
                   in_force.end());
    struct NodeFaces
    {
      bool                                              fixed = false;
      Tensor<1, dim>                                    contact_normal;
      std::map<types::boundary_id, Tensor<1, dim>> slip_normals;
    };
    std::map<unsigned int, NodeFaces> boundary_nodes;
    const BoundaryWalls<dim>          walls(grid, in_force);
    for (const auto &entry : walls.nodes_on_walls())
      {
        const types::boundary_id id   = in_force[entry.wall];
        NodeFaces &              node = boundary_nodes[entry.node];
        if (in(fixed_ids, id))
          node.fixed = true;
        else if (in(contact_ids, id))
          node.contact_normal += entry.normal;
        else
          node.slip_normals[id] = entry.normal;
      }

    // A free contact node keeps the components along the wall, which are
    // grid components only for walls along the axes.
    bool slanted_contact = false;
    for (const auto &[node, faces] : boundary_nodes)
      {
        Constraint constraint;
        if (faces.fixed)
          constraint.n_normals = dim;
        else if (faces.contact_normal.norm() > 0.)
          {
            constraint.n_normals  = dim;
            constraint.unilateral = true;
            constraint.outward =
              faces.contact_normal / faces.contact_normal.norm();
            bool along_axis = false;
            for (unsigned int d = 0; d < dim; ++d)
              along_axis |=
                std::abs(std::abs(constraint.outward[d]) - 1.) < 1e-10;
            slanted_contact |= !along_axis;
          }
        else
          for (const auto &[id, sum] : faces.slip_normals)
            {
              // Gram-Schmidt against the walls already taken.
              Tensor<1, dim> residual = sum / sum.norm();
              for (unsigned int k = 0; k < constraint.n_normals; ++k)
                residual -=
                  (residual * constraint.normals[k]) * constraint.normals[k];
              if (residual.norm() > 1e-6 && constraint.n_normals < dim)
                constraint.normals[constraint.n_normals++] =
                  residual / residual.norm();
            }
        constraint_of_node[node] = constraints.size();
        constraints.push_back(constraint);
      }
    if (Utilities::MPI::logical_or(slanted_contact,
                                   tria.get_communicator()))
      throw InputError("Boundary conditions/Contact boundaries: a contact "
                       "wall must lie along a grid axis, and its corners "
                       "may not meet another contact wall. For an inclined "
                       "plane, tilt the gravity instead (see "
                       "prm/rolling_disk.prm).");
  }


  template <int dim>
  void
  DirichletConditions<dim>::begin_explicit_solve(const double time,
                                                 const double) const
  {
    for (const auto &[id, until] : end_times)
      if ((found_at < until) != (time < until))
        {
          found_at = time;
          find_nodes();
          return;
        }
  }



  template <int dim>
  bool
  DirichletConditions<dim>::add_constraints(
    const unsigned int                              node,
    const std::array<types::global_dof_index, dim> &dofs,
    const Hold *                                    holds,
    AffineConstraints<double> &                     constraints) const
  {
    const Constraint &constraint = *constraint_of(node);
    // A free contact node keeps no slip along the wall, which a body
    // rolling without slip satisfies on the whole line of the wall; only
    // its normal motion is free.
    const bool free_contact = constraint.unilateral && holds[0] == Hold::free;
    if (free_contact || constraint.n_normals == dim)
      {
        for (unsigned int a = 0; a < dim; ++a)
          if ((!free_contact || std::abs(constraint.outward[a]) < 0.5) &&
              !constraints.is_constrained(dofs[a]))
            constraints.add_line(dofs[a]);
        return true;
      }
    bool supported = true;
    for (unsigned int k = 0; k < constraint.n_normals; ++k)
      supported &= this->hold_along_normal(dofs,
                                           constraint.normals[k],
                                           constraint.n_normals == 1,
                                           constraints);
    return supported;
  }



  template class DirichletConditions<2>;
  template class DirichletConditions<3>;
} // namespace mpm
