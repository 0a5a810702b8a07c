#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/points/load_balance.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <filesystem>
#include <iomanip>
#include <map>

namespace mpm
{
  template <int dim>
  void
  LoadBalance<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Load balance");
    prm.declare_entry("Check interval", "50", Patterns::Integer(0),
                      "Steps between two measurements of the ranks' "
                      "loads (a row of load_balance.csv each); 0: never. "
                      "A measurement costs two reductions over the ranks.");
    prm.declare_entry("Repartition", "true", Patterns::Bool(),
                      "Repartition the grid when a check finds the ranks "
                      "out of balance; false only records the imbalance.");
    prm.declare_entry("Imbalance tolerance", "1.1", Patterns::Double(1.),
                      "Repartition when the heaviest rank's weight exceeds "
                      "this times the mean weight of the ranks.");
    prm.declare_entry("Cell weight", "1", Patterns::Integer(0),
                      "The weight of a cell, empty or not.");
    prm.declare_entry("Point weight", "20", Patterns::Integer(0),
                      "The weight of each point in a cell, relative to "
                      "Cell weight. The explicit step touches only the "
                      "cells that hold points, so a point costs much more "
                      "than an empty cell's nodes.");
    prm.leave_subsection();
  }



  template <int dim>
  std::vector<std::string>
  LoadBalance<dim>::entries_that_may_change()
  {
    return {"Load balance/"};
  }



  template <int dim>
  LoadBalance<dim>::LoadBalance(ParameterHandler &         prm,
                                Grid<dim> &                grid,
                                const MaterialPoints<dim> &points,
                                const std::string &        directory,
                                const bool                 continued,
                                ConditionalOStream &       pcout)
    : grid(grid)
    , points(points)
    , pcout(pcout)
  {
    prm.enter_subsection("Load balance");
    interval     = prm.get_integer("Check interval");
    repartition_when_unbalanced = prm.get_bool("Repartition");
    tolerance    = prm.get_double("Imbalance tolerance");
    cell_weight  = prm.get_integer("Cell weight");
    point_weight = prm.get_integer("Point weight");
    prm.leave_subsection();
    if (interval > 0 && cell_weight == 0 && point_weight == 0)
      throw InputError("Load balance: Cell weight and Point weight are both "
                       "0, so there is nothing to balance.");

    filename = directory + "/load_balance.csv";
    // A continued run opens the file in load(), cut to the checkpoint.
    if (!continued)
      open_file(0);
  }



  template <int dim>
  void
  LoadBalance<dim>::open_file(const std::uint64_t continue_at)
  {
    if (interval == 0 ||
        Utilities::MPI::this_mpi_process(grid.get_communicator()) != 0)
      return;
    // The rows written after the checkpoint go; a file that is not there
    // or shorter (the run that wrote the checkpoint made no checks) starts
    // anew.
    std::error_code error;
    const auto      size = std::filesystem::file_size(filename, error);
    const bool      append = continue_at > 0 && !error && size >= continue_at;
    if (append)
      std::filesystem::resize_file(filename, continue_at, error);
    file.open(filename, append ? std::ios::app : std::ios::out);
    if (!file)
      throw InputError("Cannot write " + filename + ".");
    if (!append)
      file << "time,step,ranks,points_max,points_mean,point_imbalance,"
              "weight_imbalance,repartitioned\n";
    file << std::setprecision(8);
  }



  template <int dim>
  void
  LoadBalance<dim>::check(const double time, const unsigned int step)
  {
    if (interval == 0 || step % interval != 0)
      return;
    const MPI_Comm     communicator = grid.get_communicator();
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const auto [n_points, load] = local_load();
    const double points_max  = Utilities::MPI::max(n_points, communicator);
    const double points_mean = Utilities::MPI::sum(n_points, communicator) /
                               n_ranks;
    const double load_max  = Utilities::MPI::max(load, communicator);
    const double load_mean = Utilities::MPI::sum(load, communicator) / n_ranks;
    const double point_imbalance =
      points_mean > 0. ? points_max / points_mean : 1.;
    const double weight_imbalance = load_mean > 0. ? load_max / load_mean : 1.;

    const bool repartitioned = repartitions() && weight_imbalance > tolerance;
    if (repartitioned)
      {
        repartition_by_points();
        const double after =
          Utilities::MPI::max(local_load().second, communicator) / load_mean;
        pcout << "  load balance at step " << step << ": weight imbalance "
              << std::setprecision(3) << weight_imbalance << " -> " << after
              << std::setprecision(6) << std::endl;
      }
    if (file.is_open())
      file << time << ',' << step << ',' << n_ranks << ',' << points_max
           << ',' << points_mean << ',' << point_imbalance << ','
           << weight_imbalance << ',' << (repartitioned ? 1 : 0) << '\n'
           << std::flush;
  }



  template <int dim>
  void
  LoadBalance<dim>::grid_adapted()
  {
    // A checkpoint restores the last weights only if they made the
    // partition in force.
    if (repartitions())
      repartition_by_points();
    else
      repartitioned_by_weights = false;
  }



  template <int dim>
  bool
  LoadBalance<dim>::repartitions() const
  {
    return interval > 0 && repartition_when_unbalanced &&
           Utilities::MPI::n_mpi_processes(grid.get_communicator()) > 1;
  }



  template <int dim>
  void
  LoadBalance<dim>::repartition_by_points()
  {
    repartition_by(
      [this](const typename Triangulation<dim>::active_cell_iterator &cell) {
        return points.handler().n_particles_in_cell(cell);
      },
      cell_weight,
      point_weight);
  }



  template <int dim>
  void
  LoadBalance<dim>::repartition_by(
    const std::function<unsigned int(
      const typename Triangulation<dim>::active_cell_iterator &)> &points_in,
    const unsigned int                                          cell_weight,
    const unsigned int                                          point_weight)
  {
    // A repartition leaves every cell as it is (CELL_PERSIST); the other
    // states follow the signal's rules, should the grid also refine.
    using Active             = typename Triangulation<dim>::active_cell_iterator;
    repartitioned_by_weights = true;
    last_cell_weight         = cell_weight;
    last_point_weight        = point_weight;
    last_points_in.clear();
    grid.repartition(
      [&](const typename Triangulation<dim>::cell_iterator &cell,
          const typename Triangulation<dim>::CellStatus     status) {
        unsigned int n = 0;
        switch (status)
          {
            case Triangulation<dim>::CELL_INVALID:
              // Not an active cell (the signal's rules, as in step-68).
              break;
            case Triangulation<dim>::CELL_PERSIST:
            case Triangulation<dim>::CELL_REFINE:
              n = points_in(Active(cell));
              if (n > 0)
                last_points_in.emplace_back(
                  cell->id().template to_binary<dim>(), n);
              if (status == Triangulation<dim>::CELL_REFINE)
                n /= GeometryInfo<dim>::max_children_per_cell;
              break;
            case Triangulation<dim>::CELL_COARSEN:
              for (const auto &child : cell->child_iterators())
                n += points_in(Active(child));
              break;
          }
        return cell_weight + point_weight * n;
      });
  }



  template <int dim>
  std::pair<double, double>
  LoadBalance<dim>::local_load() const
  {
    double n_points = 0., load = 0.;
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double n = points.handler().n_particles_in_cell(cell);
          n_points += n;
          load += cell_weight + point_weight * n;
        }
    return {n_points, load};
  }



  template <int dim>
  template <class Archive>
  void
  LoadBalance<dim>::save(Archive &archive, const unsigned int) const
  {
    // Only rank 0 writes the file; the others save a length of 0.
    const std::uint64_t csv_length =
      file.is_open() ? static_cast<std::uint64_t>(file.tellp()) : 0;
    archive << csv_length << repartitioned_by_weights << last_cell_weight
            << last_point_weight << last_points_in;
  }



  template <int dim>
  template <class Archive>
  void
  LoadBalance<dim>::load(Archive &archive, const unsigned int)
  {
    bool         weighted;
    unsigned int saved_cell_weight, saved_point_weight;
    std::vector<std::pair<CellId::binary_type, unsigned int>> weighed;
    std::uint64_t csv_length;
    archive >> csv_length >> weighted >> saved_cell_weight >>
      saved_point_weight >> weighed;
    open_file(csv_length);
    if (!weighted)
      return;
    // Each rank weighed the cells it owned then; the even split gives it
    // others.
    std::map<CellId, unsigned int> points_in_cell;
    for (const auto &rank_cells :
         Utilities::MPI::all_gather(grid.get_communicator(), weighed))
      for (const auto &[cell, n] : rank_cells)
        points_in_cell.emplace(CellId(cell), n);
    repartition_by(
      [&](const typename Triangulation<dim>::active_cell_iterator &cell) {
        const auto found = points_in_cell.find(cell->id());
        return found == points_in_cell.end() ? 0u : found->second;
      },
      saved_cell_weight,
      saved_point_weight);
  }



  template class LoadBalance<2>;
  template class LoadBalance<3>;

  template void
  LoadBalance<2>::save(boost::archive::binary_oarchive &,
                       const unsigned int) const;
  template void
  LoadBalance<3>::save(boost::archive::binary_oarchive &,
                       const unsigned int) const;
  template void
  LoadBalance<2>::load(boost::archive::binary_iarchive &, const unsigned int);
  template void
  LoadBalance<3>::load(boost::archive::binary_iarchive &, const unsigned int);
} // namespace mpm
