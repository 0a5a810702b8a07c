// The axisymmetric form (Grid/Geometry = axisymmetric, x the radius),
// checked against closed forms:
// - ring masses (scenes/falling_rings.prm): a solid core and a hollow
//   cylinder beside the axis; the point masses sum to rho pi (R^2 H + (b^2 -
//   a^2) H') to the time series' 12 digits, since a point stands for the
//   ring its box sweeps, 2 pi x times the box (exact for a box centred on
//   the point);
// - free fall beside and on the axis: the momentum falls by M g per second
//   and the centre of mass keeps its radius, to the series' digits (no
//   stress, so no hoop force and no hoop rate);
// - a breathing cylinder (scenes/breathing_cylinder.prm), explicit and
//   Newmark: a long elastic cylinder with slip ends, set moving in its
//   fundamental radial mode.
//   The ring-mass-weighted centre of mass, sum m x / M, then swings as
//   sin(omega t), and its zero crossings give the period. The frequency
//   equation of the free radial vibration of a cylinder in plane strain
//   (Love, A treatise on the mathematical theory of elasticity, 1927,
//   section 200) is (lambda + 2 mu) k R J_0(k R) = 2 mu J_1(k R), omega = k
//   c_p. The hoop terms carry half of the stiffness of this mode: with
//   the hoop force sigma_tt N_i / r left out, or the hoop rate v_r / r, the
//   measured period is 2.01 times Love's (both planted, both fail);
// - a short cylinder settled on a friction floor (scenes/
//   resting_cylinder.prm): the floor force is the full ring's weight M g,
//   and the traction file's normal traction, each node's force over its
//   ring area 2 pi h (2 x_i + x_j) / 6 per face, is rho g H between the
//   axis and the rim within 5 % (the rough floor holds the base's Poisson
//   expansion, so the pressure is not exactly uniform: 2.7 % measured; a
//   plane area would be off by the factor 2 pi x);
// - quasi-static, the same hoop terms with their tangent:
//   - a long solid cylinder under a lateral pressure p with slip ends
//     (scenes/pressed_cylinder.prm): the state is uniform, sigma_r =
//     sigma_t = -p, so u_r = -p (1 + nu) (1 - 2 nu) r / E at every radius;
//     checked within 1 % at mid-radius and on the outer face;
//   - a thick-walled cylinder under internal pressure with slip ends
//     (../prm/thick_cylinder.prm) against Lame's solution: sigma_r = A -
//     B / r^2, sigma_t = A + B / r^2, A = p a^2 / (b^2 - a^2), B = A b^2,
//     u_r = (1 + nu) / E ((1 - 2 nu) A r + B / r), within 2 % on both
//     faces;
//   - and in both, the strain energy in the time series (the points'
//     stress work) against Clapeyron's half the work of the final load,
//     which ties the stresses to the closed form (the time series carries
//     no stresses); within 2 %, since the loaded points hand the traction
//     to the nodes by N(x_P), a quarter of it to the inner node of their
//     cell, not on the face (measured 1.1 % and 1.7 % low).

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tests.h"

using namespace dealii;

namespace
{
  /** The root of x J_0(x) = c J_1(x) in [1, 3], by bisection. */
  double
  breathing_root(const double c)
  {
    auto   f = [c](const double x) {
      return x * std::cyl_bessel_j(0., x) - c * std::cyl_bessel_j(1., x);
    };
    double a = 1., b = 3.;
    for (unsigned int k = 0; k < 100; ++k)
      {
        const double m = 0.5 * (a + b);
        (f(a) * f(m) <= 0. ? b : a) = m;
      }
    return 0.5 * (a + b);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  {
    auto csv = mpm_tests::run_scene("scenes/falling_rings.prm",
                                    "output-rings");
    const double rho = 1000., g = 9.81;
    const double expected =
      rho * numbers::PI *
      (0.1 * 0.1 * 0.2 + (0.45 * 0.45 - 0.25 * 0.25) * 0.3);
    const double M = csv["mass"][0];
    double fall_gap = 0., radius_gap = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        const double t = csv["time"][n];
        fall_gap = std::max(fall_gap,
                            std::abs(csv["momentum_y"][n] + M * g * t));
        radius_gap =
          std::max(radius_gap, std::abs(csv["centre_of_mass_x"][n] -
                                        csv["centre_of_mass_x"][0]));
      }
    deallog << "ring masses " << M << " kg against " << expected
            << " kg; " << csv["time"].size() << " rows of free fall"
            << std::endl;
    // The time series keeps 12 digits.
    mpm_tests::check("the ring masses sum to rho pi (R^2 H + (b^2 - a^2) "
                     "H') to 1e-11",
                     std::abs(M / expected - 1.) < 1e-11);
    mpm_tests::check("free fall: momentum -M g t to 1e-10 M g t_end",
                     fall_gap < 1e-10 * M * g * 0.2);
    mpm_tests::check("free fall: no radial motion (1e-13 m)",
                     radius_gap < 1e-13);
  }

