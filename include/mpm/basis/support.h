#ifndef mpm_basis_support_h
#define mpm_basis_support_h

#include <deal.II/base/tensor.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * What a basis gives the assembly for one material point: the nodes that
   * carry it, the shape function values there and their gradients in real
   * space. The assembly sees nothing else, so MPM and the meshfree method
   * (later) feed the same code.
   *
   * `nodes` holds the local index of each node's first nodal value (see
   * GridNodes::NodalLayout).
   */
  template <int dim>
  struct Support
  {
    static constexpr unsigned int max_nodes = 1u << dim;

    unsigned int                                n_nodes = 0;
    std::array<unsigned int, max_nodes>         nodes;
    std::array<double, max_nodes>               N;
    std::array<Tensor<1, dim>, max_nodes>       grad_N;
  };
} // namespace mpm

#endif
