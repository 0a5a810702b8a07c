#include <mpm/basis/gimp_functions.h>

#include <algorithm>
#include <cmath>

namespace mpm
{
  namespace
  {
    /**
     * The hat of node i on a line of n cells, as a function of t = x - i,
     * and its antiderivative with H(0) = 0. The two nodes at each end of
     * the line continue the first (last) cell's linear functions beyond
     * the grid: node 0 is 1 - t for t < 0, node 1 is 1 + t for t < -1 too
     * (and the mirror images at node n), so that a GIMP domain that
     * reaches out of the grid still sees a partition of unity that
     * reproduces linear fields.
     */
    struct Hat
    {
      enum Piece
      {
        hat,
        rising,
        falling
      };
      Piece left, right;

      Hat(const int i, const int n)
        : left(i == 0 ? falling : i == 1 ? rising : hat)
        , right(i == n ? rising : i == n - 1 ? falling : hat)
      {}

      double
      value(const double t) const
      {
        const Piece piece = t <= 0. ? left : right;
        if (piece == rising)
          return 1. + t;
        if (piece == falling)
          return 1. - t;
        return std::max(0., 1. - std::abs(t));
      }

      double
      antiderivative(const double t) const
      {
        const Piece piece = t <= 0. ? left : right;
        if (piece == rising)
          return t + 0.5 * t * t;
        if (piece == falling)
          return t - 0.5 * t * t;
        if (t <= -1.)
          return -0.5;
        if (t >= 1.)
          return 0.5;
        return t - 0.5 * t * std::abs(t);
      }
    };

    /**
     * GIMP: the hats averaged over [x - l, x + l], (H(x + l) - H(x - l)) /
     * 2l, and the averaged gradient (N(x + l) - N(x - l)) / 2l; for l = 0
     * the hats themselves (Q1).
     */
    LatticeWeights
    gimp_weights(const double x, const double l, const int corner, const int n)
    {
      LatticeWeights w;
      for (int k = 0; k < 4; ++k)
        {
          const int i = corner - 1 + k;
          w.value[k] = w.slope[k] = 0.;
          if (i < 0 || i > n)
            continue;
          const Hat    hat(i, n);
          const double t = x - i;
          if (l > 0.)
            {
              w.value[k] =
                (hat.antiderivative(t + l) - hat.antiderivative(t - l)) /
                (2. * l);
              w.slope[k] = (hat.value(t + l) - hat.value(t - l)) / (2. * l);
            }
          else if (k == 1 || k == 2)
            {
              // The point lies in the cell between nodes k = 1 and 2.
              const double r = x - corner;
              w.value[k]     = k == 1 ? 1. - r : r;
              w.slope[k]     = k == 1 ? -1. : 1.;
            }
        }
      return w;
    }
  } // namespace



  template <int dim>
  std::array<LatticeWeights, dim>
  GimpFunctions<dim>::weights(const Point<dim> &             x,
                              const std::array<int, dim> &   corner,
                              const ArrayView<const double> &p) const
  {
    // The half-width of the point's domain in cells, at most 1/2, so that
    // it reaches at most three nodes per direction.
    using Layout = PointLayout<dim>;
    std::array<LatticeWeights, dim> w;
    for (unsigned int d = 0; d < dim; ++d)
      {
        double size = p[Layout::reference_size + d];
        if (stretched)
          size *= std::abs(p[Layout::deformation_gradient + d * dim + d]);
        const double l =
          std::min(0.5 * size * this->node_lattice.inverse_h()[d], 0.5);
        w[d] = gimp_weights(x[d], l, corner[d], this->node_lattice.n_cells(d));
      }
    return w;
  }



  template class GimpFunctions<2>;
  template class GimpFunctions<3>;
} // namespace mpm
