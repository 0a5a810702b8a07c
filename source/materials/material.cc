#include <mpm/base/input_error.h>
#include <mpm/materials/material.h>

#include <cmath>
#include <map>
#include <sstream>

namespace mpm
{
  namespace
  {
    /**
     * The registered laws by Model name. A function's static, so that it
     * exists before the first law registers itself, whichever file's
     * statics run first.
     */
    std::map<std::string, Material::Law> &
    registered_laws()
    {
      static std::map<std::string, Material::Law> laws;
      return laws;
    }
  } // namespace



  bool
  Material::register_law(const std::string &model, const Law &law)
  {
    const bool added = registered_laws().emplace(model, law).second;
    AssertThrow(added,
                ExcMessage("Two material laws are registered as '" + model +
                           "'."));
    return true;
  }



  void
  Material::declare_parameters(ParameterHandler &prm)
  {
    std::string names, documentation = "Constitutive law.";
    for (const auto &[model, law] : registered_laws())
      {
        names += (names.empty() ? "" : "|") + model;
        documentation += " '" + model + "': " + law.description;
      }
    prm.declare_entry("Model",
                      "linear elastic",
                      Patterns::Selection(names),
                      documentation);
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
    for (const auto &entry : registered_laws())
      if (entry.second.declare_parameters != nullptr)
        entry.second.declare_parameters(prm);
  }



  std::unique_ptr<Material>
  Material::create(ParameterHandler & prm,
                   const std::string &name,
                   const std::string &section_path)
  {
    const std::string model = prm.get("Model");
    const auto        law   = registered_laws().find(model);
    if (law == registered_laws().end())
      {
        std::string known;
        for (const auto &entry : registered_laws())
          known += (known.empty() ? "" : ", ") + entry.first;
        throw InputError(section_path + "/Model = '" + model +
                         "' is not a known law; use one of: " + known + ".");
      }
    return law->second.create(prm, name, section_path);
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
    // Beyond these the explicit step (a cell over the wave speed) is not a
    // physical scale: 1e300 Pa would take steps of 1e-150 s without end.
    const auto out_of_range = [&](const std::string &entry,
                                  const double       value,
                                  const std::string &unit,
                                  const std::string &range) {
      std::ostringstream message;
      message << section_path << "/" << entry << " = " << value << " " << unit
              << " lies outside what any material has (" << range
              << "); the wave speed and the explicit step follow from it.";
      return InputError(message.str());
    };
    if (youngs_modulus > 1e13 || youngs_modulus < 1e-3)
      throw out_of_range("Young's modulus",
                         youngs_modulus,
                         "Pa",
                         "give E in Pa, from 1e-3 to 1e13; diamond has 1.2e12");
    if (rho > 1e5 || rho < 1e-3)
      throw out_of_range("Density",
                         rho,
                         "kg/m^3",
                         "give it in kg/m^3, from 1e-3 to 1e5; osmium has "
                         "22,590");
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
      // The density follows the perturbed volume.
      k.density *= determinant(kinematics.F_new) / determinant(F);
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
