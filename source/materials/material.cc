#include <mpm/core/input_error.h>
#include <mpm/materials/linear_elastic.h>
#include <mpm/materials/material.h>
#include <mpm/materials/neo_hookean.h>

#include <cmath>

namespace mpm
{
  void
  Material::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "linear elastic",
                      Patterns::Selection("linear elastic|neo-Hookean"),
                      "Constitutive law. 'linear elastic': hypoelastic, "
                      "integrated with the Jaumann stress rate as in "
                      "Wieckowski (2004). 'neo-Hookean': compressible "
                      "hyperelastic, sigma = (mu (b - I) + lambda ln(J) I)/J.");
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
  }



  std::unique_ptr<Material>
  Material::create(const ParameterHandler &prm,
                   const std::string &     name,
                   const std::string &     section_path)
  {
    const std::string model = prm.get("Model");
    if (model == "linear elastic")
      return std::make_unique<LinearElastic>(prm, name, section_path);
    if (model == "neo-Hookean")
      return std::make_unique<NeoHookean>(prm, name, section_path);
    throw InputError(section_path + "/Model = '" + model +
                     "' is not a known law; use one of: linear elastic, "
                     "neo-Hookean.");
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



  double
  Material::p_wave_speed() const
  {
    return std::sqrt(p_wave_modulus() / rho);
  }
} // namespace mpm
