// Explicit MPM scenes through the mpm command line, checked against
// solutions from outside the code:
// - free fall of one point (2D) and of a sphere of points (3D), and of the
//   point again with a PIC fraction of 0.5: MUSL
//   integrates a constant acceleration as v_n = -g t_n and
//   y_n = y_0 - g t_n (t_n + dt) / 2 (semi-implicit Euler), which converges
//   to g t^2 / 2 with an error g t dt / 2; all checked to round-off, and
//   the total momentum is -M g t;
// - axial vibration of a bar (benchmarks.md section 7): centre-of-mass
//   velocity v0 cos(omega_1 t) / (beta_1 L) within 3 % of its amplitude
//   over 40 s, with each update scheme, on 32 cells; and with uGIMP and
//   the cell-averaged dilatation rate (Time stepping/Dilatation rate),
//   which must keep the elastic bar's answer and plane strain (F_zz = 1
//   exactly; spreading the average over zz too gives 0.99999);
// - two elastic disks colliding: momentum stays zero to round-off, mass is
//   constant, and kinetic plus strain energy drifts by less than 3 %;
// - point velocities the grid cannot see (scenes/grid_blind_velocity.prm):
//   pure FLIP keeps their kinetic energy, a PIC fraction alpha scales it by
//   (1 - alpha)^2 per step, to round-off;
// - a uniform block moving into a fixed wall: after one step the point
//   velocities are those of the constrained grid, so the momentum falls by
//   v0 times the mass the wall nodes carry, M h / (2 W) for a block of
//   width W on cells of width h (2 x 2 or 3 x 3 points per cell put half a
//   cell column's mass on the wall). MUSL and USL; USF constrains the
//   velocity before the forces, so its points keep the old velocity;
// - an elastic wedge dropped into the hopper of prm/hopper_gmsh.prm (a
//   gmsh grid of general quadrilaterals, slip on its slanted walls
//   x = 0.5 - y/6 and x = 1.5 + y/6, fixed floor): the scene is symmetric
//   about x = 1, so the horizontal momentum stays zero to round-off; the
//   material stays inside the walls within half a point spacing and comes
//   to rest on them where its base is as wide as the channel; mass is
//   constant and the total energy does not grow (frictionless walls,
//   elastic material).

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

/** Output in the test's directory, named after the scene. */
mpm_tests::Columns
run_scene(const std::string &scene, const std::vector<std::string> &settings)
{
  return mpm_tests::run_scene(scene,
                              "output-" + scene.substr(scene.rfind('/') + 1),
                              settings);
}

/**
 * A free fall, by gravity or (`settings`) by a point load of the same
 * weight: the closed forms below hold either way.
 */
void
free_fall(const std::string &      scene,
          const std::string &      vertical,
          const double             pic_fraction = 0.,
          std::vector<std::string> settings     = {})
{
  settings.push_back("Time stepping/PIC fraction=" +
                     std::to_string(pic_fraction));
  auto csv = run_scene(scene, settings);
  const double y0  = csv["point0_" + vertical][0];
  const double g   = 9.81;
  const double dt  = csv["time"][1] - csv["time"][0];
  double discrete_error = 0., velocity_error = 0., convergence_gap = 0.;
  double momentum_error = 0.;
  const double mass = csv["mass"][0];
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      const double t = csv["time"][n];
      const double y = csv["point0_" + vertical][n];
      discrete_error =
        std::max(discrete_error, std::abs(y - (y0 - 0.5 * g * t * (t + dt))));
      velocity_error = std::max(
        velocity_error, std::abs(csv["point0_v" + vertical][n] + g * t));
      convergence_gap = std::max(
        convergence_gap, std::abs((y0 - 0.5 * g * t * t - y) - 0.5 * g * t * dt));
      momentum_error =
        std::max(momentum_error,
                 std::abs(csv["momentum_" + vertical][n] + mass * g * t));
    }
  deallog << scene << ", PIC fraction " << pic_fraction << ": steps "
          << csv["time"].size() - 1 << std::endl;
  mpm_tests::check("free fall: v = -g t to 1e-12", velocity_error < 1e-12);
  mpm_tests::check("free fall: y = y0 - g t (t + dt) / 2 to 1e-12",
                   discrete_error < 1e-12);
  mpm_tests::check("free fall: y0 - g t^2 / 2 - y = g t dt / 2 to 1e-12",
                   convergence_gap < 1e-12);
  mpm_tests::check("free fall: momentum = -M g t to 1e-12 M g",
                   momentum_error < 1e-12 * mass * g);
}

