#ifndef mpm_basis_meshfree_basis_h
#define mpm_basis_meshfree_basis_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/numerics/rtree.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/basis/support.h>
#include <mpm/grid/geometry.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Shape functions of the Galerkin meshfree method (Iaconeta et al. 2017,
   * section 4.2): at any position, the nodes of a cloud within a search
   * radius, found with an R-tree, and either
   *
   * - moving least squares (MLS) with a linear basis and a cubic-spline
   *   weight of radius R = f h (f the dilation parameter, h the nodal
   *   spacing); or
   * - local maximum entropy (LME, Arroyo and Ortiz 2006) with locality
   *   beta = gamma / h^2, solved by Newton on the Lagrange multiplier, and
   *   searched to the radius where the unbiased weight exp(-beta r^2) falls
   *   to 1e-6.
   *
   * Both reproduce constants and linear fields exactly (to round-off and
   * the Newton tolerance), which is what the assembly needs from a basis.
   *
   * Where the cloud is too thin, the moment matrix (MLS) ill-conditioned or
   * the point outside the convex hull of its nodes (LME), the radius grows
   * by a quarter and the evaluation is retried, up to four times. A point
   * that still fails throws RunError naming its position.
   */
  template <int dim>
  class MeshfreeBasis
  {
  public:
    enum class Kind
    {
      mls,
      lme
    };

    struct Settings
    {
      Kind         kind = Kind::lme;
      /** Nodal spacing h of the cloud. */
      double       spacing = 1.;
      double       lme_gamma = 1.8;
      /** MLS weight radius in nodal spacings. */
      double       mls_dilation = 2.;
      /** Fewest nodes a point may have. */
      unsigned int minimum_nodes = 0;
    };

    /** Counts since construction, for the run's report. */
    struct Statistics
    {
      unsigned long evaluations = 0;
      /** Evaluations that needed a larger radius (nodes added). */
      unsigned long radius_growths = 0;
      /** Retries of the shape-function solve with more nodes. */
      unsigned long retries = 0;
    };

    /** Parameters of subsection "Meshfree". */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * The meshfree methods are plane strain or 3D only (InputError for an
     * axisymmetric scene).
     */
    static void
    check_scene(const SceneChoices &choices, const Geometry<dim> &geometry)
    {
      if (choices.meshfree() &&
          geometry.kind() == Geometry<dim>::Kind::axisymmetric)
        throw InputError("Grid/Geometry = axisymmetric runs with Method = "
                         "MPM; the meshfree methods are plane strain or 3D "
                         "only.");
    }

    /** Read subsection "Meshfree"; `kind` comes from the Method entry. */
    static Settings
    parse_parameters(ParameterHandler &prm, const Kind kind, const double h);

    explicit MeshfreeBasis(const Settings &settings);

    /**
     * The basis of the scene's Method (GMM-MLS, GMM-LME), from subsection
     * "Meshfree" and the grid's smallest cell edge h; none for MPM.
     */
    static std::unique_ptr<MeshfreeBasis<dim>>
    create(ParameterHandler &prm, const SceneChoices &choices, const double h)
    {
      if (!choices.meshfree())
        return nullptr;
      return std::make_unique<MeshfreeBasis<dim>>(parse_parameters(
        prm, choices.method == "GMM-MLS" ? Kind::mls : Kind::lme, h));
    }

    MeshfreeBasis(const MeshfreeBasis &) = delete;
    MeshfreeBasis &
    operator=(const MeshfreeBasis &) = delete;

    /** New node positions: rebuilds the search tree. */
    void
    reinit(const std::vector<Point<dim>> &node_positions);

    const std::vector<Point<dim>> &
    node_positions() const
    {
      return nodes;
    }

    /**
     * Shape functions and gradients at x, with `support.nodes` the cloud
     * indices. Throws RunError if no radius within the growth limit gives
     * valid shape functions.
     */
    void
    evaluate(const Point<dim> &x, Support<dim> &support) const;

    Kind
    kind() const
    {
      return settings.kind;
    }

    /** The radius searched first around every point. */
    double
    search_radius() const
    {
      return initial_radius;
    }

    const Statistics &
    statistics() const
    {
      return counts;
    }

    /** Put the counts back (evaluations that another rank counts). */
    void
    set_statistics(const Statistics &statistics)
    {
      counts = statistics;
    }

    /** The counts, for Checkpoint: a continued run reports the whole run. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &counts.evaluations &counts.radius_growths &counts.retries;
    }

    /** Locality of LME: values below this are cut from the support. */
    static constexpr double lme_cutoff = 1e-6;

  private:
    /** Cloud indices within `radius` of x, into `found`. */
    void
    find_nodes(const Point<dim> &         x,
               const double               radius,
               std::vector<unsigned int> &found) const;

    /** MLS at x on the given nodes and weight radius; false if unusable. */
    bool
    evaluate_mls(const Point<dim> &               x,
                 const std::vector<unsigned int> &cloud,
                 const double                     radius,
                 Support<dim> &                   support) const;

    /** LME at x on the given nodes; false if Newton fails. */
    bool
    evaluate_lme(const Point<dim> &               x,
                 const std::vector<unsigned int> &cloud,
                 Support<dim> &                   support) const;

    using Tree = RTree<std::size_t,
                       boost::geometry::index::linear<16>,
                       IndexableGetterFromIndices<std::vector<Point<dim>>>>;

    Settings                settings;
    double                  initial_radius;
    unsigned int            minimum_nodes;
    std::vector<Point<dim>> nodes;
    std::unique_ptr<Tree>   tree;
    mutable std::vector<unsigned int> scratch_cloud;
    mutable Statistics      counts;
  };
} // namespace mpm

#endif
