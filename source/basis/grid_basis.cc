#include <mpm/base/input_error.h>
#include <mpm/basis/bspline_functions.h>
#include <mpm/basis/gimp_functions.h>
#include <mpm/basis/grid_basis.h>

namespace mpm
{
  template <int dim>
  void
  GridBasis<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    prm.declare_entry(
      "Shape functions",
      "linear",
      Patterns::Selection("linear|uGIMP|cpGIMP|quadratic B-spline"),
      "The shape functions of MPM on the grid. linear: Q1 on the point's "
      "cell, any grid; a point crossing a cell face sees its gradients jump "
      "(cell-crossing noise). uGIMP: the hats averaged over the point's "
      "domain (half its seeding spacing per direction, at most half a "
      "cell), smooth as points cross cells. cpGIMP: the same with the "
      "domain stretched by the diagonal of the point's F. quadratic "
      "B-spline: one C1 quadratic per node (linear in the half cell next to "
      "a grid face, so that face nodes interpolate and walls hold them as "
      "with Q1). The smooth kinds reach the nodes of the neighbouring cells "
      "and need a grid of equal axis-aligned cells filling a box "
      "(subdivided_hyper_rectangle). Method = MPM only.");
    prm.leave_subsection();
  }



  template <int dim>
  GridShapeFunctions
  GridBasis<dim>::parse_kind(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    const std::string kind = prm.get("Shape functions");
    prm.leave_subsection();
    for (const GridShapeFunctions candidate :
         {GridShapeFunctions::linear,
          GridShapeFunctions::uGIMP,
          GridShapeFunctions::cpGIMP,
          GridShapeFunctions::quadratic_bspline})
      if (name(candidate) == kind)
        return candidate;
    AssertThrow(false, ExcInternalError());
    return GridShapeFunctions::linear;
  }



  template <int dim>
  std::string
  GridBasis<dim>::name(const GridShapeFunctions kind)
  {
    switch (kind)
      {
        case GridShapeFunctions::linear:
          return "linear";
        case GridShapeFunctions::uGIMP:
          return "uGIMP";
        case GridShapeFunctions::cpGIMP:
          return "cpGIMP";
        case GridShapeFunctions::quadratic_bspline:
          return "quadratic B-spline";
      }
    return "";
  }



  template <int dim>
  GridBasis<dim>::GridBasis(const Grid<dim> &        grid,
                            const GridShapeFunctions kind)
    : shape_functions(kind)
    , linear_functions(grid)
  {
    switch (kind)
      {
        case GridShapeFunctions::linear:
          linear = &linear_functions;
          break;
        case GridShapeFunctions::uGIMP:
        case GridShapeFunctions::cpGIMP:
          functions = std::make_unique<GimpFunctions<dim>>(
            grid, kind == GridShapeFunctions::cpGIMP);
          break;
        case GridShapeFunctions::quadratic_bspline:
          functions = std::make_unique<BsplineFunctions<dim>>(grid);
          break;
      }
  }



  template class GridBasis<2>;
  template class GridBasis<3>;
} // namespace mpm
