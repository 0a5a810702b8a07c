#ifndef mpm_points_point_layout_h
#define mpm_points_point_layout_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The named layout of a material point's properties in the
   * ParticleHandler. Stress is always the full symmetric 3x3 Cauchy stress
   * (plane strain keeps sigma_zz; in an axisymmetric scene zz is the hoop
   * direction). F is dim x dim; a 2D point also carries F_zz, the
   * out-of-plane stretch (1 in plane strain, the hoop stretch r / r_0 in
   * axisymmetry).
   * `work density` is the stress work per unit reference volume, the
   * point's strain energy for elastic laws. Internal variables of the laws
   * follow; a scene sizes them to the largest law it uses. Scenes with an
   * implicit scheme add the acceleration and the point load after them (see
   * MaterialPoints), so explicit runs do not carry them.
   */
  template <int dim>
  struct PointLayout
  {
    static constexpr unsigned int mass                 = 0;
    static constexpr unsigned int reference_volume     = 1;
    /** Edge lengths of the box the point stands for, at the start. */
    static constexpr unsigned int reference_size       = 2;
    static constexpr unsigned int velocity             = reference_size + dim;
    static constexpr unsigned int deformation_gradient = velocity + dim;
    /** F_zz of a 2D point; in 3D it is part of F and takes no slot. */
    static constexpr unsigned int out_of_plane_stretch =
      deformation_gradient + dim * dim;
    static constexpr unsigned int stress =
      out_of_plane_stretch + (dim == 2 ? 1 : 0);
    static constexpr unsigned int work_density       = stress + 6;
    static constexpr unsigned int body_id            = work_density + 1;
    static constexpr unsigned int material_id        = body_id + 1;
    static constexpr unsigned int internal_variables = material_id + 1;

    static unsigned int
    n_properties(const unsigned int n_internal_variables)
    {
      return internal_variables + n_internal_variables;
    }

    /** Names for the point output, one per property. */
    static std::vector<std::string>
    names(const unsigned int n_internal_variables);

    static Tensor<1, dim>
    get_velocity(const ArrayView<const double> &p)
    {
      Tensor<1, dim> v;
      for (unsigned int d = 0; d < dim; ++d)
        v[d] = p[velocity + d];
      return v;
    }

    static Tensor<2, dim>
    get_deformation_gradient(const ArrayView<const double> &p)
    {
      Tensor<2, dim> F;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F[i][j] = p[deformation_gradient + i * dim + j];
      return F;
    }

    /** The full 3x3 F of a point, with its out-of-plane stretch in 2D. */
    static Tensor<2, 3>
    get_deformation_gradient_3d(const ArrayView<const double> &p)
    {
      return embed(get_deformation_gradient(p),
                   dim == 2 ? p[out_of_plane_stretch] : 1.);
    }

    /** Store a 3x3 F: its dim x dim part, and F_zz in 2D. */
    static void
    set_deformation_gradient_3d(const ArrayView<double> &p,
                                const Tensor<2, 3> &     F)
    {
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          p[deformation_gradient + i * dim + j] = F[i][j];
      if (dim == 2)
        p[out_of_plane_stretch] = F[2][2];
    }

    /**
     * The current volume of a point whose 3x3 deformation gradient is F:
     * the one place that says how a point's volume follows its motion.
     */
    static double
    current_volume(const ArrayView<const double> &p, const Tensor<2, 3> &F)
    {
      return determinant(F) * p[reference_volume];
    }

    static double
    current_volume(const ArrayView<const double> &p)
    {
      return current_volume(p, get_deformation_gradient_3d(p));
    }

    /** Raw order of SymmetricTensor<2,3>: xx, yy, zz, xy, xz, yz. */
    static SymmetricTensor<2, 3>
    get_stress(const ArrayView<const double> &p)
    {
      SymmetricTensor<2, 3> s;
      for (unsigned int k = 0; k < 6; ++k)
        s.access_raw_entry(k) = p[stress + k];
      return s;
    }

    static void
    set_stress(const ArrayView<double> &p, const SymmetricTensor<2, 3> &s)
    {
      for (unsigned int k = 0; k < 6; ++k)
        p[stress + k] = s.access_raw_entry(k);
    }

    /** Embed a dim x dim tensor in 3x3, with `diagonal` on the added rows. */
    static Tensor<2, 3>
    embed(const Tensor<2, dim> &t, const double diagonal)
    {
      Tensor<2, 3> t3;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          t3[i][j] = (i < dim && j < dim) ? t[i][j] : (i == j ? diagonal : 0.);
      return t3;
    }
  };
} // namespace mpm

#endif
