#include <deal.II/fe/fe_q.h>

#include <mpm/basis/grid_functions.h>

namespace mpm
{
  template <int dim>
  std::unique_ptr<FiniteElement<dim>>
  GridFunctions<dim>::node_element() const
  {
    return std::make_unique<FE_Q<dim>>(1);
  }



  template class GridFunctions<2>;
  template class GridFunctions<3>;
} // namespace mpm
