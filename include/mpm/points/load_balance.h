#ifndef mpm_points_load_balance_h
#define mpm_points_load_balance_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/grid/grid.h>
#include <mpm/points/material_points.h>

#include <boost/serialization/split_member.hpp>

#include <cstdint>
#include <fstream>
#include <functional>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * Balances the ranks by their points while the material moves.
   *
   * p4est splits the cells evenly among the ranks, which is even work only
   * while every cell holds as many points. Once a column collapses or a silo
   * empties, most cells are empty and the rank that holds the material does
   * most of the work. Every `Check interval` steps this class weighs each
   * owned cell, `Cell weight` plus `Point weight` per point in it, and when
   * the heaviest rank carries more than `Imbalance tolerance` times the
   * mean it repartitions the grid with those weights (deal.II's `weight`
   * signal, as step-68 does); the points go with their cells.
   *
   * Each check is a row of `load_balance.csv` in the output directory: the
   * largest and mean number of points on a rank, their ratio, the same
   * ratio for the weights, and whether the grid was repartitioned (the
   * ratios are those found before the repartition).
   */
  template <int dim>
  class LoadBalance
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Load balance` subsection (the handler is at top level).
     * `continued`: the run continues from a checkpoint, whose load() opens
     * the file.
     */
    LoadBalance(ParameterHandler &         prm,
                Grid<dim> &                grid,
                const MaterialPoints<dim> &points,
                const std::string &        directory,
                const bool                 continued,
                ConditionalOStream &       pcout);

    /** At a step that is due: measure, record, repartition if needed. */
    void
    check(const double time, const unsigned int step);

    /**
     * The grid's cells changed (an adaptive grid), and p4est split them
     * evenly: repartition by the points now, if this class repartitions.
     */
    void
    grid_adapted();

    /**
     * For Checkpoint, before the points: the length of load_balance.csv and
     * the weights of the last repartition (the weight entries then, and the
     * number of points in each cell this rank weighed). A continued run
     * starts on p4est's even split of the cells; load() splits them by
     * those weights again, which gives the same partition (and, as the
     * grid rebuilds its cells at each repartition, the same local order of
     * cells and nodes), so each rank owns the cells whose points it saved
     * and the continued run repeats the uninterrupted one to the last bit.
     * It does so even when the continued run no longer balances.
     */
    template <class Archive>
    void
    save(Archive &archive, const unsigned int) const;

    template <class Archive>
    void
    load(Archive &archive, const unsigned int);

    BOOST_SERIALIZATION_SPLIT_MEMBER()

    /**
     * The entries a continued run may change: the whole subsection (they
     * move no result beyond round-off).
     */
    static std::vector<std::string>
    entries_that_may_change();

  private:
    /** Whether this class repartitions: on, and more than one rank. */
    bool
    repartitions() const;

    /**
     * Repartition the grid, each cell weighted by `Cell weight` plus `Point
     * weight` times the number `points_in` gives for it (deal.II's `weight`
     * signal, which calls it for the cells as they are before the change).
     */
    void
    repartition_by(
      const std::function<unsigned int(
        const typename Triangulation<dim>::active_cell_iterator &)>
        &                points_in,
      const unsigned int cell_weight,
      const unsigned int point_weight);

    /** Repartition by the points in each cell now. */
    void
    repartition_by_points();

    /**
     * Open load_balance.csv on rank 0, if there are checks: anew, or
     * continued at `continue_at` bytes (a run continued from a checkpoint).
     */
    void
    open_file(const std::uint64_t continue_at);

    /** Points and weight of this rank's cells. */
    std::pair<double, double>
    local_load() const;

    Grid<dim> &                grid;
    const MaterialPoints<dim> &points;
    ConditionalOStream &       pcout;

    unsigned int interval;
    bool         repartition_when_unbalanced;
    double       tolerance;
    unsigned int cell_weight;
    unsigned int point_weight;

    /** The last repartition's weights; see save(). */
    bool         repartitioned_by_weights = false;
    unsigned int last_cell_weight         = 0;
    unsigned int last_point_weight        = 0;
    std::vector<std::pair<CellId::binary_type, unsigned int>> last_points_in;

    std::string filename;
    // mutable: save() asks it for its length, and tellp() is not const.
    mutable std::ofstream file;
  };
} // namespace mpm

#endif
