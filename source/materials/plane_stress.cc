#include <mpm/materials/plane_stress.h>

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm
{
  bool
  PlaneStress::update_stress(const Material &         material,
                             StepKinematics &         kinematics,
                             SymmetricTensor<2, 3> &  stress,
                             const ArrayView<double> &internal_variables,
                             const bool               plane_stress)
  {
    if (!plane_stress)
      {
        material.update_stress(kinematics, stress, internal_variables);
        return true;
      }
    const SymmetricTensor<2, 3> old_stress = stress;
    const boost::container::small_vector<double, 8> old_internal(
      internal_variables.begin(), internal_variables.end());
    const ArrayView<const double> old_view(old_internal.data(),
                                           old_internal.size());
    const double dt           = kinematics.dt;
    const double F_zz_old     = kinematics.F_old[2][2];
    const double p_wave       = material.p_wave_modulus();
    const double lambda       = p_wave - 2. * material.shear_modulus();
    const Tensor<2, 3> &L     = kinematics.velocity_gradient;
    double       J_given      = determinant(kinematics.F_new);

    // The step's zz part for the out-of-plane stretch s, with the density
    // following the volume.
    const auto set_stretch = [&](const double s) {
      kinematics.F_new[2][2]             = s * F_zz_old;
      kinematics.velocity_gradient[2][2] = (s - 1.) / dt;
      const double J                     = determinant(kinematics.F_new);
      kinematics.density *= J_given / J;
      J_given = J;
    };

    // A step that would thin the plate by half or more is no elastic
    // step: Newton starts from half then.
    const auto restore = [&]() {
      stress = old_stress;
      std::copy(old_internal.begin(),
                old_internal.end(),
                internal_variables.begin());
    };

    double s = std::max(
      1. - (old_stress[2][2] + dt * lambda * (L[0][0] + L[1][1])) / p_wave,
      0.5);
    // Secant steps on tau_zz(s) = J sigma_zz, the first with the elastic
    // slope: the law's full tangent costs several stress updates, and only
    // its zz-zz entry is wanted. The tangent only where the secant's slope
    // is not positive.
    double previous_s = 0., previous_tau = 0.;
    for (unsigned int iteration = 0; iteration < 30; ++iteration)
      {
        set_stretch(s);
        restore();
        material.update_stress(kinematics, stress, internal_variables);
        const double residual = stress[2][2];
        if (std::abs(residual) <= 1e-10 * stress.norm())
          return true;
        if (!std::isfinite(residual))
          break;

        const double J   = determinant(kinematics.F_new);
        const double tau = J * residual;
        double       slope =
          iteration > 0 ? (tau - previous_tau) / (s - previous_s) :
                          J * (p_wave + 2. * residual) / s;
        if (!(slope > 0.) || !std::isfinite(slope))
          {
            const SymmetricTensor<4, 3> c =
              material.spatial_tangent(kinematics, old_stress, old_view);
            slope = J * (c[2][2][2][2] + 2. * residual) / s;
          }
        if (!(slope > 0.))
          break;
        // Kept within a factor 2 a step. A correction below the round-off
        // of s leaves sigma_zz at the round-off of the update (a small
        // stress reached from a large one).
        const double correction = tau / slope;
        if (std::abs(correction) <=
            4. * std::numeric_limits<double>::epsilon() * s)
          return true;
        previous_s   = s;
        previous_tau = tau;
        s            = std::clamp(s - correction, 0.5 * s, 2. * s);
      }
    restore();
    return false;
  }



  SymmetricTensor<4, 3>
  PlaneStress::condense(const SymmetricTensor<4, 3> &c)
  {
    SymmetricTensor<4, 3> condensed;
    const double          c_zzzz = c[2][2][2][2];
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = i; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = k; l < 2; ++l)
            condensed[i][j][k][l] =
              c[i][j][k][l] - c[i][j][2][2] * c[2][2][k][l] / c_zzzz;
    return condensed;
  }
} // namespace mpm
