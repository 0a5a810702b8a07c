#include <deal.II/base/symmetric_tensor.h>

#include <mpm/basis/meshfree_basis.h>
#include <mpm/base/input_error.h>

#include <Eigen/Dense>

#include <boost/geometry/index/rtree.hpp>

#include <cmath>
#include <sstream>

namespace mpm
{
  namespace
  {
    /** Growths of the search radius before a point counts as failed. */
    constexpr unsigned int max_growths   = 4;
    constexpr double       growth_factor = 1.25;
    /**
     * Smallest eigenvalue ratio of the MLS moment matrix (basis scaled by
     * R) and of the LME Hessian that counts as well-conditioned.
     */
    constexpr double mls_min_eigenvalue_ratio = 1e-6;
    constexpr double lme_min_eigenvalue_ratio = 1e-12;

    /** Cubic spline of [I] and its derivative, s = |x - x_I| / R. */
    std::pair<double, double>
    cubic_spline(const double s)
    {
      if (s <= 0.5)
        return {2. / 3. - 4. * s * s + 4. * s * s * s, -8. * s + 12. * s * s};
      if (s <= 1.)
        return {4. / 3. - 4. * s + 4. * s * s - 4. / 3. * s * s * s,
                -4. + 8. * s - 4. * s * s};
      return {0., 0.};
    }
  } // namespace



