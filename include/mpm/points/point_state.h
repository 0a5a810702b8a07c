#ifndef mpm_points_point_state_h
#define mpm_points_point_state_h

#include <mpm/materials/material.h>
#include <mpm/materials/plane_stress.h>
#include <mpm/points/point_layout.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The end of a step at one material point, written once for every scheme:
   * the point's law updates its stress and internal variables from the
   * step's kinematics, the stress work of the step is added, and the new F
   * and sigma are stored.
   */
  template <int dim>
  struct PointState
  {
    using Layout = PointLayout<dim>;

    /**
     * Commit the step described by `kinematics` (whose F_new must have
     * det > 0) to the point's properties `p`. In plane stress the law's
     * update is PlaneStress's, which also chooses the zz part of the step;
     * if that fails, p is left as it was and false is returned.
     */
    static bool
    commit(const std::vector<std::unique_ptr<Material>> &materials,
           StepKinematics                                kinematics,
           const ArrayView<double> &                     p,
           const bool                                    plane_stress)
    {
      const Material &material =
        *materials[static_cast<unsigned int>(p[Layout::material_id])];
      SymmetricTensor<2, 3>       stress     = Layout::get_stress(p);
      const SymmetricTensor<2, 3> stress_old = stress;
      if (!PlaneStress::update_stress(
            material,
            kinematics,
            stress,
            ArrayView<double>(&p[Layout::internal_variables],
                              material.n_internal_variables()),
            plane_stress))
        return false;

      // Stress power per reference volume, tau : D with tau = J sigma, by
      // the trapezoidal rule.
      const SymmetricTensor<2, 3> D =
        symmetrize(kinematics.velocity_gradient);
      p[Layout::work_density] += 0.5 * kinematics.dt *
                                 (determinant(kinematics.F_old) * stress_old +
                                  determinant(kinematics.F_new) * stress) *
                                 D;

      Layout::set_deformation_gradient_3d(p, kinematics.F_new);
      Layout::set_stress(p, stress);
      return true;
    }
  };
} // namespace mpm

#endif
