#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/base/shape_parameters.h>

namespace mpm
{
  template <int dim>
  void
  ShapeParameters<dim>::declare_parameters(ParameterHandler & prm,
                                           const std::string &what)
  {
    prm.declare_entry("Shape",
                      "box",
                      Patterns::Selection("box|disk|sphere|cylinder|polygon"),
                      "'box' (Lower corner, Upper corner), 'disk' in 2D or "
                      "'sphere' in 3D (Center, Radius), 'cylinder' in 3D "
                      "(Center of one end, Axis, Radius), 'polygon' in 2D "
                      "(Vertices): the shape " + what);
    prm.declare_entry("Lower corner", "", Patterns::Anything(),
                      "Box: the corner with the smallest coordinates, "
                      "e.g. '0, 0'.");
    prm.declare_entry("Upper corner", "", Patterns::Anything(),
                      "Box: the corner with the largest coordinates.");
    prm.declare_entry("Center", "", Patterns::Anything(),
                      "Disk or sphere: its centre, e.g. '0.2, 0.2'. "
                      "Cylinder: the centre of one end face.");
    prm.declare_entry("Radius", "0", Patterns::Double(0.),
                      "Disk, sphere or cylinder: its radius.");
    prm.declare_entry("Axis", "", Patterns::Anything(),
                      "Cylinder: the vector from the centre of one end face "
                      "to the centre of the other, e.g. '0, 0, 0.0324'.");
    prm.declare_entry("Vertices", "", Patterns::Anything(),
                      "Polygon: its vertices in order, ';'-separated, e.g. "
                      "'0,0; 1,0; 0,1'.");
  }



  template <int dim>
  std::unique_ptr<Shape<dim>>
  ShapeParameters<dim>::create(const ParameterHandler &prm,
                               const std::string &     section_path,
                               Point<dim> &            center)
  {
    const std::string shape_name = prm.get("Shape");
    if (shape_name == "box")
      {
        const Point<dim> lower_corner = parse_point<dim>(
          prm.get("Lower corner"), section_path + "/Lower corner");
        const Point<dim> upper_corner = parse_point<dim>(
          prm.get("Upper corner"), section_path + "/Upper corner");
        for (unsigned int d = 0; d < dim; ++d)
          if (!(upper_corner[d] > lower_corner[d]))
            throw InputError(section_path +
                             "/Upper corner must be larger than Lower corner "
                             "in every coordinate.");
        return std::make_unique<BoxShape<dim>>(lower_corner, upper_corner);
      }
    else if (shape_name == "disk" || shape_name == "sphere")
      {
        if ((shape_name == "disk") != (dim == 2))
          throw InputError(section_path + "/Shape = " + shape_name +
                           " needs Dimension = " + (dim == 2 ? "3" : "2") +
                           "; use " + (dim == 2 ? "disk" : "sphere") + ".");
        center = parse_point<dim>(prm.get("Center"), section_path + "/Center");
        const double radius = prm.get_double("Radius");
        if (!(radius > 0.))
          throw InputError(section_path + "/Radius must be positive.");
        return std::make_unique<BallShape<dim>>(center, radius);
      }
    else if (shape_name == "cylinder")
      {
        if (dim != 3)
          throw InputError(section_path +
                           "/Shape = cylinder needs Dimension = 3; in 2D "
                           "use a box.");
        center = parse_point<dim>(prm.get("Center"), section_path + "/Center");
        const Tensor<1, dim> axis =
          parse_point<dim>(prm.get("Axis"), section_path + "/Axis");
        const double radius = prm.get_double("Radius");
        if (!(radius > 0.))
          throw InputError(section_path + "/Radius must be positive.");
        if (!(axis.norm() > 0.))
          throw InputError(section_path + "/Axis must not be zero.");
        return std::make_unique<CylinderShape<dim>>(center, axis, radius);
      }
    else
      {
        if (dim != 2)
          throw InputError(section_path +
                           "/Shape = polygon is available in 2D only.");
        const std::vector<Point<dim>> vertices = parse_point_list<dim>(
          prm.get("Vertices"), section_path + "/Vertices");
        if (vertices.size() < 3)
          throw InputError(section_path +
                           "/Vertices must list at least 3 points.");
        return std::make_unique<PolygonShape<dim>>(vertices);
      }

  }



  template struct ShapeParameters<2>;
  template struct ShapeParameters<3>;
} // namespace mpm
