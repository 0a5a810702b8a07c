// Points added during a run (scenes/inflow.prm): three loose portions of
// granular fill, 0.2 m x 0.1 m at 1000 kg/m3 (20 kg per metre), released
// at t = 0.05, 0.35 and 0.65 s into an empty grid. Checked against
// counting and mechanics:
// - before the first release the grid is empty; after the k-th release
//   the mass is exactly k portions (1e-12) and the points k times 72;
// - the first portion falls freely until the second is released: MUSL
//   integrates a constant acceleration as semi-implicit Euler, so its
//   centre of mass is y0 - g s (s + dt)/2 (1e-9 m, the time series' 10
//   digits) and its momentum -M g s (1e-10), with s the time since the
//   release, and being loose (J =
//   1.5) it carries no stress: zero strain energy;
// - the first two portions have landed by the end (the third is still
//   falling): no point is below the floor or above the release box;
// - with the automatic step, the first step after the first release
//   (everything at rest and stress-free) is the one in which gravity moves
//   the portion by CFL h: dt = sqrt(CFL h / g), and the portion's lowest
//   point drops by g dt^2 = CFL h (1e-12);
// A release into cells that still hold material is in bad_input.cc.
// 1 and 2 ranks print the same figures.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const double g = 9.81, portion = 20., t0 = 0.05, y0 = 0.9;
  const std::vector<double> releases = {0.05, 0.35, 0.65};

  auto csv = mpm_tests::run_scene("scenes/inflow.prm", "output-inflow");
  double       mass_gap = 0., height_gap = 0., fall_gap = 0.;
  double       energy_in_fall = 0.;
  bool         counts_right = true;
  unsigned int fall_rows    = 0;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      const double t = csv["time"][n], dt = csv["dt"][n];
      // A release happens at the start of the step that begins at its time.
      unsigned int k = 0;
      for (const double r : releases)
        k += r < t - 1e-9;
      mass_gap = std::max(mass_gap, std::abs(csv["mass"][n] - k * portion));
      counts_right = counts_right && csv["points"][n] == 72. * k;
      if (k == 1)
        {
          const double s = t - t0;
          height_gap     = std::max(
            height_gap,
            std::abs(csv["centre_of_mass_y"][n] - (y0 - g * s * (s + dt) / 2)));
          fall_gap = std::max(fall_gap,
                              std::abs(csv["momentum_y"][n] + portion * g * s) /
                                (portion * g * s));
          energy_in_fall =
            std::max(energy_in_fall, std::abs(csv["strain_energy"][n]));
          ++fall_rows;
        }
    }
  deallog << "end: " << csv["points"].back() << " points, "
          << csv["mass"].back() << " kg/m; " << fall_rows
          << " rows of free fall" << std::endl;
  mpm_tests::check("the mass is k portions after the k-th release, to "
                   "1e-12, and the points 72 k",
                   mass_gap < 1e-12 * portion && counts_right);
  mpm_tests::check("the first portion falls freely: y0 - g s (s + dt)/2 "
                   "(1e-9 m) and -M g s (1e-10)",
                   fall_rows > 1000 && height_gap < 1e-9 && fall_gap < 1e-10);
  mpm_tests::check("a loose portion carries no stress while it falls",
                   energy_in_fall == 0.);
  mpm_tests::check("at the end the fill lies between the floor and the "
                   "release box",
                   csv["min_y"].back() > 0. && csv["max_y"].back() < 0.95);

  {
    auto automatic = mpm_tests::run_scene("scenes/inflow.prm",
                                          "output-inflow-automatic",
                                          {"Time stepping/Time step=0",
                                           "Time stepping/End time=0.2"});
    const double cfl_h = 0.3 * 0.05;
    // Row 0: t = 0; row 1: the empty grid to the release at 0.05; row 2:
    // the first step of the portion.
    // The lowest row of points starts a sixth of a cell above y = 0.85.
    const double dt   = automatic["dt"][2];
    const double drop = 0.85 + 0.05 / 6 - automatic["min_y"][2];
    deallog << "automatic step: empty grid to t = " << automatic["time"][1]
            << ", then dt = " << dt << " s" << std::endl;
    mpm_tests::check("automatic step from rest: dt = sqrt(CFL h / g) and "
                     "the portion drops by CFL h, to 1e-12",
                     std::abs(automatic["time"][1] - 0.05) < 1e-12 &&
                       std::abs(dt - std::sqrt(cfl_h / g)) < 1e-12 * dt &&
                       std::abs(drop - cfl_h) < 1e-12);
  }
}
