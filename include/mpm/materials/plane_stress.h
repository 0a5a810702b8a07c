#ifndef mpm_materials_plane_stress_h
#define mpm_materials_plane_stress_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/material.h>

namespace mpm
{
  using namespace dealii;

  /**
   * Plane stress at one material point, for every law: the step's
   * out-of-plane stretch s = F_zz,new / F_zz,old is the one for which the
   * law's own update gives sigma_zz = 0. The law does not know it is in a
   * plate; it sees a 3x3 step whose zz part is chosen for it.
   *
   * The first guess is the hypoelastic closed form, L_zz = -(sigma_zz,old /
   * dt + lambda (L_xx + L_yy)) / (lambda + 2 mu), exact for the Jaumann
   * laws in an elastic step (the in-plane spin leaves sigma_zz alone), so
   * these take one evaluation; it is kept at s >= 1/2, and Newton keeps s
   * within a factor 2 a step, so s stays positive. Otherwise a scalar Newton on s follows, with
   * the law's own consistent tangent: perturbing F_new by (I + h e_z e_z)
   * changes tau_zz by (c_tau_zzzz + 2 tau_zz) h, so d tau_zz / ds =
   * J (c_zzzz + 2 sigma_zz) / s.
   *
   * The implicit schemes condense the law's tangent on the zz direction:
   * with sigma_zz = 0 held, d_zz = -c_zz:d / c_zzzz.
   */
  class PlaneStress
  {
  public:
    /**
     * The law's update of one point's step, the one call of every scheme:
     * in plane stress (`plane_stress`) with sigma_zz = 0, choosing the zz
     * parts of kinematics.F_new and of its velocity gradient (and scaling
     * its density, if given, to the new volume); otherwise the law's own
     * update. Returns false, with `stress` and `internal_variables` as
     * they came in, if Newton does not bring |sigma_zz| below 1e-10 of
     * the stress in 30 iterations.
     */
    static bool
    update_stress(const Material &         material,
                  StepKinematics &         kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables,
                  const bool               plane_stress);

    /**
     * The in-plane tangent with sigma_zz = 0 held: c_ijkl - c_ijzz c_zzkl
     * / c_zzzz for in-plane ijkl, zero where an index is z.
     */
    static SymmetricTensor<4, 3>
    condense(const SymmetricTensor<4, 3> &c);
  };
} // namespace mpm

#endif
