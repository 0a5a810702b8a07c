#include <mpm/base/input_error.h>
#include <mpm/basis/grid_basis.h>

namespace mpm
{
  namespace
  {
    /**
     * One direction of a smooth support: for the lattice nodes corner - 1
     * + k, k = 0..3, the value and the derivative (per cell length) of
     * their function at a point whose lattice coordinate is x (in cells,
     * between 0 and n).
     */
    struct Weights1D
    {
      std::array<double, 4> value;
      std::array<double, 4> slope;
    };

    /**
     * Quadratic B-splines: N(s) = 3/4 - s^2 for |s| <= 1/2, (3/2 - |s|)^2 / 2
     * for 1/2 < |s| < 3/2, s the distance to the node in cells; in the half
     * cell next to a grid face, 1 - s and s on the two nearest nodes, which
     * meet the quadratics with the same value and slope at s = 1/2.
     */
    Weights1D
    bspline_weights(const double x, const int corner, const int n)
    {
      Weights1D w;
      for (int k = 0; k < 4; ++k)
        {
          const int    i = corner - 1 + k;
          double       value = 0., slope = 0.;
          const double s = x - i;
          if (i < 0 || i > n)
            ;
          else if (x < 0.5)
            {
              // Next to the lower face: nodes 0 and 1, linear.
              if (i == 0)
                value = 1. - x, slope = -1.;
              else if (i == 1)
                value = x, slope = 1.;
            }
          else if (x > n - 0.5)
            {
              if (i == n)
                value = x - (n - 1), slope = 1.;
              else if (i == n - 1)
                value = n - x, slope = -1.;
            }
          else if (std::abs(s) <= 0.5)
            value = 0.75 - s * s, slope = -2. * s;
          else if (std::abs(s) < 1.5)
            {
              const double r = 1.5 - std::abs(s);
              value          = 0.5 * r * r;
              slope          = s > 0. ? -r : r;
            }
          w.value[k] = value;
          w.slope[k] = slope;
        }
      return w;
    }

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
    Weights1D
    gimp_weights(const double x, const double l, const int corner, const int n)
    {
      Weights1D w;
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
    : grid(grid)
    , shape_functions(kind)
  {
    if (kind != GridShapeFunctions::linear)
      lattice = std::make_unique<NodeLattice<dim>>(
        grid, "Grid/Shape functions = " + name(kind));
  }



  template <int dim>
  void
  GridBasis<dim>::evaluate_smooth(const unsigned int    active_cell_index,
                                  const Point<dim> &    reference_point,
                                  const Tensor<1, dim> &l,
                                  Support<dim> &        support) const
  {
    const typename NodeLattice<dim>::Cell &cell =
      lattice->cell(active_cell_index);
    // Per direction, the nodes (k) that carry the point.
    std::array<Weights1D, dim>                  weights;
    std::array<std::array<unsigned int, 3>, dim> reached;
    std::array<unsigned int, dim>                n_reached;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double x = cell.corner[d] + reference_point[d];
        weights[d] =
          shape_functions == GridShapeFunctions::quadratic_bspline ?
            bspline_weights(x, cell.corner[d], lattice->n_cells(d)) :
            gimp_weights(x, l[d], cell.corner[d], lattice->n_cells(d));
        n_reached[d] = 0;
        for (unsigned int k = 0; k < 4; ++k)
          if (weights[d].value[k] != 0. || weights[d].slope[k] != 0.)
            {
              Assert(n_reached[d] < 3, ExcInternalError());
              reached[d][n_reached[d]++] = k;
            }
      }

    unsigned int n = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n *= n_reached[d];
    support.resize(n);
    const Tensor<1, dim> &inverse_h = lattice->inverse_h();
    unsigned int          kept      = 0;
    for (unsigned int j = 0; j < n; ++j)
      {
        unsigned int patch_index = 0, stride = 1, rest = j;
        std::array<unsigned int, dim> k;
        for (unsigned int d = 0; d < dim; ++d)
          {
            k[d] = reached[d][rest % n_reached[d]];
            rest /= n_reached[d];
            patch_index += k[d] * stride;
            stride *= NodeLattice<dim>::patch_width;
          }
        double value = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          value *= weights[d].value[k[d]];
        Tensor<1, dim> gradient;
        for (unsigned int g = 0; g < dim; ++g)
          {
            double component = weights[g].slope[k[g]] * inverse_h[g];
            for (unsigned int d = 0; d < dim; ++d)
              if (d != g)
                component *= weights[d].value[k[d]];
            gradient[g] = component;
          }
        // A node whose value and slope vanish in different directions
        // carries nothing.
        if (value == 0. && gradient.norm_square() == 0.)
          continue;
        support.nodes[kept] = cell.nodes[patch_index];
        Assert(support.nodes[kept] != NodeLattice<dim>::no_node,
               ExcInternalError());
        support.N[kept]      = value;
        support.grad_N[kept] = gradient;
        ++kept;
      }
    support.n_nodes = kept;
  }



