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



    /**
     * The row and column of each independent entry of a
     * SymmetricTensor<2, 3>, in deal.II's order: written through its raw
     * entries, the two functions below avoid its index accessors.
     */
    constexpr unsigned int row[6]    = {0, 1, 2, 0, 0, 1};
    constexpr unsigned int column[6] = {0, 1, 2, 1, 2, 2};



    /**
     * f b f^T of a symmetric b, only the 6 independent entries of the
     * result worked out. deal.II's general contractions and symmetrize()
     * were a fifth of an explicit plastic step.
     */
    SymmetricTensor<2, 3>
    push_forward(const Tensor<2, 3> &f, const SymmetricTensor<2, 3> &b)
    {
      // In 2D scenes z is an axis of both (f = I + dt L, L in plane but
      // for L_zz): the in-plane block and zz alone, each entry summed as
      // below but for the zero terms.
      if (f[0][2] == 0. && f[1][2] == 0. && f[2][0] == 0. && f[2][1] == 0. &&
          b.access_raw_entry(4) == 0. && b.access_raw_entry(5) == 0.)
        {
          const double b_xx = b.access_raw_entry(0),
                       b_yy = b.access_raw_entry(1),
                       b_xy = b.access_raw_entry(3);
          const double fb00 = f[0][0] * b_xx + f[0][1] * b_xy;
          const double fb01 = f[0][0] * b_xy + f[0][1] * b_yy;
          const double fb10 = f[1][0] * b_xx + f[1][1] * b_xy;
          const double fb11 = f[1][0] * b_xy + f[1][1] * b_yy;
          SymmetricTensor<2, 3> result;
          result.access_raw_entry(0) = fb00 * f[0][0] + fb01 * f[0][1];
          result.access_raw_entry(1) = fb10 * f[1][0] + fb11 * f[1][1];
          result.access_raw_entry(2) =
            f[2][2] * b.access_raw_entry(2) * f[2][2];
          result.access_raw_entry(3) = fb00 * f[1][0] + fb01 * f[1][1];
          return result;
        }
      const Tensor<2, 3> full(b);
      Tensor<2, 3>       fb;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          fb[i][j] = f[i][0] * full[0][j] + f[i][1] * full[1][j] +
                     f[i][2] * full[2][j];
      SymmetricTensor<2, 3> result;
      for (unsigned int k = 0; k < 6; ++k)
        {
          const unsigned int i = row[k], j = column[k];
          result.access_raw_entry(k) =
            fb[i][0] * f[j][0] + fb[i][1] * f[j][1] + fb[i][2] * f[j][2];
        }
      return result;
    }



    /**
     * sum_a v_a n_a (x) n_a, entry by entry (no outer products). In 2D
     * scenes one axis is z exactly (principal_axes): the in-plane block
     * from the other two, zz from it, each entry summed as below but for
     * the zero terms.
     */
    SymmetricTensor<2, 3>
    from_principal(const Tensor<1, 3> &                v,
                   const std::array<Tensor<1, 3>, 3> &n)
    {
      SymmetricTensor<2, 3> t;
      for (unsigned int z = 0; z < 3; ++z)
        if (n[z][0] == 0. && n[z][1] == 0. && n[z][2] == 1.)
          {
            const unsigned int p = (z == 0 ? 1 : 0), q = (z == 2 ? 1 : 2);
            if (n[p][2] != 0. || n[q][2] != 0.)
              break;
            const Tensor<1, 3> &np = n[p], &nq = n[q];
            t.access_raw_entry(0) =
              v[p] * (np[0] * np[0]) + v[q] * (nq[0] * nq[0]);
            t.access_raw_entry(1) =
              v[p] * (np[1] * np[1]) + v[q] * (nq[1] * nq[1]);
            t.access_raw_entry(2) = v[z];
            t.access_raw_entry(3) =
              v[p] * (np[0] * np[1]) + v[q] * (nq[0] * nq[1]);
            return t;
          }
      for (unsigned int k = 0; k < 6; ++k)
        {
          const unsigned int i = row[k], j = column[k];
          t.access_raw_entry(k) = v[0] * (n[0][i] * n[0][j]) +
                                  v[1] * (n[1][i] * n[1][j]) +
                                  v[2] * (n[2][i] * n[2][j]);
        }
      return t;
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
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        principal_stiffness[a][b] = lambda + (a == b ? 2. * mu : 0.);
    principal_compliance = invert(principal_stiffness);
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
    // The step's relative deformation gradient f = F_new F_old^-1, which
    // the kinematics give as I + dt L (no inverse).
    const Tensor<2, 3> f = Tensor<2, 3>(unit_symmetric_tensor<3>()) +
                           kinematics.dt * kinematics.velocity_gradient;
    Assert((f * kinematics.F_old - kinematics.F_new).norm() <=
             1e-8 * kinematics.F_new.norm(),
           ExcMessage("StepKinematics: F_new is not (I + dt L) F_old."));

    Step step;
    step.b_trial     = push_forward(f, b_old);
    const auto eigen = principal_axes(step.b_trial);
    Tensor<1, 3> eps;
    for (unsigned int a = 0; a < 3; ++a)
      {
        step.beta[a]       = eigen[a].first;
        step.directions[a] = eigen[a].second;
        eps[a]             = 0.5 * std::log(eigen[a].first);
      }
    const Tensor<1, 3> trial_tau = principal_stiffness * eps;
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
    stress = from_principal(step.result.tau / step.J, step.directions);
    // An elastic step keeps the trial b_e; after a return, the elastic
    // strains of the returned stress rebuild it.
    SymmetricTensor<2, 3> b_new = step.b_trial;
    if (step.result.plastic)
      {
        // Equal elastic strains (a return to an edge or to the apex, at
        // zero strain on a cohesionless apex) share their exponential.
        const Tensor<1, 3> strain = principal_compliance * step.result.tau;
        Tensor<1, 3>       stretch;
        for (unsigned int a = 0; a < 3; ++a)
          stretch[a] = a > 0 && strain[a] == strain[a - 1] ?
                         stretch[a - 1] :
                         std::exp(2. * strain[a]);
        b_new = from_principal(stretch, step.directions);
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
    Tensor<1, 3>                stretch_minus_1 = principal_compliance * tau;
    std::array<Tensor<1, 3>, 3> directions;
    for (unsigned int a = 0; a < 3; ++a)
      {
        stretch_minus_1[a] = std::expm1(2. * stretch_minus_1[a]);
        directions[a]      = eigen[a].second;
      }
    const SymmetricTensor<2, 3> b_minus_I =
      from_principal(stretch_minus_1, directions);
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
