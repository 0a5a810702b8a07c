#include <deal.II/base/exceptions.h>

#include <deal.II/base/quadrature_lib.h>

#include <mpm/bodies/body.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/base/shape_parameters.h>

#include <algorithm>
#include <iostream>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  Body<dim>::declare_parameters(ParameterHandler &prm)
  {
    ShapeParameters<dim>::declare_parameters(
      prm,
      "filled with points. Only the part inside the grid gets points, so a "
      "grid that starts on a symmetry plane cuts the shape there.");
    prm.declare_entry("Material", "", Patterns::Anything(),
                      "Name of the material (one of Materials/Names).");
    prm.declare_entry("Points per cell direction", "2", Patterns::Integer(1, 10),
                      "Material points per background cell and direction "
                      "(with Point placement = body mesh: per cell of the "
                      "body's own mesh and direction). A point belongs to "
                      "the first body, in the order of Bodies/Names, that "
                      "contains it.");
    prm.declare_entry("Point placement", "centres",
                      Patterns::Selection("centres|Gauss|body mesh"),
                      "centres: points at the centres of a regular n x n "
                      "(x n) subdivision of each cell, with equal volumes. "
                      "Gauss: points at the n x n (x n) Gauss points, with "
                      "the Gauss weights (the material points of a FE "
                      "solution with the same quadrature). body mesh: the "
                      "body gets a mesh of its own (a box: a grid of "
                      "bricks; a disk or sphere: deal.II's ball), with "
                      "cells about as large as the background grid's "
                      "smallest, and a point at each of the n x n (x n) "
                      "Gauss points of its cells with the volume they "
                      "stand for: the points then follow the body's "
                      "surface instead of the grid's cells, so a disk is "
                      "round rather than a staircase with a flat bottom "
                      "(what a disk that rolls needs).");
    prm.declare_entry("Initial stress", "none",
                      Patterns::Selection("none|geostatic"),
                      "none: the body starts unstressed, and gravity acts "
                      "on it from rest. geostatic: the K0 procedure, "
                      "vertical stress -rho g depth below the body's top "
                      "(its highest point; a flat free surface) and "
                      "horizontal stress K0 times that. Each body counts "
                      "only its own weight, so a body under another starts "
                      "out of equilibrium. Needs Gravity and a "
                      "law that can hold a stress at rest (linear elastic, "
                      "Mohr-Coulomb, von Mises, Drucker-Prager "
                      "viscoplastic).");
    prm.declare_entry("K0", "0.5", Patterns::Double(0.),
                      "Ratio of horizontal to vertical stress of the "
                      "geostatic stress; Jaky's 1 - sin(phi) is the usual "
                      "choice for normally consolidated soil.");
    prm.declare_entry("Density", "0", Patterns::Double(0.),
                      "The bulk density of the body's points [kg/m^3]; "
                      "0: its material's Density. Only for a law whose "
                      "stress follows the density (Wieckowski granular: a "
                      "loose portion of 1000 kg/m^3 starts stress-free).");
    prm.declare_entry("First release", "0", Patterns::Double(0.),
                      "Inflow: the time [s] at which the body's points are "
                      "first put into the grid (0: at the start).");
    prm.declare_entry("Releases", "1", Patterns::Integer(1),
                      "Inflow: how many times the body is released, at "
                      "First release + k Release interval, k = 0, 1, ...: "
                      "each release seeds the body's region afresh (a "
                      "portion of fill falling into a silo, [W] 5.1.2). "
                      "The region's cells must be empty then.");
    prm.declare_entry("Release interval", "0", Patterns::Double(0.),
                      "Inflow: the time [s] between releases; must be "
                      "positive if Releases > 1.");
    prm.declare_entry(
      "Contact group", "default", Patterns::Anything(),
      "The contact group of the body: bodies of one group share a velocity "
      "field at the nodes, and stick together where they meet; bodies of "
      "different groups meet through Contact/Pairs (Coulomb friction, "
      "free separation). A name without '-', ':', ',' or spaces. Explicit "
      "scheme only, for two groups or more.");
    prm.declare_entry("Initial velocity", "0; 0; 0", Patterns::Anything(),
                      "Initial velocity as a function of position x, y (, z) "
                      "and the constant pi: one expression per component, "
                      "';'-separated, e.g. '0.1; 0.1' or "
                      "'0.1*sin(pi*x/50); 0'. Extra trailing components "
                      "beyond the dimension are ignored if zero.");
  }



  template <int dim>
  Body<dim>::Body(const ParameterHandler &        prm,
                  const std::string &             name,
                  const std::string &             section_path,
                  const std::vector<std::string> &material_names)
    : body_name(name)
  {
    group            = Utilities::trim(prm.get("Contact group"));
    bulk_density     = prm.get_double("Density");
    first_release    = prm.get_double("First release");
    n_releases       = prm.get_integer("Releases");
    release_interval = prm.get_double("Release interval");
    if (n_releases > 1 && !(release_interval > 0.))
      throw InputError(section_path + "/Releases = " +
                       std::to_string(n_releases) +
                       " needs a positive Release interval.");
    geostatic_k0 = prm.get("Initial stress") == "geostatic" ?
                     prm.get_double("K0") :
                     -1.;
    if (geostatic() && is_inflow())
      throw InputError(section_path + ": an inflow (First release > 0 or "
                       "Releases > 1) starts with Initial stress = none.");
    const unsigned int n = prm.get_integer("Points per cell direction");
    own_mesh = prm.get("Point placement") == "body mesh";
    if (prm.get("Point placement") != "centres")
      placement_1d = QGauss<1>(n);
    else
      placement_1d = QIterated<1>(QMidpoint<1>(), n);
    placement = Quadrature<dim>(placement_1d);
    // The origin of the Initial velocity expressions: the centre of a disk,
    // sphere or cylinder end.
    Point<dim> center;
    shape = ShapeParameters<dim>::create(prm, section_path, center);
    if (own_mesh && !shape->has_mesh())
      throw InputError(section_path + "/Point placement = body mesh needs a "
                       "box, disk or sphere (Shape = " + prm.get("Shape") +
                       ").");

    const std::string material_name = prm.get("Material");
    const auto        found =
      std::find(material_names.begin(), material_names.end(), material_name);
    if (found == material_names.end())
      {
        throw InputError(section_path + "/Material = '" + material_name +
                         "' is not one of Materials/Names: " +
                         comma_separated(material_names) + ".");
      }
    material = found - material_names.begin();

    // One expression per component; allow a 3-component default in 2D.
    std::vector<std::string> expressions =
      Utilities::split_string_list(prm.get("Initial velocity"), ';');
    while (expressions.size() > dim && expressions.back() == "0")
      expressions.pop_back();
    if (expressions.size() != dim)
      throw InputError(section_path + "/Initial velocity = '" +
                       prm.get("Initial velocity") + "' must have " +
                       std::to_string(dim) + " ';'-separated components.");
    velocity = parse_function<dim>(expressions,
                                   FunctionParser<dim>::default_variable_names(),
                                   center,
                                   section_path + "/Initial velocity");
  }



  template <int dim>
  Tensor<1, dim>
  Body<dim>::initial_velocity(const Point<dim> &x) const
  {
    Tensor<1, dim> v;
    for (unsigned int d = 0; d < dim; ++d)
      v[d] = velocity->value(x, d);
    return v;
  }



  template <int dim>
  double
  Body<dim>::release_time(const unsigned int k) const
  {
    return first_release + k * release_interval;
  }



  template class Body<2>;
  template class Body<3>;
} // namespace mpm