  // Explicit, and Newmark (beta = 1/4, gamma = 1/2, dt = 0.2 ms: 64 steps
  // a period, so its period error (omega dt)^2 / 12 is below 0.1 %).
  for (const bool newmark : {false, true})
    {
      auto csv = mpm_tests::run_scene(
        "scenes/breathing_cylinder.prm",
        newmark ? "output-breathing-newmark" : "output-breathing",
        newmark ? std::vector<std::string>{"Time stepping/Scheme=Newmark",
                                           "Time stepping/Time step=2e-4"} :
                  std::vector<std::string>{});
      const double E = 1e7, nu = 0.3, rho = 1000., R = 0.5;
      const double c_p =
        std::sqrt(E * (1. - nu) / ((1. + nu) * (1. - 2. * nu)) / rho);
      const double kR = breathing_root((1. - 2. * nu) / (1. - nu));
      const double period = 2. * numbers::PI * R / (kR * c_p);

      // Zero crossings of x_cm - x_cm(0), by linear interpolation.
      const std::vector<double> &t = csv["time"];
      const std::vector<double> &x = csv["centre_of_mass_x"];
      std::vector<double>        crossings;
      double                     amplitude = 0.;
      for (unsigned int n = 1; n < t.size(); ++n)
        {
          const double a = x[n - 1] - x[0], b = x[n] - x[0];
          amplitude      = std::max(amplitude, std::abs(b));
          if (n > 1 && a * b < 0.)
            crossings.push_back(t[n - 1] + (t[n] - t[n - 1]) * a / (a - b));
        }
      const double measured =
        crossings.empty() ? 0. : 2. * crossings.back() / crossings.size();
      deallog << "k R = " << kR << "; period " << measured << " s against "
              << period << " s (" << crossings.size()
              << " half periods, ratio " << measured / period
              << "); centre of mass swings by " << amplitude << " m"
              << std::endl;
      const std::string scheme = newmark ? " (Newmark)" : " (explicit)";
      mpm_tests::check("breathing cylinder" + scheme +
                         ": at least 6 half periods",
                       crossings.size() >= 6);
      mpm_tests::check("breathing cylinder" + scheme +
                         ": the period of the fundamental radial mode within "
                         "1 %",
                       std::abs(measured / period - 1.) < 0.01);
    }

  // A cylinder at rest on a friction floor: the floor's force is the full
  // ring's weight, and its traction file, force over each node's ring
  // area, the pressure rho g H.
  {
    auto csv = mpm_tests::run_scene("scenes/resting_cylinder.prm",
                                    "output-resting");
    const double M = csv["mass"].back(), g = 9.81;
    // The mean over the last 200 steps, once settled.
    const std::vector<double> &N = csv["bottom_normal_force"];
    double                     mean = 0.;
    for (unsigned int n = N.size() - 200; n < N.size(); ++n)
      mean += N[n] / 200.;
    std::string last;
    for (const auto &entry :
         std::filesystem::directory_iterator("output-resting"))
      if (entry.path().filename().string().rfind("bottom_tractions_", 0) ==
            0 &&
          entry.path().string() > last)
        last = entry.path().string();
    mpm_tests::Columns tractions = mpm_tests::read_csv(last);
    const double       pressure  = 1000. * g * 0.1, h = 0.025, R = 0.3;
    double             largest   = 0.;
    for (unsigned int k = 0; k < tractions["x"].size(); ++k)
      if (tractions["x"][k] > 0.5 * h && tractions["x"][k] < R - 0.5 * h)
        largest = std::max(largest, std::abs(tractions["normal_traction"][k] /
                                               pressure -
                                             1.));
    deallog << "resting cylinder: floor force / M g = " << mean / (M * g)
            << "; floor pressure off rho g H by at most " << largest
            << " between the axis and the rim" << std::endl;
    mpm_tests::check("resting cylinder: the floor carries the ring's weight "
                     "to 1e-6",
                     std::abs(mean / (M * g) - 1.) < 1e-6);
    mpm_tests::check("resting cylinder: the floor pressure is rho g H within "
                     "5 % between the axis and the rim",
                     largest < 0.05);
  }