void
vibrating_bar(const std::string &scheme, const bool cell_average = false)
{
  auto csv = run_scene(
    "../prm/vibrating_bar.prm",
    {"Time stepping/Update scheme=" + scheme,
     "Time stepping/Dilatation rate=" +
       std::string(cell_average ? "cell average" : "point"),
     // Q1 gives every point of a cell of this bar the same dilatation
     // rate, which the average leaves as it is; uGIMP's varies.
     "Grid/Shape functions=" + std::string(cell_average ? "uGIMP" : "linear"),
     "Output/Tracked points=12.3, 0.2"});
  const double L = 25., v0 = 0.1, beta = numbers::PI / (2. * L),
               omega = beta * std::sqrt(100. / 1.);
  const double amplitude = v0 / (beta * L);
  double       error     = 0.;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      const double v_cm = csv["momentum_x"][n] / csv["mass"][n];
      error             = std::max(error,
                       std::abs(v_cm - amplitude * std::cos(omega * csv["time"][n])));
    }
  const std::string title =
    "vibrating bar " + scheme +
    (cell_average ? ", uGIMP, cell-averaged dilatation" : "");
  deallog << title << ": end time " << csv["time"].back()
          << ", error / amplitude " << std::setprecision(2) << error / amplitude
          << std::setprecision(6) << std::endl;
  mpm_tests::check(title + ": centre-of-mass velocity within 3% over 40 s",
                   error < 0.03 * amplitude);
  if (cell_average)
    {
      // The average spreads the cell's dilatation rate over x and y only:
      // plane strain stays plane.
      double out_of_plane = 0.;
      for (const double F_zz : csv["point0_F_zz"])
        out_of_plane = std::max(out_of_plane, std::abs(F_zz - 1.));
      mpm_tests::check(title + ": F_zz = 1 exactly", out_of_plane == 0.);
    }
}

void
two_disks()
{
  auto csv = run_scene("../prm/two_disks.prm", {});
  const double e0 = csv["total_energy"][0];
  const double m0 = csv["mass"][0];
  const double p_scale = m0 * 0.1; // mass times initial speed per axis
  double       drift = 0., momentum = 0., mass_change = 0., min_kinetic = e0;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      drift    = std::max(drift, std::abs(csv["total_energy"][n] - e0) / e0);
      momentum = std::max({momentum,
                           std::abs(csv["momentum_x"][n]),
                           std::abs(csv["momentum_y"][n])});
      mass_change = std::max(mass_change, std::abs(csv["mass"][n] - m0));
      min_kinetic = std::min(min_kinetic, csv["kinetic_energy"][n]);
    }
  mpm_tests::check("two disks: momentum zero to 1e-12 of m v0",
                   momentum < 1e-12 * p_scale);
  mpm_tests::check("two disks: mass constant to 1e-12",
                   mass_change < 1e-12 * m0);
  mpm_tests::check("two disks: they collide (kinetic energy falls below "
                   "half)",
                   min_kinetic < 0.5 * e0);
  mpm_tests::check("two disks: they bounce apart (kinetic energy back "
                   "above 80%)",
                   csv["kinetic_energy"].back() > 0.8 * e0);
  deallog << "two disks: energy drift " << std::setprecision(2) << drift
          << std::setprecision(6) << std::endl;
  mpm_tests::check("two disks: energy drift below 3%", drift < 0.03);
}

void
grid_blind_velocity(const double pic_fraction)
{
  auto csv = run_scene("scenes/grid_blind_velocity.prm",
                       {"Time stepping/PIC fraction=" +
                        std::to_string(pic_fraction)});
  const double e0    = csv["kinetic_energy"][0];
  double       error = 0., momentum = 0.;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      error = std::max(error,
                       std::abs(csv["kinetic_energy"][n] -
                                e0 * std::pow(1. - pic_fraction, 2. * n)) /
                         e0);
      momentum = std::max(momentum, std::abs(csv["momentum_x"][n]));
    }
  deallog << "grid-blind velocity, PIC fraction " << pic_fraction
          << ": steps " << csv["time"].size() - 1 << std::endl;
  mpm_tests::check("grid-blind velocity: kinetic energy = E0 (1 - alpha)^2n "
                   "to 1e-12",
                   error < 1e-12);
  mpm_tests::check("grid-blind velocity: momentum zero to 1e-12",
                   momentum < 1e-12 * std::sqrt(2. * e0 * csv["mass"][0]));
}

