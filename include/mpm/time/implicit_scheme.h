#ifndef mpm_time_implicit_scheme_h
#define mpm_time_implicit_scheme_h

#include <mpm/basis/grid_basis.h>
#include <mpm/basis/meshfree_basis.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/time/implicit_integrator.h>
#include <mpm/time/time_scheme.h>

#include <memory>

namespace mpm
{
  using namespace dealii;

  /**
   * The quasi-static scheme (load steps over the pseudo-time End time) and
   * Newmark's (the fixed Time step) in time: each step is solved by the
   * ImplicitIntegrator; a step that does not converge is cut in half, up
   * to four times, and after a cut the step grows back by doubling, one
   * converged step at a time.
   */
  template <int dim>
  class ImplicitScheme : public TimeScheme<dim>
  {
  public:
    /** `Load steps`, and the Newton and Newmark subsections. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * `dynamic`: Newmark, else quasi-static. With a `meshfree` basis the
     * steps run on the Galerkin meshfree method.
     */
    ImplicitScheme(ParameterHandler &                      prm,
                   const typename TimeScheme<dim>::Scene & scene,
                   const bool                              dynamic,
                   const GridBasis<dim> &                  basis,
                   const DirichletConditions<dim> &        dirichlet,
                   const Tensor<1, dim> &                  gravity,
                   std::unique_ptr<MeshfreeBasis<dim>>     meshfree);

    /**
     * Newmark needs the initial acceleration: M a = f_ext - f_int with the
     * lumped mass, from the same projection the explicit scheme uses.
     */
    void
    start() override;

    double
    advance(const double time, const unsigned int step) override;

    /** The implicit schemes do not use the nodal vector: project it. */
    void
    prepare_grid_output() override;

    const NodeCloud<dim> *
    node_cloud() const override
    {
      return integrator.node_cloud();
    }

    void
    print_statistics() const override;

    std::vector<std::string>
    entries_that_may_change() const override;

    void
    save(boost::archive::binary_oarchive &archive) const override;

    void
    load(boost::archive::binary_iarchive &archive) override;

  private:
    /**
     * The size of a step before cuts: the Newmark Time step, or End time
     * over the number of load steps.
     */
    double
    step_size() const;

    const bool               dynamic;
    unsigned int             n_load_steps;
    ImplicitIntegrator<dim>  integrator;
    /** After a cut, the step grows back by doubling. */
    double                   next_step;
  };
} // namespace mpm

#endif
