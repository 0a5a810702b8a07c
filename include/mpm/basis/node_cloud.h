#ifndef mpm_basis_node_cloud_h
#define mpm_basis_node_cloud_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/points/material_points.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The nodes of the Galerkin meshfree method (Iaconeta et al. 2017,
   * Algorithm 2). They start at the background grid vertices of the cells
   * that hold material, each with the grid condition of its vertex, and
   * from then on move with the solution and keep their velocity and
   * acceleration from step to step, as finite element nodes do; the grid
   * is only the frame that holds the points.
   *
   * Contact boundaries of the grid hold nodes without slip where the
   * material reaches them, until the wall pulls (the integrator's active
   * set).
   */
  template <int dim>
  class NodeCloud
  {
  public:
    using Condition = typename DirichletConditions<dim>::Constraint;

    NodeCloud(const MaterialPoints<dim> &      points,
              const GridBasis<dim> &           basis,
              const DirichletConditions<dim> & dirichlet);

    unsigned int
    size() const
    {
      return positions.size();
    }

    /** The grid's smallest cell edge: the nodal spacing h. */
    double
    spacing() const
    {
      return nodal_spacing;
    }

    /**
     * The components of node i that a condition holds: all of them if the
     * node is engaged with a contact wall or sits on a fixed wall, and
     * component a on a slip wall whose normal is axis a. Throws InputError
     * for slanted slip walls, which the meshfree method does not support.
     */
    std::array<bool, dim>
    held_components(const unsigned int i) const;

    /** A contact boundary of the grid: the plane outward . x = offset. */
    struct ContactWall
    {
      Tensor<1, dim> outward;
      double         offset;
    };

    std::vector<Point<dim>>     positions;
    std::vector<Tensor<1, dim>> velocities;
    std::vector<Tensor<1, dim>> accelerations;
    /** The grid condition of each node's starting vertex, or nullptr. */
    std::vector<const Condition *> conditions;
    /** False until the nodes have taken v and a from the points. */
    bool has_history = false;

    std::vector<ContactWall> contact_walls;
    /**
     * Per node, the contact wall that holds it (no slip, as the grid's
     * contact nodes), or -1 if it is free. Kept from step to step.
     */
    std::vector<int> engaged_wall;

  private:
    double nodal_spacing;
  };
} // namespace mpm

#endif
