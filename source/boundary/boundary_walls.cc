#include <mpm/boundary/boundary_walls.h>

#include <algorithm>
#include <map>

namespace mpm
{
  template <int dim>
  BoundaryWalls<dim>::BoundaryWalls(const Grid<dim> &                      grid,
                                    const std::vector<types::boundary_id> &ids)
    : owned_normal_sums(ids.size())
  {
    // Each boundary face belongs to one cell, and every cell around a node
    // of this rank's cells is owned or ghost here.
    std::map<std::pair<unsigned int, unsigned int>, NodeOnWall> found;
    for_each_boundary_face(grid, false, [&](const auto &cell, const unsigned int f) {
      const auto face = cell->face(f);
      const auto wall = std::find(ids.begin(), ids.end(), face->boundary_id());
      if (wall == ids.end())
        return;
      const unsigned int   w      = wall - ids.begin();
      const Tensor<1, dim> normal = Grid<dim>::face_normal(cell, f);
      if (cell->is_locally_owned())
        owned_normal_sums[w] += normal;
      for (const unsigned int v : face->vertex_indices())
        {
          const unsigned int node = grid.node_of_dof(face->vertex_dof_index(v, 0));
          NodeOnWall &entry = found[{node, w}];
          entry.node        = node;
          entry.wall        = w;
          entry.normal += normal;
          // int N_v dA over the face; in axisymmetry over the surface of
          // revolution, 2 pi L (2 x_v + x_other) / 6 on a segment; in plane
          // stress over the plate's initial thickness.
          double share = face->measure() / face->n_vertices();
          if (dim == 2)
            share *= grid.geometry().out_of_plane_measure(
              Point<dim>((2. * face->vertex(v) + face->vertex(1 - v)) / 3.));
          entry.share += share;
          entry.position = face->vertex(v);
        }
    });
    entries.reserve(found.size());
    for (const auto &[key, entry] : found)
      entries.push_back(entry);
  }



  template class BoundaryWalls<2>;
  template class BoundaryWalls<3>;
} // namespace mpm
