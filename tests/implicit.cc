// Implicit MPM.
// Newmark (beta = 1/4, gamma = 1/2), which is exact for a constant
// acceleration:
// - a point in free fall follows y0 - g t^2 / 2 and v = -g t to 1e-12;
// - the vibrating bar (prm/vibrating_bar.prm) with a time step of 0.1 s,
//   twice the explicit one, stays within 3 % of the analytical
//   centre-of-mass velocity over 40 s; with Bossak's alpha = -0.3 it loses
//   energy (numerical damping) and still stays within 3 %;
// - the same point pushed by a point load instead of gravity follows
//   y0 - F t^2 / (2 m): the initial acceleration includes the load.
// Quasi-static, on the oedometer of prm/oedometer.prm (neo-Hookean,
// nu = 0, rollers, fixed base, load on the top row of points):
// - the first load step, before any point crosses a cell, is homogeneous
//   below the loaded cell and matches the closed form of the law,
//   sigma = E sinh(eps_L) (benchmarks.md section 4), to 1e-8;
// - full Newton converges quadratically: once the out-of-balance ratio is
//   below 1e-2, each ratio is below 10 times the square of the one before
//   (asserted from the printed iterations), in every load step;
// - with full cells integrated by cell volume (the default), every load
//   step to eps_L = -0.5 stays within 1 % of the closed form, however the
//   points have crossed cells (on cells half as tall as wide, so that the
//   traction's face area is not the square root of the point volume); so
//   does the same load given as a total
//   force instead of a traction and ramped with t^2 instead of t (both
//   compared with the load of each step);
// - the cantilever under self-weight ([I] 5.1) with h = 0.5 m: run
//   linearly (one load step, one iteration) its tip deflects by the linear
//   bilinear-FE value 0.60226 m of benchmarks.md section 1 (the points sit
//   at the 2 x 2 Gauss positions, so the first MPM solve is that FE solve);
//   run nonlinearly in 5 load steps it converges, within 1 % of it, and
//   with the Newton line search it takes the same full steps;
// - the disk of prm/rolling_disk.prm (Newmark, lumped mass, contact plane
//   without slip, points on a ball mesh of the disk) on its coarse grid
//   (h = 0.05 m) rolls for 1 s with dt = 4 ms: its centre moves along the
//   plane by a t^2 / 2 within 3 %, a = 2/3 g sin(60 deg) (benchmarks.md
//   section 2); a disk stuck to the plane would not move, a sliding one
//   would reach 150 %. It stays on the plane: its centre neither sinks nor
//   lifts by more than a fifth of a cell. A disk of grid-placed points
//   has a flat bottom 0.2 m wide, hops from 0.26 s on and runs 10 %
//   behind;
// - a 3D column under its own weight (quasi-static, rollers, nu = 0)
//   settles to the closed form of uniaxial strain, u(y) = -rho g (H y -
//   y^2 / 2) / E, within the linear interpolation of the quadratic u;
// - explicit-only Time stepping entries set in a Newmark run are named in
//   a note on the screen (none without them);
// - on one and two ranks alike.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "tests.h"

using namespace dealii;

/**
 * Largest relative error of E sinh(eps_L) against the applied stress, the
 * full traction times the load factor at each time.
 */
