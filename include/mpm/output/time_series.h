#ifndef mpm_output_time_series_h
#define mpm_output_time_series_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <boost/serialization/split_member.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/base/force_report.h>
#include <mpm/points/material_points.h>

#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Global quantities of the points at one instant. Energies per unit
   * thickness in 2D. The gravitational energy is -sum m g.x, so the total
   * is conserved under gravity.
   */
  template <int dim>
  struct Diagnostics
  {
    double         kinetic_energy       = 0.;
    double         strain_energy        = 0.;
    double         gravitational_energy = 0.;
    Tensor<1, dim> momentum;
    double         mass = 0.;

    double
    total_energy() const
    {
      return kinetic_energy + strain_energy + gravitational_energy;
    }
  };

  /**
   * The CSV time series of a run: time, step, dt, the Diagnostics, the
   * material's extent and volume, the position, velocity, stress and
   * diagonal of F of tracked points, and the forces that the walls,
   * obstacles and contacts between bodies report (ForceReport). A tracked
   * point is the material point nearest to a given position at the start.
   */
  template <int dim>
  class TimeSeries
  {
  public:
    /**
     * `continued`: the run continues from a checkpoint, whose load() opens
     * the file where the checkpoint left it; otherwise the file is written
     * anew, header first.
     */
    /** `Time series file`, `Time series interval` and `Tracked points`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Output` subsection (the handler is at top level); the file
     * goes into `directory`.
     */
    TimeSeries(ParameterHandler &                              prm,
               const std::string &                             directory,
               const Tensor<1, dim> &                          gravity,
               const MaterialPoints<dim> &                     points,
               const std::vector<const ForceReport *> &        reports,
               const bool                                      continued);

    /** Simulated time between rows; 0: every step. */
    double
    interval() const
    {
      return row_interval;
    }

    /** Compute the diagnostics and write a row (rank 0 writes). */
    Diagnostics<dim>
    write_row(const double               time,
              const unsigned int         step,
              const double               dt,
              const MaterialPoints<dim> &points);

    /**
     * For Checkpoint: the tracked points and the length of the file. A
     * continued run cuts the rows that the stopped run wrote after the
     * checkpoint, and appends.
     */
    template <class Archive>
    void
    save(Archive &archive, const unsigned int) const;

    template <class Archive>
    void
    load(Archive &archive, const unsigned int);

    BOOST_SERIALIZATION_SPLIT_MEMBER()

  private:
    /** The (i, j) of the stress components written per tracked point. */
    static std::vector<std::pair<unsigned int, unsigned int>>
    tracked_stress_components();

    /** Rank 0: cut the file to `length` bytes and open it to append. */
    void
    continue_file(const std::uint64_t length);

    std::string                                   filename;
    double                                        row_interval;
    const Tensor<1, dim>                          gravity;
    const MPI_Comm                                communicator;
    // mutable: save() asks it for its length, and tellp() is not const.
    mutable std::ofstream                         file;
    std::vector<types::particle_index>            tracked_ids;
    const std::vector<const ForceReport *> reports;
  };



  template <int dim>
  template <class Archive>
  void
  TimeSeries<dim>::save(Archive &archive, const unsigned int) const
  {
    // Only rank 0 writes the file; the others save a length of 0.
    const std::uint64_t length =
      file.is_open() ? static_cast<std::uint64_t>(file.tellp()) : 0;
    archive << tracked_ids << length;
  }



  template <int dim>
  template <class Archive>
  void
  TimeSeries<dim>::load(Archive &archive, const unsigned int)
  {
    std::uint64_t length = 0;
    archive >> tracked_ids >> length;
    continue_file(length);
  }
} // namespace mpm

#endif