  template <int dim>
  void
  GridBasis<dim>::condense_hanging_vertices(const CellGeometry &cell,
                                            Support<dim> &      support) const
  {
    std::array<double, n_vertices>         value;
    std::array<Tensor<1, dim>, n_vertices> gradient;
    std::array<bool, n_vertices>           hangs = {};
    const auto hanging = grid.hanging_vertices(cell);
    for (const auto &entry : hanging)
      hangs[entry.vertex] = true;
    unsigned int n = 0;
    for (unsigned int v = 0; v < n_vertices; ++v)
      {
        value[v]    = support.N[v];
        gradient[v] = support.grad_N[v];
        if (!hangs[v])
          {
            support.nodes[n]  = support.nodes[v];
            support.N[n]      = value[v];
            support.grad_N[n] = gradient[v];
            ++n;
          }
      }
    for (const auto &entry : hanging)
      {
        unsigned int i = 0;
        while (i < n && support.nodes[i] != entry.master)
          ++i;
        if (i == n)
          {
            support.resize(++n);
            support.nodes[i]  = entry.master;
            support.N[i]      = 0.;
            support.grad_N[i] = Tensor<1, dim>();
          }
        support.N[i] += entry.weight * value[entry.vertex];
        support.grad_N[i] += entry.weight * gradient[entry.vertex];
      }
    support.n_nodes = n;
  }



  template <int dim>
  void
  GridBasis<dim>::cell_integrals(const unsigned int active_cell_index,
                                 Support<dim> &     integrals) const
  {
    if (shape_functions != GridShapeFunctions::quadratic_bspline)
      {
        // The hats: the Gauss rule of the bilinear cell.
        const double offset = 0.5 / std::sqrt(3.);
        const CellGeometry &cell = grid.cell_geometry(active_cell_index);
        integrals.resize(n_vertices);
        std::array<double, n_vertices>         values;
        std::array<Tensor<1, dim>, n_vertices> grad_ref;
        for (unsigned int v = 0; v < n_vertices; ++v)
          {
            integrals.nodes[v] = cell.nodes[v];
            integrals.N[v]     = 0.;
          }
        for (unsigned int q = 0; q < n_vertices; ++q)
          {
            Point<dim> xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = (q & (1u << d)) ? 0.5 + offset : 0.5 - offset;
            reference_values(xi, values, grad_ref);
            const double weight =
              determinant(jacobian(cell, grad_ref)) / n_vertices;
            for (unsigned int v = 0; v < n_vertices; ++v)
              integrals.N[v] += weight * values[v];
          }
        if (cell.n_hanging > 0)
          condense_hanging_vertices(cell, integrals);
        return;
      }

    // B-splines are quadratic on each half cell: two Gauss points on each
    // half, per direction, are exact.
    const typename NodeLattice<dim>::Cell &cell =
      lattice->cell(active_cell_index);
    std::array<std::array<double, 4>, dim> per_direction;
    const double                           offset = 0.25 / std::sqrt(3.);
    for (unsigned int d = 0; d < dim; ++d)
      {
        per_direction[d].fill(0.);
        for (const double x : {0.25 - offset, 0.25 + offset,
                               0.75 - offset, 0.75 + offset})
          {
            const Weights1D w = bspline_weights(cell.corner[d] + x,
                                                cell.corner[d],
                                                lattice->n_cells(d));
            for (unsigned int k = 0; k < 4; ++k)
              per_direction[d][k] += 0.25 * w.value[k] /
                                     lattice->inverse_h()[d];
          }
      }
    integrals.resize(0);
    for (unsigned int patch_index = 0;
         patch_index < NodeLattice<dim>::n_patch_nodes;
         ++patch_index)
      {
        double value = 1.;
        for (unsigned int d = 0, rest = patch_index; d < dim; ++d, rest /= 4)
          value *= per_direction[d][rest % 4];
        if (value == 0.)
          continue;
        const unsigned int j = integrals.n_nodes;
        integrals.resize(j + 1);
        integrals.nodes[j] = cell.nodes[patch_index];
        integrals.N[j]     = value;
      }
  }



  template class GridBasis<2>;
  template class GridBasis<3>;
} // namespace mpm
