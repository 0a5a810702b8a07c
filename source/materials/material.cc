#include <mpm/core/input_error.h>
#include <mpm/materials/drucker_prager_viscoplastic.h>
#include <mpm/materials/hencky.h>
#include <mpm/materials/linear_elastic.h>
#include <mpm/materials/material.h>
#include <mpm/materials/mohr_coulomb.h>
#include <mpm/materials/neo_hookean.h>
#include <mpm/materials/von_mises.h>
#include <mpm/materials/wieckowski_granular.h>

#include <cmath>

namespace mpm
{
  void
  Material::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "linear elastic",
                      Patterns::Selection("linear elastic|neo-Hookean|Hencky|"
                                          "Mohr-Coulomb|von Mises|"
                                          "Drucker-Prager viscoplastic|"
                                          "Wieckowski granular"),
                      "Constitutive law. 'linear elastic': hypoelastic, "
                      "integrated with the Jaumann stress rate as in "
                      "Wieckowski (2004). 'neo-Hookean': compressible "
                      "hyperelastic, sigma = (mu (b - I) + lambda ln(J) I)/J. "
                      "'Hencky': hyperelastic, Kirchhoff stress linear in the "
                      "logarithmic strain. 'Mohr-Coulomb' and 'von Mises': "
                      "elastoplastic at finite strain with Hencky elasticity "
                      "(subsections of the same names). 'Drucker-Prager "
                      "viscoplastic': Wieckowski's (2004) cohesionless "
                      "Perzyna law with the Jaumann rate (its subsection). "
                      "'Wieckowski granular': his law for loose fill, eq. "
                      "(24): pressure exponential in the volume change plus "
                      "bulk viscosity, shear modulus proportional to the "
                      "pressure, deviator as 'Drucker-Prager viscoplastic' "
                      "(both subsections; Young's modulus is not used).");
    prm.declare_entry("Density",
                      "1000",
                      Patterns::Double(0.),
                      "Mass density of the undeformed material [kg/m^3].");
    prm.declare_entry("Young's modulus",
                      "1e6",
                      Patterns::Double(0.),
                      "Young's modulus E [Pa].");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Double(-1., 0.5),
                      "Poisson's ratio nu, -1 < nu < 0.5.");
    MohrCoulomb::declare_parameters(prm);
    VonMises::declare_parameters(prm);
    DruckerPragerViscoplastic::declare_parameters(prm);
    WieckowskiGranular::declare_parameters(prm);
  }



  std::unique_ptr<Material>
  Material::create(ParameterHandler & prm,
                   const std::string &name,
                   const std::string &section_path)
  {
    const std::string model = prm.get("Model");
    if (model == "linear elastic")
      return std::make_unique<LinearElastic>(prm, name, section_path);
    if (model == "neo-Hookean")
      return std::make_unique<NeoHookean>(prm, name, section_path);
    if (model == "Hencky")
      return std::make_unique<Hencky>(prm, name, section_path);
    if (model == "Mohr-Coulomb")
      return std::make_unique<MohrCoulomb>(prm, name, section_path);
    if (model == "von Mises")
      return std::make_unique<VonMises>(prm, name, section_path);
    if (model == "Drucker-Prager viscoplastic")
      return std::make_unique<DruckerPragerViscoplastic>(prm,
                                                         name,
                                                         section_path);
    if (model == "Wieckowski granular")
      return std::make_unique<WieckowskiGranular>(prm, name, section_path);
    throw InputError(section_path + "/Model = '" + model +
                     "' is not a known law; use one of: linear elastic, "
                     "neo-Hookean, Hencky, Mohr-Coulomb, von Mises, "
                     "Drucker-Prager viscoplastic, Wieckowski granular.");
  }



  Material::Material(const ParameterHandler &prm,
                     const std::string &     name,
                     const std::string &     section_path)
    : material_name(name)
    , rho(prm.get_double("Density"))
    , youngs_modulus(prm.get_double("Young's modulus"))
    , poissons_ratio(prm.get_double("Poisson's ratio"))
  {
    if (!(rho > 0.))
      throw InputError(section_path + "/Density must be positive.");
    if (!(youngs_modulus > 0.))
      throw InputError(section_path + "/Young's modulus must be positive.");
    if (!(poissons_ratio > -1. && poissons_ratio < 0.5))
      throw InputError(section_path +
                       "/Poisson's ratio must lie strictly between -1 and "
                       "0.5.");
    mu     = youngs_modulus / (2. * (1. + poissons_ratio));
    lambda = youngs_modulus * poissons_ratio /
             ((1. + poissons_ratio) * (1. - 2. * poissons_ratio));
  }



  SymmetricTensor<4, 3>
  Material::numerical_spatial_tangent(
    const StepKinematics &         kinematics,
    const SymmetricTensor<2, 3> &  old_stress,
    const ArrayView<const double> &old_internal_variables) const
  {
    const double        h = 1e-6;
    std::vector<double> internal;
    const Tensor<2, 3>  F_old_inverse = invert(kinematics.F_old);
    // Kirchhoff stress of the step from the old state to F.
    auto kirchhoff = [&](const Tensor<2, 3> &F) {
      StepKinematics k = kinematics;
      k.F_new          = F;
      k.velocity_gradient =
        (F * F_old_inverse - Tensor<2, 3>(unit_symmetric_tensor<3>())) /
        kinematics.dt;
      internal.assign(old_internal_variables.begin(),
                      old_internal_variables.end());
      SymmetricTensor<2, 3> sigma = old_stress;
      update_stress(k,
                    sigma,
                    ArrayView<double>(internal.data(), internal.size()));
      return SymmetricTensor<2, 3>(determinant(F) * sigma);
    };

    const Tensor<2, 3> &        F   = kinematics.F_new;
    const double                J   = determinant(F);
    const Tensor<2, 3>          tau = kirchhoff(F);
    SymmetricTensor<4, 3>       c;
    const Tensor<2, 3>          I = unit_symmetric_tensor<3>();
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = k; l < 3; ++l)
        {
          Tensor<2, 3> E;
          E[k][l] = E[l][k] = (k == l ? 1. : 0.5);
          const Tensor<2, 3> rate =
            Tensor<2, 3>(kirchhoff((I + h * E) * F) -
                         kirchhoff((I - h * E) * F)) /
              (2. * h) -
            E * tau - tau * E;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              c[i][j][k][l] = 0.5 * (rate[i][j] + rate[j][i]) / J;
        }
    return c;
  }



  double
  Material::initialize_stress(const SymmetricTensor<2, 3> &,
                              const ArrayView<double> &,
                              const std::string &who) const
  {
    throw InputError(who + ": material '" + name() +
                     "' is hyperelastic without internal state, so it "
                     "cannot start under stress; use a rate or plastic law "
                     "or Initial stress = none.");
  }



  double
  Material::elastic_energy_density(const SymmetricTensor<2, 3> &stress) const
  {
    const double p = trace(stress);
    return 0.5 * ((stress * stress) -
                  lambda / (3. * lambda + 2. * mu) * p * p) /
           (2. * mu);
  }



  double
  Material::p_wave_speed() const
  {
    return std::sqrt(p_wave_modulus() / rho);
  }
} // namespace mpm
