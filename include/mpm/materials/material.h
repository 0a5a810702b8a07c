#ifndef mpm_materials_material_h
#define mpm_materials_material_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * What a constitutive law sees of one material point over one step. All
   * tensors are 3x3: a 2D plane-strain point has F_zz = 1 and no
   * out-of-plane velocity gradient, but keeps its out-of-plane stress, which
   * the laws (and later plasticity) need.
   */
  struct StepKinematics
  {
    Tensor<2, 3> F_old;
    Tensor<2, 3> F_new;
    /** Velocity gradient L over the step: F_new = (I + dt L) F_old. */
    Tensor<2, 3> velocity_gradient;
    double       dt;
    /**
     * The point's density at the end of the step, its mass over its current
     * volume. 0: not given; a law that needs it then takes its own Density
     * over det F_new.
     */
    double density = 0.;

    /** How many grid fields a law may read. */
    static constexpr unsigned int max_grid_fields = 4;

    /**
     * The values at the point of the grid fields its law reads
     * (Material::grid_fields()), in that order, after the nodal solve of
     * the step.
     */
    std::array<double, max_grid_fields> grid_fields{};
  };

  /**
   * The one constitutive interface. A law updates the Cauchy stress of a
   * point from its kinematics and its internal variables. Elastic constants
   * E, nu and the density are common to every law and live here; a law adds
   * its own parameters in a subsection named after it.
   */
  class Material
  {
  public:
    virtual ~Material() = default;

    /**
     * What the registry knows of a law: what it is (for the documentation
     * of `Model`), how it declares its own subsection (if it has one) and
     * how it is built from the current subsection, the material's name and
     * the subsection's path (for messages).
     */
    struct Law
    {
      std::string description;
      void (*declare_parameters)(ParameterHandler &) = nullptr;
      std::unique_ptr<Material> (*create)(ParameterHandler &,
                                          const std::string &,
                                          const std::string &) = nullptr;
    };

    /**
     * Add a law under its `Model` name. Each law calls this once, at the
     * end of its own file (MPM_REGISTER_MATERIAL), so a new law is one new
     * file. Returns true, for the static that calls it.
     */
    static bool
    register_law(const std::string &model, const Law &law);

    /**
     * Declare the entries of one material subsection: those common to
     * every law, `Model` with every registered law, and each law's own
     * subsection.
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Build the law named by `Model` in the current subsection. */
    static std::unique_ptr<Material>
    create(ParameterHandler & prm,
           const std::string &name,
           const std::string &section_path);

    /** Cauchy stress at the end of the step, in place. */
    virtual void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const = 0;

    /**
     * The spatial tangent c of the Cauchy stress, c = c_tau / J, where c_tau
     * relates the Truesdell rate of the Kirchhoff stress to the rate of
     * deformation: the material part of the updated-Lagrangian tangent,
     * [I] eqs. (24) and (33). It is the tangent of update_stress() itself
     * (consistent), at kinematics.F_new, for the step that starts from
     * `old_stress` and `old_internal_variables`.
     */
    virtual SymmetricTensor<4, 3>
    spatial_tangent(const StepKinematics &         kinematics,
                    const SymmetricTensor<2, 3> &  old_stress,
                    const ArrayView<const double> &old_internal_variables)
      const = 0;

    /**
     * The same tangent by central differences of update_stress(): for a
     * perturbation F_new -> (I + h E) F_new with E symmetric, the Truesdell
     * rate of tau is (tau(+h) - tau(-h)) / 2h - E tau - tau E = c_tau : E.
     * Accurate to about 1e-9 relative where the update is smooth, which
     * keeps Newton quadratic to that level. Laws without a closed form use
     * it; the tests compare the closed forms with it.
     */
    SymmetricTensor<4, 3>
    numerical_spatial_tangent(
      const StepKinematics &         kinematics,
      const SymmetricTensor<2, 3> &  old_stress,
      const ArrayView<const double> &old_internal_variables) const;

    /**
     * Put a point at rest (F = I) under `stress`: set the internal
     * variables that hold it, and return the elastic energy density stored.
     * Laws whose stress is a function of F alone cannot hold a stress at
     * F = I; they refuse with an InputError naming `who`.
     */
    virtual double
    initialize_stress(const SymmetricTensor<2, 3> &stress,
                      const ArrayView<double> &    internal_variables,
                      const std::string &          who) const;

    /**
     * The names of the internal variables a point of this law carries, in
     * the output. A variable that several laws share (plastic_strain) has
     * the same index in each.
     */
    const std::vector<std::string> &
    internal_variable_names() const
    {
      return internal_names;
    }

    unsigned int
    n_internal_variables() const
    {
      return internal_names.size();
    }

    const std::string &
    name() const
    {
      return material_name;
    }

    double
    density() const
    {
      return rho;
    }

    double
    shear_modulus() const
    {
      return mu;
    }

    /** lambda + 2 mu: with the density it gives the p-wave speed. */
    double
    p_wave_modulus() const
    {
      return lambda + 2. * mu;
    }

    double
    p_wave_speed() const;

    /**
     * The speed whose time to cross a cell bounds the explicit step at this
     * state: the p-wave speed, which for a law whose stiffness follows the
     * state depends on it, plus 2 mu_v / (rho h) for a law with a viscosity
     * mu_v (the diffusive limit dt < rho h^2 / (2 mu_v) in the same form).
     */
    virtual double
    signal_speed(const SymmetricTensor<2, 3> &,
                 const ArrayView<const double> &,
                 const double) const
    {
      return p_wave_speed();
    }

    /**
     * The state of a freshly seeded point (F = I) of the given density:
     * sets its internal variables (zero on entry) and returns its stress,
     * zero except for a law whose seeded state is stressed. Such a law must
     * refuse initialize_stress(), which would replace it. The work density
     * starts at zero, so the stored energy is measured from the seeded
     * state.
     */
    virtual SymmetricTensor<2, 3>
    seeded_state(const double /*density*/,
                 const ArrayView<double> & /*internal_variables*/) const
    {
      return {};
    }

    /**
     * Whether the stress follows the point's density (StepKinematics::
     * density) rather than F alone, so that a body of this law may be
     * seeded at a density other than the law's (a loose portion).
     */
    virtual bool
    stress_follows_density() const
    {
      return false;
    }

    /**
     * The names of the grid fields (GridField) the law reads at its points,
     * StepKinematics::grid_fields in this order: quantities computed on the
     * grid from all points, such as the density from the point positions,
     * [W] eqs. 12-13. At most StepKinematics::max_grid_fields.
     */
    virtual std::vector<std::string>
    grid_fields() const
    {
      return {};
    }

  protected:
    /** Linear elastic energy density 1/2 sigma : C^-1 : sigma. */
    double
    elastic_energy_density(const SymmetricTensor<2, 3> &stress) const;

    Material(const ParameterHandler &prm,
             const std::string &     name,
             const std::string &     section_path);

    std::string material_name;
    double      rho;
    double      youngs_modulus;
    double      poissons_ratio;
    double      lambda;
    double      mu;
    /** Set by a law that carries internal variables, in its constructor. */
    std::vector<std::string> internal_names;
  };
} // namespace mpm

/**
 * Register the Material subclass `Class` under the `Model` name `model`, at
 * the end of the law's own source file. `declare` is the law's own
 * declare_parameters, or nullptr for a law without a subsection.
 */
#define MPM_REGISTER_MATERIAL(Class, model, description, declare)       \
  namespace                                                             \
  {                                                                     \
    std::unique_ptr<::mpm::Material>                                    \
    create_##Class(::dealii::ParameterHandler &       prm,               \
                   const std::string &               name,              \
                   const std::string &               section_path)      \
    {                                                                   \
      return std::make_unique<Class>(prm, name, section_path);          \
    }                                                                   \
    const bool Class##_registered =                                     \
      ::mpm::Material::register_law(model,                              \
                                    {description, declare, &create_##Class}); \
  }

#endif
