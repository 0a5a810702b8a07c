#ifndef mpm_time_implicit_assembler_h
#define mpm_time_implicit_assembler_h

#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>

#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>
#include <mpm/time/implicit_state.h>
#include <mpm/time/newmark.h>

#include <memory>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The residual f_ext - f_int (- inertia) and the tangent of an implicit
   * step, point by point through PointAssembly, for whichever basis made
   * the groups of the ImplicitState: MPM and the meshfree method share it.
   */
  template <int dim>
  class ImplicitAssembler
  {
  public:
    ImplicitAssembler(const MaterialPoints<dim> &                   points,
                      const std::vector<std::unique_ptr<Material>> &materials,
                      const Tensor<1, dim> &                        gravity,
                      const Newmark &                               newmark);

    /**
     * Residual f_ext - f_int into state.residual (f_ext into
     * state.correction, for the force scale), and the tangent if asked,
     * with the Coulomb force of the walls where nodes slide on them. A
     * point inverted by the iterate throws RunError.
     */
    void
    assemble(ImplicitState<dim> &state,
             const double        load_factor,
             const bool          with_tangent);

    /**
     * What the law sees of a step of the point with properties p by the
     * deformation increment dF from its F_n, with hoop_increment as its
     * zz part (see hoop_increment()): F_new = dF F_n, the velocity
     * gradient L = (dF - I) / dt over the step (or load step, in
     * pseudo-time), so rate laws see their rate, and the density at F_new.
     */
    static StepKinematics
    step_kinematics(const Tensor<2, dim> &         dF,
                    const double                   hoop_increment,
                    const ArrayView<const double> &p,
                    const double                   dt)
    {
      using Layout               = PointLayout<dim>;
      const Tensor<2, 3> dF_3d   = Layout::embed(dF, hoop_increment);
      StepKinematics     k;
      k.F_old             = Layout::get_deformation_gradient_3d(p);
      k.F_new             = dF_3d * k.F_old;
      k.dt                = dt;
      k.velocity_gradient =
        (dF_3d - Tensor<2, 3>(unit_symmetric_tensor<3>())) / dt;
      k.density = p[Layout::mass] / Layout::current_volume(p, k.F_new);
      return k;
    }

    /**
     * The out-of-plane part of a point's step: in an axisymmetric scene the
     * hoop stretch r / r_n = 1 + u_r / r_n, with u_r the radial
     * displacement at the point, which starts the step at `position`; 1
     * otherwise.
     */
    static double
    hoop_increment(const Geometry<dim> &               geometry,
                   const Support<dim> &               support,
                   const std::vector<Tensor<1, dim>> &du,
                   const Point<dim> &                 position)
    {
      return 1. + geometry.hoop_ratio(position, [&]() {
               double u_r = 0.;
               for (unsigned int i = 0; i < support.n_nodes; ++i)
                 u_r += support.N[i] * du[i][0];
               return u_r;
             });
    }

  private:
    /**
     * Where nodes of the group slide on walls with friction
     * (state.sliding_nodes): the wall resists with mu N along the slide,
     * N the force the material presses with, n . r of the node's rows
     * before constraints. Its derivative -mu s n . dr/du goes into the
     * node's rows of the group's tangent, so Newton stays quadratic (and
     * the tangent unsymmetric).
     */
    void
    add_friction_tangent(const ImplicitState<dim> &                  state,
                         const std::vector<types::global_dof_index> &dofs,
                         FullMatrix<double> &cell_tangent) const;

    /** The force mu N of each sliding node, once all groups are in. */
    void
    add_friction_forces(ImplicitState<dim> &state) const;

    /**
     * Add a group's matrix into the tangent when all its dofs are owned
     * here and unconstrained, and return true; otherwise leave it to
     * AffineConstraints and return false. Epetra's SumIntoGlobalValues
     * maps and searches every entry: with the meshfree supports (48 x 48
     * entries a point for LME 1.8) that was most of an assembly. Here each
     * column is mapped once, and each row is searched in one sweep.
     */
    bool
    add_to_tangent(ImplicitState<dim> &                        state,
                   const std::vector<types::global_dof_index> &dofs,
                   const FullMatrix<double> &                  matrix);

    const MaterialPoints<dim> &                   points;
    const std::vector<std::unique_ptr<Material>> &materials;
    const Tensor<1, dim>                          gravity;
    const Newmark &                               newmark;

    /**
     * Scratch of add_to_tangent: a group's local columns, sorted, and
     * where each of them sits in the current row.
     */
    std::vector<std::pair<int, unsigned int>> tangent_columns;
    std::vector<int>                          tangent_offsets;
  };
} // namespace mpm

#endif
