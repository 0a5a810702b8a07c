#include <deal.II/base/mpi.h>

#include <mpm/basis/node_cloud.h>
#include <mpm/base/input_error.h>
#include <mpm/boundary/boundary_walls.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace mpm
{
  template <int dim>
  NodeCloud<dim>::NodeCloud(const MaterialPoints<dim> &      points,
                            const Grid<dim> &                grid,
                            const DirichletConditions<dim> & dirichlet)
    : nodal_spacing(grid.minimum_cell_size())
  {
    // Each rank finds the vertices of its own cells and the boundary
    // faces among them; every rank then holds the whole cloud.
    std::vector<double>                  local_nodes, local_walls;
    std::map<unsigned int, unsigned int> node_of_vertex;
    for (const auto &cell : points.get_triangulation().active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            points.handler().n_particles_in_cell(cell) == 0)
          continue;
        for (const unsigned int v : cell->vertex_indices())
          if (node_of_vertex.emplace(cell->vertex_index(v), 0).second)
            {
              // A copy: the grid's conditions are rebuilt when it changes,
              // and the cloud's nodes keep theirs. No condition: no normals.
              const Condition *condition = dirichlet.constraint_of(
                grid.node_of(cell->active_cell_index(), v));
              pack_node(cell->vertex(v),
                        condition != nullptr ? *condition : Condition(),
                        local_nodes);
            }
      }

    using Kind = typename DirichletConditions<dim>::WallKind;
    BoundaryWalls<dim>::for_each_boundary_face(
      grid, true, [&](const auto &cell, const unsigned int f) {
        const Kind kind = dirichlet.kind_of(cell->face(f)->boundary_id());
        if (kind == Kind::none)
          return;
        const Tensor<1, dim> outward = cell->face(f)->center() - cell->center();
        for (unsigned int d = 0; d < dim; ++d)
          local_walls.push_back(outward[d]);
        for (unsigned int d = 0; d < dim; ++d)
          local_walls.push_back(cell->face(f)->center()[d]);
        local_walls.push_back(static_cast<double>(kind));
      });

    const MPI_Comm communicator = points.get_communicator();
    const auto     all_nodes =
      Utilities::MPI::all_gather(communicator, local_nodes);
    const auto all_walls =
      Utilities::MPI::all_gather(communicator, local_walls);
    const bool several_ranks = all_nodes.size() > 1;

    // One rank keeps the order of its cells. On several ranks the order in
    // which they report depends on the partition, which a continued run
    // may not have at this point: the nodes are ordered by position.
    std::map<Point<dim>, Condition, LexicographicLess> by_position;
    for (const std::vector<double> &nodes : all_nodes)
      for (unsigned int k = 0; k < nodes.size(); k += node_record_size)
        {
          Point<dim> x;
          Condition  condition;
          unpack_node(&nodes[k], x, condition);
          if (several_ranks)
            by_position.emplace(x, condition);
          else
            {
              positions.push_back(x);
              conditions.push_back(condition);
            }
        }
    for (const auto &[x, condition] : by_position)
      {
        positions.push_back(x);
        conditions.push_back(condition);
      }
    velocities.resize(positions.size());
    accelerations.resize(positions.size());

    // The walls, from the boundary faces that carry a condition.
    constexpr unsigned int wall_record_size = 2 * dim + 1;
    for (const std::vector<double> &faces : all_walls)
      for (unsigned int k = 0; k < faces.size(); k += wall_record_size)
        {
          Tensor<1, dim> outward;
          Point<dim>     center;
          for (unsigned int d = 0; d < dim; ++d)
            {
              outward[d] = faces[k + d];
              center[d]  = faces[k + dim + d];
            }
          add_wall(outward,
                   center,
                   static_cast<Kind>(std::lround(faces[k + 2 * dim])));
        }
    if (several_ranks)
      std::sort(walls.begin(), walls.end(), [](const Wall &a, const Wall &b) {
        return std::make_tuple(a.axis, a.outward[a.axis], a.offset) <
               std::make_tuple(b.axis, b.outward[b.axis], b.offset);
      });

    AssertThrow(walls.size() <= 32, ExcMessage("More than 32 walls."));
    for (unsigned int i = 0; i < size(); ++i)
      held_components(i); // refuses slanted walls now, not mid-run
  }



  template <int dim>
  void
  NodeCloud<dim>::add_wall(
    const Tensor<1, dim> &                      outward,
    const Point<dim> &                          face_center,
    const typename DirichletConditions<dim>::WallKind kind)
  {
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
    const double offset = normal * face_center;
    for (const Wall &wall : walls)
      if (wall.axis == axis && wall.outward * normal > 0. &&
          std::abs(wall.offset - offset) < 1e-10 * nodal_spacing)
        {
          // Walls are planes here; one plane with two conditions would
          // need the extent of each.
          if (wall.kind != kind)
            throw InputError("Boundary conditions: the meshfree methods "
                             "need one condition per plane of the grid's "
                             "boundary; a plane carries two.");
          return;
        }
    walls.push_back({normal, offset, axis, kind});
  }



  template <int dim>
  void
  NodeCloud<dim>::pack_node(const Point<dim> &   x,
                            const Condition &    condition,
                            std::vector<double> &record)
  {
    for (unsigned int d = 0; d < dim; ++d)
      record.push_back(x[d]);
    record.push_back(condition.n_normals);
    record.push_back(condition.unilateral ? 1. : 0.);
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int d = 0; d < dim; ++d)
        record.push_back(condition.normals[k][d]);
    for (unsigned int d = 0; d < dim; ++d)
      record.push_back(condition.outward[d]);
  }



  template <int dim>
  void
  NodeCloud<dim>::unpack_node(const double *record,
                              Point<dim> &  x,
                              Condition &   condition)
  {
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = *record++;
    condition.n_normals  = static_cast<unsigned int>(*record++);
    condition.unilateral = *record++ == 1.;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int d = 0; d < dim; ++d)
        condition.normals[k][d] = *record++;
    for (unsigned int d = 0; d < dim; ++d)
      condition.outward[d] = *record++;
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
