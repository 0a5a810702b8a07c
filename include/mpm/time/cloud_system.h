#ifndef mpm_time_cloud_system_h
#define mpm_time_cloud_system_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <mpm/basis/meshfree_basis.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/time/implicit_system.h>
#include <mpm/time/newmark.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The unknowns of the Galerkin meshfree method ([I] Algorithm 2): those
   * of a NodeCloud, whose nodes move with the solution and keep their
   * velocity and acceleration as history; one group per point, its
   * support from MLS or LME shape functions; the walls held on the nodes
   * that start on them or that the material brings to them.
   */
  template <int dim>
  class CloudSystem : public ImplicitSystem<dim>
  {
  public:
    CloudSystem(MaterialPoints<dim> &               points,
                const Grid<dim> &                   grid,
                const DirichletConditions<dim> &    dirichlet,
                std::unique_ptr<MeshfreeBasis<dim>> meshfree,
                const Newmark &                     newmark,
                ConditionalOStream &                pcout,
                TimerOutput &                       timer);

    void
    setup(ImplicitState<dim> &state) override;

    /** The nodes' own v and a once they have them ([I] Algorithm 2). */
    void
    project_initial_conditions(ImplicitState<dim> &state) override;

    bool
    has_active_set() const override
    {
      return !cloud.walls.empty();
    }

    bool
    update_active_set(ImplicitState<dim> &state) override;

    void
    remember_active_set() override
    {
      cloud.held_by_walls.remember();
    }

    void
    restore_active_set() override
    {
      cloud.held_by_walls.restore();
    }

    /** The nodes take the step's displacement and Newmark update. */
    void
    finish_step(const ImplicitState<dim> &state) override;

    /** The nodes and the meshfree counters. */
    void
    save(boost::archive::binary_oarchive &archive) const override
    {
      archive << cloud << *meshfree;
    }

    void
    load(boost::archive::binary_iarchive &archive) override
    {
      archive >> cloud >> *meshfree;
    }

    const NodeCloud<dim> *
    node_cloud() const override
    {
      return &cloud;
    }

    const MeshfreeBasis<dim> *
    meshfree_basis() const override
    {
      return meshfree.get();
    }

  private:
    /** The pattern of the points' supports under the constraints. */
    DynamicSparsityPattern
    sparsity_pattern(const ImplicitState<dim> &state) const;

    /**
     * Conditions on the held nodes. LME interpolates on the boundary of
     * the cloud's hull (weak Kronecker delta), so the held components of
     * those nodes are set to zero. MLS does not: there the interpolated
     * displacement at each held node, sum_j N_j(x_d) u_j, is set to zero,
     * which ties the held nodes' values to their free neighbours.
     */
    void
    make_constraints(ImplicitState<dim> &state);

    std::unique_ptr<MeshfreeBasis<dim>> meshfree;
    NodeCloud<dim>                      cloud;
    /**
     * Per node, the lowest rank whose points reach it in this step (the
     * owner of its unknowns), or the number of ranks if none does.
     */
    std::vector<unsigned int> reaching_rank;
    const Newmark &                     newmark;
    ConditionalOStream &                pcout;
    TimerOutput &                       timer;
  };
} // namespace mpm

#endif
