#ifndef mpm_time_implicit_system_h
#define mpm_time_implicit_system_h

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <mpm/basis/meshfree_basis.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/points/material_points.h>
#include <mpm/time/implicit_state.h>

#include <cmath>

namespace mpm
{
  using namespace dealii;

  /**
   * Where the unknowns of an implicit step live: on the background grid
   * (GridSystem, MPM) or on the node cloud of the meshfree method
   * (CloudSystem). A system numbers the unknowns of each step, groups the
   * points by the unknowns their supports touch, imposes the walls as
   * constraints (with the active set of walls that hold the material only
   * while it presses) and gives the nodal velocity and acceleration at the
   * step's start. Assembly, Newton, Newmark and the point update see only
   * the ImplicitState it fills, never which system filled it.
   */
  template <int dim>
  class ImplicitSystem
  {
  public:
    virtual ~ImplicitSystem() = default;

    /**
     * The unknowns, the groups with their supports at the start of the
     * step, the constraints and the matrix pattern of a new step.
     */
    virtual void
    setup(ImplicitState<dim> &state) = 0;

    /**
     * Dynamic runs: the nodal velocity and acceleration at the step's
     * start, under the constraints (state.velocity_ghosted and
     * state.acceleration_ghosted). By default projected from the points.
     */
    virtual void
    project_initial_conditions(ImplicitState<dim> &state);

    /** Whether some wall holds the material only while it presses. */
    virtual bool
    has_active_set() const = 0;

    /**
     * After a converged solve: release held nodes whose wall force pulls
     * and engage free ones where material closes on a wall, each at most
     * once a step; then the constraints of the new set. Returns whether the
     * set changed (on any rank).
     */
    virtual bool
    update_active_set(ImplicitState<dim> &state) = 0;

    /** Keep the active set as it is, to put it back if the step fails. */
    virtual void
    remember_active_set() = 0;

    virtual void
    restore_active_set() = 0;

    /** After the step converged: the nodes that move take the step. */
    virtual void
    finish_step(const ImplicitState<dim> &)
    {}

    /** The state carried from step to step, for Checkpoint. */
    virtual void
    save(boost::archive::binary_oarchive &archive) const = 0;

    virtual void
    load(boost::archive::binary_iarchive &archive) = 0;

    /** The meshfree nodes, or nullptr for MPM. */
    virtual const NodeCloud<dim> *
    node_cloud() const
    {
      return nullptr;
    }

    /** The meshfree basis, or nullptr for MPM. */
    virtual const MeshfreeBasis<dim> *
    meshfree_basis() const
    {
      return nullptr;
    }

  protected:
    explicit ImplicitSystem(MaterialPoints<dim> &points)
      : points(points)
    {}

    /**
     * How far the material of a point at x reaches beyond it, half its
     * spacing: the distance at which a wall holds it. The spacing comes
     * from the point's area: in an axisymmetric scene its ring volume over
     * 2 pi x, in plane stress its volume over its thickness.
     */
    double
    reach_of(const ArrayView<const double> &p, const Point<dim> &x) const
    {
      using Layout = PointLayout<dim>;
      const Grid<dim> &grid = points.get_grid();
      return 0.5 * std::pow(grid.geometry().volume_at_initial_thickness(
                              Layout::current_volume(p) /
                                grid.geometry().out_of_plane_measure(x),
                              dim == 2 ? p[Layout::out_of_plane_stretch] :
                                         1.),
                            1. / dim);
    }

    /**
     * Whether a wall node, `to_node` away from a point on a wall with
     * unit normal `outward`, stands for the stretch of the wall that the
     * point touches: along each axis within half the node spacing
     * `spacing[a]` of it. A node stands for the wall up to half a spacing
     * on either side (as its lumped mass stands for half a cell of
     * material), so a disk that rolls pivots on the node nearest to where
     * it touches, not on one up to a spacing ahead, which would hold it
     * back by that lever arm. Contact walls are axis-aligned.
     */
    static bool
    on_node_stretch(const Tensor<1, dim> &to_node,
                    const Tensor<1, dim> &outward,
                    const Tensor<1, dim> &spacing)
    {
      const Tensor<1, dim> along = to_node - (to_node * outward) * outward;
      for (unsigned int a = 0; a < dim; ++a)
        if (std::abs(along[a]) > (0.5 + 1e-9) * spacing[a])
          return false;
      return true;
    }

    MaterialPoints<dim> &points;
  };
} // namespace mpm

#endif