  template <int dim>
  void
  MeshfreeBasis<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Meshfree");
    prm.declare_entry("LME gamma", "1.8", Patterns::Double(0.),
                      "Locality of the local max-entropy shape functions, "
                      "beta = gamma / h^2 with h the nodal spacing: 0.8 is "
                      "wide and smooth, 4 close to linear finite elements. "
                      "The support reaches h sqrt(-ln(1e-6) / gamma): 4.16 h "
                      "for 0.8, 2.77 h for 1.8, 2.22 h for 2.8.");
    prm.declare_entry("MLS dilation", "2", Patterns::Double(0.),
                      "Radius of the cubic-spline MLS weight in nodal "
                      "spacings. With a linear basis it must take in more "
                      "than dim + 1 nodes in general position; 2 gives 12 "
                      "nodes in 2D on a square cloud.");
    prm.declare_entry("Minimum nodes", "0", Patterns::Integer(0),
                      "Fewest nodes a point's support may have; the search "
                      "radius grows (by 1/4, up to 4 times) until it has "
                      "them. 0: (dim + 1)(dim + 2) / 2, that is 6 in 2D and "
                      "10 in 3D.");
    prm.leave_subsection();
  }



  template <int dim>
  typename MeshfreeBasis<dim>::Settings
  MeshfreeBasis<dim>::parse_parameters(ParameterHandler &prm,
                                       const Kind        kind,
                                       const double      h)
  {
    Settings s;
    s.kind    = kind;
    s.spacing = h;
    prm.enter_subsection("Meshfree");
    s.lme_gamma     = prm.get_double("LME gamma");
    s.mls_dilation  = prm.get_double("MLS dilation");
    s.minimum_nodes = prm.get_integer("Minimum nodes");
    prm.leave_subsection();
    if (kind == Kind::lme && !(s.lme_gamma > 0.))
      throw InputError("Meshfree/LME gamma must be positive.");
    if (kind == Kind::mls && !(s.mls_dilation > 1.))
      throw InputError("Meshfree/MLS dilation must be larger than 1: the "
                       "weight must reach beyond the nearest nodes.");
    return s;
  }



  template <int dim>
  MeshfreeBasis<dim>::MeshfreeBasis(const Settings &settings)
    : settings(settings)
    , initial_radius(
        settings.kind == Kind::lme ?
          settings.spacing * std::sqrt(-std::log(lme_cutoff) /
                                       settings.lme_gamma) :
          settings.spacing * settings.mls_dilation)
    , minimum_nodes(settings.minimum_nodes > 0 ?
                      settings.minimum_nodes :
                      (dim + 1) * (dim + 2) / 2)
  {
    Assert(settings.spacing > 0., ExcMessage("The nodal spacing is zero."));
  }



  template <int dim>
  void
  MeshfreeBasis<dim>::reinit(const std::vector<Point<dim>> &node_positions)
  {
    // The tree refers to `nodes`: rebuild it after every change.
    tree.reset();
    nodes = node_positions;
    tree  = std::make_unique<Tree>(pack_rtree_of_indices(nodes));
  }



  template <int dim>
  void
  MeshfreeBasis<dim>::find_nodes(const Point<dim> &         x,
                                 const double               radius,
                                 std::vector<unsigned int> &found) const
  {
    found.clear();
    Point<dim> lower = x, upper = x;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lower[d] -= radius;
        upper[d] += radius;
      }
    const boost::geometry::model::box<Point<dim>> box(lower, upper);
    const double radius_square = radius * radius;
    for (const std::size_t i :
         *tree | boost::geometry::index::adaptors::queried(
                   boost::geometry::index::intersects(box)))
      if ((nodes[i] - x).norm_square() < radius_square)
        found.push_back(static_cast<unsigned int>(i));
  }



  template <int dim>
  void
  MeshfreeBasis<dim>::evaluate(const Point<dim> &x, Support<dim> &support) const
  {
    Assert(tree, ExcMessage("reinit() the basis with the node cloud first."));
    ++counts.evaluations;
    double radius = initial_radius;
    for (unsigned int growth = 0; growth <= max_growths; ++growth)
      {
        if (growth > 0)
          {
            radius *= growth_factor;
            if (growth == 1)
              ++counts.radius_growths;
          }
        find_nodes(x, radius, scratch_cloud);
        if (scratch_cloud.size() < minimum_nodes)
          continue;
        const bool valid =
          settings.kind == Kind::mls ?
            evaluate_mls(x, scratch_cloud, radius, support) :
            evaluate_lme(x, scratch_cloud, support);
        if (valid)
          return;
        ++counts.retries;
      }
    std::ostringstream message;
    message << "The " << (settings.kind == Kind::mls ? "MLS" : "LME")
            << " shape functions at (" << x << ") could not be built: "
            << scratch_cloud.size() << " nodes within " << radius << " ("
            << radius / settings.spacing << " nodal spacings), ";
    if (scratch_cloud.size() < minimum_nodes)
      message << "fewer than the " << minimum_nodes << " required.";
    else if (settings.kind == Kind::mls)
      message << "and their moment matrix is singular.";
    else
      message << "and the point is not inside their convex hull.";
    throw RunError(message.str());
  }



  template <int dim>
  bool
  MeshfreeBasis<dim>::evaluate_mls(const Point<dim> &               x,
                                   const std::vector<unsigned int> &cloud,
                                   const double                     radius,
                                   Support<dim> &support) const
  {
    // Linear basis p(y) = [1, (y - x) / R]: centred on the point, so that
    // the moment matrix is O(1) whatever the spacing.
    using Vector = Eigen::Matrix<double, dim + 1, 1>;
    using Matrix = Eigen::Matrix<double, dim + 1, dim + 1>;
    const unsigned int n = cloud.size();
    support.resize(n);
    Matrix                             A = Matrix::Zero();
    std::array<Matrix, dim>            dA;
    for (auto &m : dA)
      m.setZero();
    for (unsigned int i = 0; i < n; ++i)
      {
        const Tensor<1, dim> d = nodes[cloud[i]] - x;
        const double         r = d.norm();
        const auto [w, dw_ds]  = cubic_spline(r / radius);
        Vector p;
        p[0] = 1.;
        for (unsigned int k = 0; k < dim; ++k)
          p[k + 1] = d[k] / radius;
        const Matrix ppT = p * p.transpose();
        A += w * ppT;
        // dw/dx = w'(s) (x - x_I) / (R r)
        Tensor<1, dim> grad_w;
        if (r > 0.)
          grad_w = -dw_ds / (radius * r) * d;
        for (unsigned int k = 0; k < dim; ++k)
          dA[k] += grad_w[k] * ppT;
        support.nodes[i]  = cloud[i];
        support.N[i]      = w;
        support.grad_N[i] = grad_w;
      }
    const Eigen::SelfAdjointEigenSolver<Matrix> eigen(A, Eigen::EigenvaluesOnly);
    const Vector lambda = eigen.eigenvalues();
    if (!(lambda[0] > mls_min_eigenvalue_ratio * lambda[dim]))
      return false;
    const Matrix A_inverse = A.inverse();
    // N_I = gamma . p_I w_I with gamma = A^-1 p(x) = A^-1 e_0, and
    // d gamma = A^-1 (dp(x) - dA gamma).
    Vector e0 = Vector::Zero();
    e0[0]     = 1.;
    const Vector            gamma = A_inverse * e0;
    std::array<Vector, dim> dgamma;
    for (unsigned int k = 0; k < dim; ++k)
      {
        Vector dp   = Vector::Zero();
        dp[k + 1]   = 1. / radius;
        dgamma[k]   = A_inverse * (dp - dA[k] * gamma);
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        const Tensor<1, dim> d = nodes[cloud[i]] - x;
        Vector               p;
        p[0] = 1.;
        for (unsigned int k = 0; k < dim; ++k)
          p[k + 1] = d[k] / radius;
        const double w      = support.N[i];
        const double gamma_p = gamma.dot(p);
        support.N[i]        = gamma_p * w;
        for (unsigned int k = 0; k < dim; ++k)
          support.grad_N[i][k] =
            dgamma[k].dot(p) * w + gamma_p * support.grad_N[i][k];
      }
    return true;
  }



  template <int dim>
  bool
  MeshfreeBasis<dim>::evaluate_lme(const Point<dim> &               x,
                                   const std::vector<unsigned int> &cloud,
                                   Support<dim> &support) const
  {
    // p_a = exp(-beta |x - x_a|^2 + lambda . (x - x_a)) / Z, with lambda
    // minimising log Z (Arroyo and Ortiz 2006): Newton with backtracking on
    // the convex log Z.
    const unsigned int n    = cloud.size();
    const double       h    = settings.spacing;
    const double       beta = settings.lme_gamma / (h * h);
    const double       tolerance = 1e-12 * h;
    constexpr unsigned int max_iterations = 100;
    support.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        support.nodes[i]  = cloud[i];
        support.grad_N[i] = x - nodes[cloud[i]];
      }
    // Fills support.N with p_a; returns log Z.
    auto values = [&](const Tensor<1, dim> &lambda) {
      double f_max = -std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i < n; ++i)
        {
          const Tensor<1, dim> &d = support.grad_N[i];
          support.N[i]            = -beta * d.norm_square() + lambda * d;
          f_max                   = std::max(f_max, support.N[i]);
        }
      double Z = 0.;
      for (unsigned int i = 0; i < n; ++i)
        {
          support.N[i] = std::exp(support.N[i] - f_max);
          Z += support.N[i];
        }
      for (unsigned int i = 0; i < n; ++i)
        support.N[i] /= Z;
      return f_max + std::log(Z);
    };
    auto gradient = [&]() {
      Tensor<1, dim> r;
      for (unsigned int i = 0; i < n; ++i)
        r += support.N[i] * support.grad_N[i];
      return r;
    };
    auto hessian = [&](const Tensor<1, dim> &r) {
      SymmetricTensor<2, dim> J;
      for (unsigned int i = 0; i < n; ++i)
        J += support.N[i] * symmetrize(outer_product(support.grad_N[i],
                                                     support.grad_N[i]));
      return J - symmetrize(outer_product(r, r));
    };
    // lambda_min / lambda_max >= det J / (tr J)^dim: a bound that needs no
    // eigenvalues (whose closed form loses a double root to round-off).
    auto well_conditioned = [](const SymmetricTensor<2, dim> &J) {
      return determinant(J) >
             lme_min_eigenvalue_ratio * std::pow(trace(J), dim);
    };

    Tensor<1, dim> lambda;
    double         log_Z = values(lambda);
    Tensor<1, dim> r     = gradient();
    bool           converged = false;
    for (unsigned int it = 0; it < max_iterations; ++it)
      {
        if (r.norm() < tolerance)
          {
            converged = true;
            break;
          }
        const SymmetricTensor<2, dim> J = hessian(r);
        if (!well_conditioned(J))
          return false;
        const Tensor<1, dim> step = -(invert(J) * r);
        // Backtrack until log Z decreases (Armijo), or, close to the
        // minimum where changes of log Z are below round-off, until |r|
        // does.
        const double         log_Z_start = log_Z;
        const Tensor<1, dim> r_start     = r;
        double               t           = 1.;
        bool                 decreased   = false;
        for (unsigned int cut = 0; cut < 30 && !decreased; ++cut)
          {
            if (cut > 0)
              t *= 0.5;
            log_Z = values(lambda + t * step);
            r     = gradient();
            decreased = log_Z <= log_Z_start + 1e-4 * t * (r_start * step) ||
                        r.norm() < r_start.norm();
          }
        if (!decreased)
          return false;
        lambda += t * step;
      }
    if (!converged)
      return false;
    // grad p_a = -p_a J^-1 (x - x_a) at the converged lambda.
    const SymmetricTensor<2, dim> J = hessian(r);
    if (!well_conditioned(J))
      return false;
    const SymmetricTensor<2, dim> J_inverse = invert(J);
    for (unsigned int i = 0; i < n; ++i)
      support.grad_N[i] = -support.N[i] * (J_inverse * support.grad_N[i]);
    return true;
  }



  template class MeshfreeBasis<2>;
  template class MeshfreeBasis<3>;
} // namespace mpm