  // Quasi-static: u_r of the tracked points (E = 1e7 Pa, nu = 0.3, p = 1e4
  // Pa) against the closed forms.
  const double E = 1e7, nu = 0.3, p = 1e4;
  auto radial_displacement = [](mpm_tests::Columns &csv,
                                const unsigned int k) {
    const std::string x = "point" + std::to_string(k) + "_x";
    return csv[x].back() - csv[x].front();
  };
  {
    auto csv = mpm_tests::run_scene("scenes/pressed_cylinder.prm",
                                    "output-pressed");
    double largest = 0.;
    for (const auto &[k, r] : {std::pair{0u, 0.09875}, {1u, 0.19875}})
      {
        const double exact = -p * (1. + nu) * (1. - 2. * nu) * r / E;
        const double ratio = radial_displacement(csv, k) / exact;
        deallog << "pressed cylinder, r = " << r << ": u_r / closed form = "
                << ratio << std::endl;
        largest = std::max(largest, std::abs(ratio - 1.));
      }
    // Clapeyron: the stored energy is half the work of the final load,
    // p 2 pi R H |u_r(R)| / 2 (R = 0.2 m, H = 0.01 m).
    const double energy = 0.5 * p * 2. * numbers::PI * 0.2 * 0.01 * p *
                          (1. + nu) * (1. - 2. * nu) * 0.2 / E;
    const double energy_ratio = csv["strain_energy"].back() / energy;
    deallog << "pressed cylinder: strain energy / closed form = "
            << energy_ratio << std::endl;
    mpm_tests::check("pressed cylinder: the uniform state's u_r within 1 %",
                     largest < 0.01);
    mpm_tests::check("pressed cylinder: the strain energy (the stresses "
                     "against the strains) within 2 %",
                     std::abs(energy_ratio - 1.) < 0.02);
  }
  {
    auto csv = mpm_tests::run_scene("../prm/thick_cylinder.prm",
                                    "output-lame");
    const double a = 0.1, b = 0.2;
    const double A = p * a * a / (b * b - a * a), B = A * b * b;
    double       largest = 0.;
    for (const auto &[k, r] : {std::pair{0u, 0.10125}, {1u, 0.19875}})
      {
        const double exact = (1. + nu) / E * ((1. - 2. * nu) * A * r + B / r);
        const double ratio = radial_displacement(csv, k) / exact;
        deallog << "thick-walled cylinder, r = " << r
                << ": u_r / Lame = " << ratio << std::endl;
        largest = std::max(largest, std::abs(ratio - 1.));
      }
    // Clapeyron: p 2 pi a H u_r(a) / 2 (H = 0.01 m).
    const double energy =
      0.5 * p * 2. * numbers::PI * a * 0.01 * (1. + nu) / E *
      ((1. - 2. * nu) * A * a + B / a);
    const double energy_ratio = csv["strain_energy"].back() / energy;
    deallog << "thick-walled cylinder: strain energy / Lame's = "
            << energy_ratio << std::endl;
    mpm_tests::check("thick-walled cylinder: u_r of both faces within 2 % of "
                     "Lame's",
                     largest < 0.02);
    mpm_tests::check("thick-walled cylinder: the strain energy within 2 % "
                     "of Lame's",
                     std::abs(energy_ratio - 1.) < 0.02);
  }
}
