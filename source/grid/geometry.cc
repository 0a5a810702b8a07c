#include <mpm/base/input_error.h>
#include <mpm/grid/geometry.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  void
  Geometry<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Geometry",
      "plane strain",
      Patterns::Selection("plane strain|plane stress|axisymmetric"),
      "What a 2D scene stands for. plane strain: a slice of unit depth "
      "(F_zz = 1, sigma_zz kept). plane stress: a plate of initial "
      "thickness Thickness, free on both faces (sigma_zz = 0 at every "
      "point, met by its law, with F_zz = h / h_0 the thickness ratio, an "
      "output); masses, volumes and forces are those of the plate, so "
      "with Thickness = 1 they are per unit initial thickness. "
      "axisymmetric: a body of revolution about "
      "the y axis, x the radius (the grid must lie in x >= 0, and a grid "
      "boundary on the axis must be a Slip or Fixed boundary); each point "
      "is the ring it sweeps, so masses, forces, impulses and removed mass "
      "are those of the full ring (2 pi x), and sigma_zz is the hoop "
      "stress. Axisymmetric scenes run with MPM in every scheme. "
      "3D scenes take plane strain (the default), which there means no "
      "reduction.");
    prm.declare_entry("Thickness",
                      "1",
                      Patterns::Double(),
                      "The plate's initial thickness h_0 in plane stress "
                      "[m]. Only with Geometry = plane stress.");
  }



  template <int dim>
  Geometry<dim>::Geometry(const ParameterHandler &prm)
  {
    const std::string geometry = prm.get("Geometry");
    if (geometry == "axisymmetric")
      {
        if (dim != 2)
          throw InputError("Grid/Geometry = axisymmetric needs Dimension = 2 "
                           "(x the radius, y the axis).");
        geometry_kind = Kind::axisymmetric;
      }
    else if (geometry == "plane stress")
      {
        if (dim != 2)
          throw InputError("Grid/Geometry = plane stress needs Dimension = 2 "
                           "(a plate in the x-y plane).");
        geometry_kind = Kind::plane_stress;
      }
    else
      geometry_kind = dim == 3 ? Kind::solid : Kind::plane_strain;
    thickness = prm.get_double("Thickness");
    if (geometry_kind != Kind::plane_stress && thickness != 1.)
      throw InputError("Grid/Thickness is the plate's thickness in plane "
                       "stress: set Grid/Geometry = plane stress, or leave "
                       "Thickness at 1 (a plane-strain slice has unit "
                       "depth).");
    if (!(thickness > 0.) || !std::isfinite(thickness))
      throw InputError("Grid/Thickness = " + prm.get("Thickness") +
                       ": the plate's thickness must be positive.");
  }



  template <int dim>
  void
  Geometry<dim>::check_gravity(const Tensor<1, dim> &gravity) const
  {
    if (geometry_kind == Kind::axisymmetric && gravity[0] != 0.)
      throw InputError("Gravity has an x component in an axisymmetric "
                       "scene, where x is the radius: gravity must act "
                       "along the axis, y.");
  }



  template <int dim>
  std::string
  Geometry<dim>::name() const
  {
    switch (geometry_kind)
      {
        case Kind::plane_stress:
          return "plane stress";
        case Kind::axisymmetric:
          return "axisymmetric";
        case Kind::solid:
          return "3D";
        default:
          return "plane strain";
      }
  }



  template class Geometry<2>;
  template class Geometry<3>;
} // namespace mpm
