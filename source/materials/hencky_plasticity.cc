#include <mpm/base/input_error.h>
#include <mpm/materials/hencky_plasticity.h>
#include <mpm/materials/principal_axes.h>

#include <array>
#include <cmath>
#include <sstream>

namespace mpm
{
  namespace
  {
    /**
     * c += k A (x) B on the 6 x 6 independent entries. deal.II's
     * outer_product of two symmetric tensors goes through its index
     * accessors entry by entry, and was an eighth of an implicit
     * Mohr-Coulomb run.
     */
    void
    add_outer_product(SymmetricTensor<4, 3> &      c,
                      const double                 k,
                      const SymmetricTensor<2, 3> &A,
                      const SymmetricTensor<2, 3> &B)
    {
      constexpr unsigned int n = SymmetricTensor<2, 3>::n_independent_components;
      for (unsigned int I = 0; I < n; ++I)
        {
          const double kA = k * A.access_raw_entry(I);
          for (unsigned int J = 0; J < n; ++J)
            c.access_raw_entry(n * I + J) += kA * B.access_raw_entry(J);
        }
    }
  } // namespace



  HenckyPlasticity::HenckyPlasticity(const ParameterHandler &prm,
                                     const std::string &     name,
                                     const std::string &     section_path)
    : Material(prm, name, section_path)
  {
    internal_names = {"plastic_strain",
                      "elastic_b_minus_I_xx",
                      "elastic_b_minus_I_yy",
                      "elastic_b_minus_I_zz",
                      "elastic_b_minus_I_xy",
                      "elastic_b_minus_I_xz",
                      "elastic_b_minus_I_yz"};
    principal_compliance = invert(principal_stiffness());
  }



  Tensor<2, 3>
  HenckyPlasticity::principal_stiffness() const
  {
    Tensor<2, 3> D;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        D[a][b] = lambda + (a == b ? 2. * mu : 0.);
    return D;
  }



  HenckyPlasticity::Step
  HenckyPlasticity::compute_step(
    const StepKinematics &         kinematics,
    const ArrayView<const double> &old_internal_variables,
    const bool                     with_tangent) const
  {
    SymmetricTensor<2, 3> b_old = unit_symmetric_tensor<3>();
    for (unsigned int k = 0; k < 6; ++k)
      b_old.access_raw_entry(k) += old_internal_variables[elastic_b_minus_I + k];
    const Tensor<2, 3> f = kinematics.F_new * invert(kinematics.F_old);
    const SymmetricTensor<2, 3> b_trial =
      symmetrize(Tensor<2, 3>(f * Tensor<2, 3>(b_old) * transpose(f)));

    Step         step;
    step.b_trial = b_trial;
    Tensor<1, 3> trial_tau;
    const auto   eigen = principal_axes(b_trial);
    const Tensor<2, 3> D = principal_stiffness();
    Tensor<1, 3>       eps;
    for (unsigned int a = 0; a < 3; ++a)
      {
        step.beta[a]       = eigen[a].first;
        step.directions[a] = eigen[a].second;
        eps[a]             = 0.5 * std::log(eigen[a].first);
      }
    trial_tau   = D * eps;
    step.result =
      return_to_yield_surface(trial_tau,
                              old_internal_variables[equivalent_plastic_strain],
                              with_tangent);
    step.J = determinant(kinematics.F_new);
    return step;
  }



  void
  HenckyPlasticity::update_stress(const StepKinematics &   kinematics,
                                  SymmetricTensor<2, 3> &  stress,
                                  const ArrayView<double> &internal_variables)
    const
  {
    const Step step = compute_step(
      kinematics,
      ArrayView<const double>(internal_variables.data(),
                              internal_variables.size()),
      false);
    std::array<SymmetricTensor<2, 3>, 3> m;
    stress = 0;
    for (unsigned int a = 0; a < 3; ++a)
      {
        m[a] = symmetrize(outer_product(step.directions[a], step.directions[a]));
        stress += step.result.tau[a] / step.J * m[a];
      }
    // An elastic step keeps the trial b_e; after a return, the elastic
    // strains of the returned stress rebuild it.
    SymmetricTensor<2, 3> b_new = step.b_trial;
    if (step.result.plastic)
      {
        const Tensor<1, 3> eps_elastic =
          principal_compliance * step.result.tau;
        b_new = 0;
        for (unsigned int a = 0; a < 3; ++a)
          b_new += std::exp(2. * eps_elastic[a]) * m[a];
      }
    b_new -= unit_symmetric_tensor<3>();
    for (unsigned int k = 0; k < 6; ++k)
      internal_variables[elastic_b_minus_I + k] = b_new.access_raw_entry(k);
    internal_variables[equivalent_plastic_strain] +=
      step.result.plastic_strain_increment;
  }



  double
  HenckyPlasticity::initialize_stress(
    const SymmetricTensor<2, 3> &stress,
    const ArrayView<double> &    internal_variables,
    const std::string &          who) const
  {
    const auto eigen = principal_axes(stress);
    Tensor<1, 3> tau;
    for (unsigned int a = 0; a < 3; ++a)
      tau[a] = eigen[a].first;
    const double scale = tau.norm() + 1.;
    if (yield_function(tau, 0.) > 1e-10 * scale)
      {
        std::ostringstream message;
        message << who << ": the initial stress (principal " << tau[0]
                << ", " << tau[1] << ", " << tau[2]
                << " Pa) lies outside the yield surface of material '"
                << name() << "'; choose K0 nearer 1, or start from rest.";
        throw InputError(message.str());
      }
    const Tensor<1, 3>    eps = principal_compliance * tau;
    SymmetricTensor<2, 3> b_minus_I;
    for (unsigned int a = 0; a < 3; ++a)
      b_minus_I += (std::exp(2. * eps[a]) - 1.) *
                   symmetrize(outer_product(eigen[a].second, eigen[a].second));
    for (unsigned int k = 0; k < 6; ++k)
      internal_variables[elastic_b_minus_I + k] =
        b_minus_I.access_raw_entry(k);
    return elastic_energy_density(stress);
  }



  SymmetricTensor<4, 3>
  HenckyPlasticity::spatial_tangent(
    const StepKinematics &kinematics,
    const SymmetricTensor<2, 3> &,
    const ArrayView<const double> &old_internal_variables) const
  {
    const Step step = compute_step(kinematics, old_internal_variables, true);
    const Tensor<1, 3> &tau  = step.result.tau;
    const Tensor<2, 3> &D    = step.result.tangent;
    const Tensor<1, 3> &beta = step.beta;

    std::array<SymmetricTensor<2, 3>, 3> m;
    for (unsigned int a = 0; a < 3; ++a)
      m[a] = symmetrize(outer_product(step.directions[a], step.directions[a]));
    SymmetricTensor<4, 3> c;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        add_outer_product(c, D[a][b] - (a == b ? 2. * tau[a] : 0.), m[a], m[b]);
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = a + 1; b < 3; ++b)
        {
          // Relative to the larger stretch, equal eigenvalues take the
          // limit; below 1e-8 the difference quotient loses its digits.
          const double g =
            std::abs(beta[a] - beta[b]) <
                1e-8 * std::max(std::abs(beta[a]), std::abs(beta[b])) ?
              D[a][a] - D[a][b] - 2. * tau[a] :
              2. * (tau[a] * beta[b] - tau[b] * beta[a]) / (beta[a] - beta[b]);
          const SymmetricTensor<2, 3> s = symmetrize(
            outer_product(step.directions[a], step.directions[b]));
          add_outer_product(c, 2. * g, s, s);
        }
    return c / step.J;
  }
} // namespace mpm
