#ifndef mpm_time_newmark_h
#define mpm_time_newmark_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

namespace mpm
{
  using namespace dealii;

  /**
   * Newmark's time integration of the nodal motion ([I] eqs. 46-49), with
   * Bossak's numerical damping: the `Newmark` subsection, and the nodal
   * acceleration and velocity at the end of a step from its displacement
   * increment. The quasi-static scheme reads the subsection too, but uses
   * none of it (`dynamic` is false).
   */
  class Newmark
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse the `Newmark` subsection (the handler is at top level). */
    Newmark(ParameterHandler &prm, const bool dynamic);

    /**
     * The nodal acceleration at the end of a step of size dt from the
     * displacement increment du and the nodal v and a at the start.
     */
    template <int dim>
    Tensor<1, dim>
    end_acceleration(const Tensor<1, dim> &du,
                     const Tensor<1, dim> &v,
                     const Tensor<1, dim> &a,
                     const double          dt) const
    {
      return (du - dt * v - dt * dt * (0.5 - beta) * a) / (beta * dt * dt);
    }

    /** The velocity gained over a step of size dt from a at its ends. */
    template <int dim>
    Tensor<1, dim>
    velocity_increment(const Tensor<1, dim> &a_old,
                       const Tensor<1, dim> &a_new,
                       const double          dt) const
    {
      return dt * ((1. - gamma) * a_old + gamma * a_new);
    }

    /** Bossak's alpha_B (0: plain Newmark). */
    double bossak_alpha;
    double beta;
    double gamma;
    /** The lumped nodal mass instead of the consistent point mass. */
    bool lumped_mass;
  };
} // namespace mpm

#endif