void
block_into_wall(const std::string &scheme)
{
  auto csv = run_scene("scenes/grid_blind_velocity.prm",
                       {"Boundary conditions/Fixed boundaries=left",
                        "Bodies/block/Initial velocity=-1; 0",
                        "Time stepping/Update scheme=" + scheme});
  const double mass     = csv["mass"][0];
  const double expected = -(1. - 0.1 / 2.) * mass;
  deallog << "block into a wall, " << scheme << ": momentum after one step "
          << csv["momentum_x"][1] / mass << " M v0" << std::endl;
  mpm_tests::check("block into a wall (" + scheme +
                     "): momentum after one step = -(M - M h / 2W) v0 to "
                     "1e-12",
                   std::abs(csv["momentum_x"][1] - expected) < 1e-12 * mass);
}

void
hopper()
{
  auto         csv       = run_scene("../prm/hopper_gmsh.prm", {});
  const double mass      = csv["mass"][0];
  const double e0        = csv["total_energy"][0];
  const double momentum  = mass * std::sqrt(2. * 9.81 * 2.6);
  const double half_step = 0.25 * (1. / 16.); // half a point spacing
  double       largest_px = 0., energy_growth = 0., outside = 0., mass_change = 0.;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      largest_px    = std::max(largest_px, std::abs(csv["momentum_x"][n]));
      energy_growth = std::max(energy_growth, csv["total_energy"][n] - e0);
      mass_change = std::max(mass_change, std::abs(csv["mass"][n] - mass));
      // The leftmost point lies at a height of at most max_y, where the
      // wall is at 0.5 - max_y / 6 or further right.
      const double top = csv["max_y"][n];
      outside          = std::max({outside,
                          (0.5 - top / 6.) - csv["min_x"][n],
                          csv["max_x"][n] - (1.5 + top / 6.),
                          -csv["min_y"][n]});
    }
  deallog << "hopper: " << csv["time"].size() - 1 << " steps, lowest point "
          << csv["min_y"].back() << std::endl;
  mpm_tests::check("hopper: ran to 1 s", csv["time"].back() > 1. - 1e-12);
  mpm_tests::check("hopper: symmetric, horizontal momentum below 1e-10 of "
                   "the impact momentum",
                   largest_px < 1e-10 * momentum);
  mpm_tests::check("hopper: the material stays within half a point spacing "
                   "of the slanted walls and the floor",
                   outside < half_step);
  // The wedge's base (1.3 m) is as wide as the channel (1 + y/3) at
  // y = 0.9: it comes to rest on the walls there, held about one cell
  // (0.125 m tall) early by the wall cells' nodes, not on the floor.
  mpm_tests::check("hopper: the wedge's base rests on the walls near y = "
                   "0.9, within a cell above it",
                   csv["min_y"].back() > 0.9 - half_step &&
                     csv["min_y"].back() < 0.9 + 0.125);
  mpm_tests::check("hopper: mass constant to round-off, total energy does "
                   "not grow (to 1e-9 of its start)",
                   mass_change < 1e-12 * mass &&
                     energy_growth < 1e-9 * std::abs(e0));
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  free_fall("scenes/free_fall.prm", "y");
  free_fall("scenes/free_fall_3d.prm", "z");
  // Uniform motion: the PIC velocity N (v + dt a) equals the FLIP one, so
  // the closed forms hold for any blend (and fail if PIC used v^t).
  free_fall("scenes/free_fall.prm", "y", 0.5);
  // No gravity: a point load of the weight, 1000 kg/m3 x 0.25^2 m2 x g,
  // on the one point (explicit schemes apply Loads as the implicit ones).
  free_fall("scenes/free_fall.prm",
            "y",
            0.,
            {"Gravity=0, 0",
             "Materials/soft/Density=1000",
             "Loads/Total force=0, -613.125",
             "Loads/Region lower corner=0, 0",
             "Loads/Region upper corner=1, 1"});
  hopper();
  for (const std::string scheme : {"USF", "USL", "MUSL"})
    vibrating_bar(scheme);
  vibrating_bar("MUSL", true);
  two_disks();
  grid_blind_velocity(0.);
  grid_blind_velocity(0.1);
  for (const std::string scheme : {"MUSL", "USL"})
    block_into_wall(scheme);
}
