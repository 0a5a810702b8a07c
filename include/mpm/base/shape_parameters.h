#ifndef mpm_base_shape_parameters_h
#define mpm_base_shape_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <mpm/base/shape.h>

#include <memory>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * A Shape from parameters: `Shape` (box, disk, sphere, cylinder, polygon)
   * and its geometry, declared and read in the current subsection. Bodies
   * and obstacles describe their shapes with the same entries.
   */
  template <int dim>
  struct ShapeParameters
  {
    /** `what` ends the documentation of `Shape`, e.g. "filled with points". */
    static void
    declare_parameters(ParameterHandler &prm, const std::string &what);

    /**
     * The shape of the current subsection, whose path (for messages) is
     * `section_path`. `center` becomes the centre of a disk or sphere and
     * the centre of a cylinder's first end, and stays as it is otherwise.
     */
    static std::unique_ptr<Shape<dim>>
    create(const ParameterHandler &prm,
           const std::string &     section_path,
           Point<dim> &            center);
  };
} // namespace mpm

#endif
