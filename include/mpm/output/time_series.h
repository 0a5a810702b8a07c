#ifndef mpm_output_time_series_h
#define mpm_output_time_series_h

#include <deal.II/base/point.h>

#include <mpm/points/material_points.h>

#include <fstream>
#include <map>
#include <string>
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
   * The CSV time series of a run: time, step, dt, the Diagnostics, and the
   * position and velocity of tracked points. A tracked point is the material
   * point nearest to a given position at the start.
   */
  template <int dim>
  class TimeSeries
  {
  public:
    TimeSeries(const std::string &             filename,
               const std::vector<Point<dim>> &tracked_positions,
               const Tensor<1, dim> &          gravity,
               const MaterialPoints<dim> &     points);

    /** Compute the diagnostics and write a row (rank 0 writes). */
    Diagnostics<dim>
    write_row(const double               time,
              const unsigned int         step,
              const double               dt,
              const MaterialPoints<dim> &points);

  private:
    const Tensor<1, dim>                          gravity;
    const MPI_Comm                                communicator;
    std::ofstream                                 file;
    std::vector<types::particle_index>            tracked_ids;
  };
} // namespace mpm

#endif