double
oedometer_error(mpm_tests::Columns &csv,
                const double                                full_traction,
                const std::function<double(double)> &       load_factor)
{
  const double E     = 1e6;
  double       error = 0.;
  for (unsigned int n = 1; n < csv["time"].size(); ++n)
    {
      const double eps_L =
        std::log((csv["point1_y"][n] - csv["point0_y"][n]) /
                 (csv["point1_y"][0] - csv["point0_y"][0]));
      const double sigma = load_factor(csv["time"][n]) * full_traction;
      error = std::max(error,
                       std::abs(E * std::sinh(eps_L) - sigma) / std::abs(sigma));
    }
  return error;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  // Newmark free fall.
  {
    auto   csv   = mpm_tests::run_scene("scenes/free_fall.prm",
                                     "newmark-free-fall",
                                     {"Time stepping/Scheme=Newmark"});
    double error = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        const double t = csv["time"][n];
        error          = std::max(
          {error,
           std::abs(csv["point0_y"][n] - (csv["point0_y"][0] - 4.905 * t * t)),
           std::abs(csv["point0_vy"][n] + 9.81 * t)});
      }
    mpm_tests::check("Newmark free fall: y = y0 - g t^2 / 2, v = -g t to "
                     "1e-12",
                     error < 1e-12);
  }

  // The same point pushed by a point load of 1 N/m instead of gravity: the
  // initial acceleration includes the load, so y = y0 - t^2 / (2 m).
  {
    auto csv = mpm_tests::run_scene("scenes/free_fall.prm",
                                    "newmark-point-load",
                                    {"Time stepping/Scheme=Newmark",
                                     "Gravity=0, 0",
                                     "Loads/Total force=0, -1",
                                     "Loads/Region lower corner=0.5, 0.75",
                                     "Loads/Region upper corner=0.75, 1"});
    const double a     = 1. / csv["mass"][0];
    double       error = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        const double t = csv["time"][n];
        error          = std::max(
          {error,
           std::abs(csv["point0_y"][n] - (csv["point0_y"][0] - a * t * t / 2)),
           std::abs(csv["point0_vy"][n] + a * t)});
      }
    mpm_tests::check("Newmark under a point load F: y = y0 - F t^2 / (2 m) "
                     "to 1e-12",
                     error < 1e-12 * std::max(1., a));
  }

  // Newmark vibrating bar.
  {
    auto csv = mpm_tests::run_scene("../prm/vibrating_bar.prm",
                                    "newmark-bar",
                                    {"Time stepping/Scheme=Newmark",
                                     "Time stepping/Time step=0.1"});
    const double beta      = numbers::PI / 50.;
    const double amplitude = 0.1 / (beta * 25.);
    double       error     = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      error = std::max(error,
                       std::abs(csv["momentum_x"][n] / csv["mass"][n] -
                                amplitude *
                                  std::cos(10. * beta * csv["time"][n])));
    mpm_tests::check("Newmark vibrating bar, dt = 0.1: centre-of-mass "
                     "velocity within 3% over 40 s",
                     error < 0.03 * amplitude);

    // Bossak (alpha_B = -0.3) damps: the energy it keeps at the end is
    // below the trapezoidal rule's, and the bar is still within 3 %.
    auto bossak = mpm_tests::run_scene("../prm/vibrating_bar.prm",
                                       "bossak-bar",
                                       {"Time stepping/Scheme=Newmark",
                                        "Time stepping/Time step=0.1",
                                        "Newmark/Bossak alpha=-0.3"});
    double bossak_error = 0.;
    for (unsigned int n = 0; n < bossak["time"].size(); ++n)
      bossak_error =
        std::max(bossak_error,
                 std::abs(bossak["momentum_x"][n] / bossak["mass"][n] -
                          amplitude * std::cos(10. * beta * bossak["time"][n])));
    mpm_tests::check("Bossak vibrating bar: less energy at 40 s than Newmark, "
                     "within 3% of the analytical velocity",
                     bossak["total_energy"].back() <
                         csv["total_energy"].back() &&
                       bossak_error < 0.03 * amplitude);
  }

  const std::string scene = "../prm/oedometer.prm";
  const double      E = 1e6, full_traction = -521095.3;

  // First load step only: 10 % of the load.
  {
    auto csv = mpm_tests::run_scene(
      scene,
      "first-step",
      {"Time stepping/End time=0.1",
       "Time stepping/Load steps=1",
       "Loads/Traction=0, " + std::to_string(0.1 * full_traction)});
    const double eps_L =
      std::log((csv["point1_y"][1] - csv["point0_y"][1]) /
               (csv["point1_y"][0] - csv["point0_y"][0]));
    const double sigma = 0.1 * full_traction;
    mpm_tests::check("first step: E sinh(eps_L) = applied stress to 1e-8",
                     std::abs(E * std::sinh(eps_L) - sigma) <
                       1e-8 * std::abs(sigma));
  }

  // Cantilever under self-weight, h = 0.5.
  {
    const std::string cantilever = "../prm/cantilever.prm";
    auto tip = [](mpm_tests::Columns &csv) {
      // Bilinear extrapolation to (8, 0.5) of the four points of the last
      // cell below the axis: exact for the Q1 displacement field.
      double v[4];
      for (unsigned int k = 0; k < 4; ++k)
        v[k] = csv["point" + std::to_string(k) + "_y"].back() -
               csv["point" + std::to_string(k) + "_y"][0];
      const double s = (8. - csv["point0_x"][0]) /
                       (csv["point1_x"][0] - csv["point0_x"][0]);
      const double t = (0.5 - csv["point0_y"][0]) /
                       (csv["point2_y"][0] - csv["point0_y"][0]);
      return -((1 - s) * (1 - t) * v[0] + s * (1 - t) * v[1] +
               (1 - s) * t * v[2] + s * t * v[3]);
    };
    auto csv = mpm_tests::run_scene(cantilever,
                                    "cantilever-linear",
                                    {"Newton/Variant=linear",
                                     "Time stepping/Load steps=1"});
    const double linear = tip(csv);
    mpm_tests::check("cantilever h = 0.5, linear: tip deflection = 0.60226 "
                     "(linear FE) to 1e-5",
                     std::abs(linear - 0.60226) < 1e-5 * 0.60226);

    // Its exit code (0: every load step converged) is in the output.
    csv = mpm_tests::run_scene(cantilever, "cantilever-nonlinear");
    const double nonlinear = tip(csv);
    mpm_tests::check("cantilever h = 0.5, nonlinear: tip within 1 % of the "
                     "linear value",
                     std::abs(nonlinear - linear) < 0.01 * linear);

    // Where Newton converges quadratically every full correction lowers the
    // out-of-balance force, so the line search must take them all.
    csv = mpm_tests::run_scene(cantilever,
                               "cantilever-line-search",
                               {"Newton/Line search=true"});
    mpm_tests::check("cantilever h = 0.5, nonlinear with the line search: "
                     "the same tip to 1e-12",
                     std::abs(tip(csv) - nonlinear) < 1e-12 * nonlinear);

    // Modified Newton keeps the first tangent of each load step (and its
    // factorisation): it converges linearly to the same equilibrium, given
    // the iterations to get there in the same five load steps.
    csv = mpm_tests::run_scene(cantilever,
                               "cantilever-modified-newton",
                               {"Newton/Variant=modified",
                                "Newton/Maximum iterations=200"});
    mpm_tests::check("cantilever h = 0.5, modified Newton: the same load "
                     "steps and the same tip to 1e-8",
                     csv["step"].back() == 5 &&
                       std::abs(tip(csv) - nonlinear) < 1e-8 * nonlinear);
  }

  mpm_tests::check_plastic_tangent("MPM");

  // 3D, quasi-static: a column under its own weight in uniaxial strain.
  // Q1 with points at the Gauss positions gives the exact nodal
  // displacements of this 1D problem; between nodes the quadratic u(y) is
  // interpolated linearly, off by at most rho g h^2 / (8 E): 0.4 % of the
  // displacement at the top point, 0.5 % at mid-height. The finite-strain
  // law adds 1e-3.
  {
    auto csv = mpm_tests::run_scene("scenes/column_3d_self_weight.prm",
                                    "column-3d");
    const double rho_g_over_E = 1000. * 9.81 / 1e7;
    bool         matches      = csv["time"].back() > 1. - 1e-12;
    for (const std::string point : {"point0_y", "point1_y"})
      {
        const double y0       = csv[point][0];
        const double expected = -rho_g_over_E * (y0 - 0.5 * y0 * y0);
        const double u        = csv[point].back() - y0;
        deallog << "3D column: " << point << " from " << y0 << ": u / exact = "
                << std::setprecision(4) << u / expected
                << std::setprecision(6) << std::endl;
        matches = matches && std::abs(u / expected - 1.) < 0.01;
      }
    mpm_tests::check("3D quasi-static column under self weight: u(y) = -rho "
                     "g (H y - y^2 / 2) / E within 1 % at the top and at "
                     "mid-height",
                     matches);
  }

  // Rolling disk, coarse, 1 s.
  {
    auto csv = mpm_tests::run_scene("../prm/rolling_disk.prm",
                                    "rolling-disk",
                                    {"Time stepping/Time step=4e-3"});
    const double t = csv["time"].back();
    const auto [ratio, drift] = mpm_tests::rolling_disk_ratio_and_drift(csv);
    mpm_tests::check("rolling disk, h = 0.05, dt = 4 ms, t = 1 s: rolls "
                     "within 3 % of a t^2 / 2 (sliding gives 150 %)",
                     t > 1. - 1e-9 && std::abs(ratio - 1.) < 0.03);
    mpm_tests::check("rolling disk stays on the plane: centre height within "
                     "0.01 m",
                     drift < 0.01);
  }

  // The whole oedometer, ten load steps to eps_L = -0.5, on cells half as
  // tall as wide: each point of the top row carries a face of 0.05 m, not
  // the square root of its volume.
  {
    auto csv = mpm_tests::run_scene(
      scene, "full", {"Grid/Arguments=1, 20 : 0, 0 : 0.1, 1.0 : true"});
    mpm_tests::check("every load step to eps_L = -0.5 within 1 % of E "
                     "sinh(eps_L)",
                     oedometer_error(csv, full_traction, [](double t) {
                       return t;
                     }) < 0.01);
  }

  // The same traction given as a total force on the width of 0.1 m, and
  // ramped by a load factor t^2 instead of t: the same closed form, at the
  // load of each step.
  {
    auto csv = mpm_tests::run_scene(
      scene,
      "force-ramp",
      {"Loads/Traction=",
       "Loads/Total force=0, " + std::to_string(0.1 * full_traction),
       "Loads/Load factor=t^2"});
    mpm_tests::check("total force ramped with t^2: every load step within "
                     "1 % of E sinh(eps_L)",
                     oedometer_error(csv, full_traction, [](double t) {
                       return t * t;
                     }) < 0.01);
  }

  // Five load steps to eps_L = -0.26, Newton's ratios from the log.
  {
    std::string screen;
    mpm_tests::run_scene(
      scene,
      "newton",
      {"Time stepping/End time=0.5",
       "Time stepping/Load steps=5",
       "Loads/Traction=0, " + std::to_string(0.5 * full_traction)},
      &screen);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        std::istringstream lines(screen);
        std::vector<std::vector<double>> steps;
        for (std::string line; std::getline(lines, line);)
          if (line.find("load step") != std::string::npos)
            steps.emplace_back();
          else if (line.find("out-of-balance ratio") != std::string::npos)
            steps.back().push_back(
              std::stod(line.substr(line.rfind(' ') + 1)));
        bool         quadratic = true;
        unsigned int checked   = 0;
        for (const auto &ratios : steps)
          for (unsigned int k = 0; k + 1 < ratios.size(); ++k)
            if (ratios[k] < 1e-2 && ratios[k + 1] > 1e-14)
              {
                ++checked;
                quadratic =
                  quadratic && ratios[k + 1] < 10. * ratios[k] * ratios[k];
              }
        deallog << "load steps: " << steps.size() << std::endl;
        mpm_tests::check("Newton converges quadratically (" +
                           std::string(checked >= 5 ? "at least 5" :
                                                      "fewer than 5") +
                           " iterations checked)",
                         quadratic && checked >= 5);
      }
  }

  // Entries of the explicit scheme set in an implicit run do nothing, and
  // the screen says so (numbers compare by value: CFL 0.30 is the default).
  {
    std::string with, without;
    mpm_tests::run_scene("../prm/rolling_disk.prm",
                         "output-explicit-entries",
                         {"Time stepping/End time=0.004",
                          "Time stepping/Update scheme=USL",
                          "Time stepping/PIC fraction=0.05",
                          "Time stepping/CFL number=0.30"},
                         &with);
    mpm_tests::run_scene("../prm/rolling_disk.prm",
                         "output-explicit-entries",
                         {"Time stepping/End time=0.004"},
                         &without);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        const std::string note =
          "mpm: note: Time stepping/Update scheme, PIC fraction apply to "
          "the explicit scheme only; this Newmark run ignores them.";
        deallog << note << std::endl;
        mpm_tests::check("a Newmark run with explicit entries set names "
                         "them on the screen",
                         with.find(note) != std::string::npos);
        mpm_tests::check("and one without them prints no note",
                         without.find("mpm: note") == std::string::npos);
      }
  }
}
