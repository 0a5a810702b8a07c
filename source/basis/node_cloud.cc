#include <mpm/basis/node_cloud.h>
#include <mpm/base/input_error.h>

#include <map>

namespace mpm
{
  template <int dim>
  NodeCloud<dim>::NodeCloud(const MaterialPoints<dim> &      points,
                            const Grid<dim> &                grid,
                            const DirichletConditions<dim> & dirichlet)
    : nodal_spacing(grid.minimum_cell_size())
  {
    std::map<unsigned int, unsigned int> node_of_vertex;
    for (const auto &cell : points.get_triangulation().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            points.handler().n_particles_in_cell(cell) == 0)
          continue;
        for (const unsigned int v : cell->vertex_indices())
          if (node_of_vertex.emplace(cell->vertex_index(v), positions.size())
                .second)
            {
              positions.push_back(cell->vertex(v));
              // A copy: the grid's conditions are rebuilt when it changes,
              // and the cloud's nodes keep theirs. No condition: no normals.
              const Condition *condition = dirichlet.constraint_of(
                grid.node_of(cell->active_cell_index(), v));
              conditions.push_back(condition != nullptr ? *condition :
                                                          Condition());
            }
      }
    velocities.resize(positions.size());
    accelerations.resize(positions.size());

    // The walls, from the boundary faces that carry a condition.
    using Kind = typename DirichletConditions<dim>::WallKind;
    for (const auto &cell : points.get_triangulation().active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->at_boundary(f))
              continue;
            const Kind kind = dirichlet.kind_of(cell->face(f)->boundary_id());
            if (kind == Kind::none)
              continue;
            const Tensor<1, dim> outward =
              cell->face(f)->center() - cell->center();
            unsigned int axis = 0;
            for (unsigned int d = 1; d < dim; ++d)
              if (std::abs(outward[d]) > std::abs(outward[axis]))
                axis = d;
            Tensor<1, dim> normal;
            normal[axis] = outward[axis] > 0. ? 1. : -1.;
            if ((outward - (outward * normal) * normal).norm() >
                1e-10 * outward.norm())
              throw InputError("Boundary conditions: the meshfree methods "
                               "support walls along the grid axes only.");
            const double offset = normal * cell->face(f)->center();
            bool         known  = false;
            for (const Wall &wall : walls)
              if (wall.axis == axis && wall.outward * normal > 0. &&
                  std::abs(wall.offset - offset) < 1e-10 * nodal_spacing)
                {
                  // Walls are planes here; one plane with two conditions
                  // would need the extent of each.
                  if (wall.kind != kind)
                    throw InputError(
                      "Boundary conditions: the meshfree methods need one "
                      "condition per plane of the grid's boundary; a plane "
                      "carries two.");
                  known = true;
                }
            if (!known)
              walls.push_back({normal, offset, axis, kind});
          }
      }

    AssertThrow(walls.size() <= 32, ExcMessage("More than 32 walls."));
    for (unsigned int i = 0; i < size(); ++i)
      held_components(i); // refuses slanted walls now, not mid-run
  }



  template <int dim>
  std::array<bool, dim>
  NodeCloud<dim>::held_components(const unsigned int i) const
  {
    std::array<bool, dim> held{};
    for (unsigned int w = 0; w < walls.size(); ++w)
      if (is_held_by(i, w))
        {
          if (walls[w].kind == DirichletConditions<dim>::WallKind::slip)
            held[walls[w].axis] = true;
          else
            held.fill(true);
        }
    const Condition *condition = &conditions[i];
    if (condition->n_normals == 0 || condition->unilateral)
      return held;
    if (condition->n_normals == dim)
      {
        held.fill(true);
        return held;
      }
    for (unsigned int k = 0; k < condition->n_normals; ++k)
      {
        bool along_axis = false;
        for (unsigned int a = 0; a < dim; ++a)
          if (std::abs(std::abs(condition->normals[k][a]) - 1.) < 1e-10)
            {
              held[a]    = true;
              along_axis = true;
            }
        if (!along_axis)
          throw InputError("Boundary conditions: the meshfree methods "
                           "support slip walls along the grid axes only; "
                           "material starts on a slanted one.");
      }
    return held;
  }



  template class NodeCloud<2>;
  template class NodeCloud<3>;
} // namespace mpm
