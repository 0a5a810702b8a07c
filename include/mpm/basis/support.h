#ifndef mpm_basis_support_h
#define mpm_basis_support_h

#include <deal.II/base/tensor.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * What a basis gives the assembly for one material point: the nodes that
   * carry it, the shape function values there and their gradients in real
   * space. The assembly sees nothing else, so MPM (GridBasis) and the
   * Galerkin meshfree method (MeshfreeBasis) feed the same code.
   *
   * `nodes` holds node ids: for GridBasis the Grid's (rank-local) node ids,
   * for MeshfreeBasis the index of the node in the cloud. Nodal storage
   * turns ids into offsets.
   *
   * A grid support has 2^dim nodes, a meshfree one a few dozen; the arrays
   * only grow, so a Support reused point after point allocates only at the
   * start.
   */
  template <int dim>
  struct Support
  {
    unsigned int                n_nodes = 0;
    std::vector<unsigned int>   nodes;
    std::vector<double>         N;
    std::vector<Tensor<1, dim>> grad_N;

    void
    resize(const unsigned int n)
    {
      n_nodes = n;
      if (nodes.size() < n)
        {
          nodes.resize(n);
          N.resize(n);
          grad_N.resize(n);
        }
    }
  };
} // namespace mpm

#endif
