// Walls with Coulomb friction (Boundary conditions/Friction boundaries),
// explicit MUSL, checked against mechanics from outside the code:
// - an elastic block on an inclined plane (scenes/friction_block.prm:
//   gravity tilted by 30 degrees): with mu = 0.2 < tan 30 its centre of
//   mass slides with a = g (sin 30 - mu cos 30) (the rigid-block law),
//   checked within 1 % over 0.5 s, and the same block on a frictionless
//   slip floor (a = g sin 30) and a fixed floor (a = 0) misses that law
//   by far, so the check tells friction from its absence and from no-slip;
//   with mu = 0.7 > tan 30 it sticks (|x - x0| < 1e-4 m);
// - at every step, the wall force of the time series: |T| <= mu N to
//   round-off; sliding, the friction impulse is mu times the normal
//   impulse within 1 % (nodes at the block's edges, with little mass and
//   large accelerations, may stick while the block slides); and the point
//   momentum changes by dt (M g - wall force) to round-off, since the
//   wall's reaction is the only other force (Newton's third law at the
//   nodes);
// - at each output time, every node of the traction file: |t_T| <= mu t_N
//   to round-off, t_N >= 0, and, sliding, |t_T| = mu t_N at every node
//   that carries load; the normal tractions integrate to the time series'
//   normal force (the end nodes of the floor carry half a cell of it);
// - the block thrown up off the floor (initial velocity 0.5, 2 m/s): the
//   one-sided wall lets it go, so its momentum is M (v0 + g t) to the 12
//   digits of the time series, as in free flight; a slip floor, which holds
//   the block's bottom nodes, does not let it go;
// - the same with the implicit Newmark scheme (Bossak alpha = -0.3, whose
//   damping settles the block as pure PIC does explicitly; dt = 5 ms, 100
//   steps), where the active set finds the nodes that stick and slide:
//   the same rigid-block law within 1 %, against the slip and fixed
//   floors; mu = 0.7 sticks; |T| <= mu N at every step and node, and
//   |T| = mu N where the block slides (to Newton's tolerance); thrown up,
//   the block's momentum is that of the same block with no floor (the
//   Newmark start differs from M (v0 + g t)), and a slip floor misses it;
// - a cube in 3D (scenes/friction_cube.prm, Newmark) with gravity tilted
//   towards the floor's diagonal: it slides along the diagonal with the
//   same law within 1 % (the sliding directions follow the motion), with
//   |T| = mu N;
// - quasi-static, a block pressed onto a rough base (prm/rough_base.prm,
//   mu = 0.3, half model with a slip wall on the axis): the base carries
//   the load, p B (vertical equilibrium); Coulomb at every node; near the
//   axis the base sticks (|t_T| < mu t_N / 2) and at the free edge the
//   Poisson expansion slides it (|t_T| = mu t_N); on a frictionless base
//   (mu = 0) no shear at all, and the block spreads wider than on the
//   rough one.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>
#include <filesystem>
#include <tuple>
#include <utility>

#include "tests.h"

using namespace dealii;

namespace
{
  const double g     = 9.81;
  const double theta = numbers::PI / 6.;

  mpm_tests::Columns
  run(const std::string &             name,
      const std::vector<std::string> &settings,
      const std::string &             scene = "scenes/friction_block.prm")
  {
    // No traction files of an earlier run.
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::remove_all("output-" + name);
    MPI_Barrier(MPI_COMM_WORLD);
    return mpm_tests::run_scene(scene, "output-" + name, settings);
  }

  /** The centre of mass's acceleration along the plane, by a fit of x(t). */
  double
  acceleration_along_plane(mpm_tests::Columns &csv)
  {
    // x - x0 = a t^2 / 2 + v-free: fit a by least squares over all rows.
    const double x0 = csv["centre_of_mass_x"][0];
    double       num = 0., den = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        const double s = 0.5 * csv["time"][n] * csv["time"][n];
        num += s * (csv["centre_of_mass_x"][n] - x0);
        den += s * s;
      }
    return num / den;
  }

  /**
   * The block's acceleration along the plane on a frictionless slip floor
   * and on a fixed floor, with `settings` (runs named with `prefix`).
   */
  std::pair<double, double>
  slip_and_fixed_floors(const std::string &             prefix,
                        const std::vector<std::string> &settings)
  {
    std::vector<std::string> slip = settings, fixed = settings;
    for (auto *floor : {&slip, &fixed})
      floor->push_back("Boundary conditions/Friction boundaries=");
    slip.push_back("Boundary conditions/Slip boundaries=bottom");
    fixed.push_back("Boundary conditions/Fixed boundaries=bottom");
    const double exact   = g * (std::sin(theta) - 0.2 * std::cos(theta));
    auto         slip_csv  = run(prefix + "frictionless", slip);
    auto         fixed_csv = run(prefix + "fixed", fixed);
    const double a_slip  = acceleration_along_plane(slip_csv);
    const double a_fixed = acceleration_along_plane(fixed_csv);
    deallog << (prefix.empty() ? "" : "Newmark, ")
            << "slip floor: a / (g sin 30) = " << a_slip / (g * 0.5)
            << "; fixed floor: a / (g (sin - mu cos)) = " << a_fixed / exact
            << std::endl;
    return {a_slip, a_fixed};
  }



  /**
   * The largest travel of the centre of mass from its start, and the
   * largest |T| - mu N, over the rows.
   */
  std::pair<double, double>
  travel_and_bound(mpm_tests::Columns &csv, const double mu)
  {
    double travel = 0., bound = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        travel = std::max(travel,
                          std::abs(csv["centre_of_mass_x"][n] -
                                   csv["centre_of_mass_x"][0]));
        bound  = std::max(bound,
                         std::abs(csv["bottom_tangential_force"][n]) -
                           mu * csv["bottom_normal_force"][n]);
      }
    return {travel, bound};
  }



  /**
   * Check the traction files of a run; returns the number of files. The
   * explicit law sets the Coulomb bound exactly: it holds to 1e-12 of the
   * largest traction. In an implicit run, the wall's force at a node is
   * the node's out-of-balance force, so the bound holds as far as the
   * node's balance does: Newton stops once |r| < tol |f_ext|, and
   * |f_ext| is at most the sum of the nodal external forces, the load W.
   * Each node's force is then right to tol W, its normal and tangential
   * tractions to tol W over the node's share of the floor, and
   * |t_T| - mu t_N to (1 + mu) times that. `unbalanced_force` is tol W
   * for an implicit run and 0 for an explicit one.
   */
  unsigned int
  check_tractions(const std::string & directory,
                  const double        mu,
                  const bool          slides,
                  mpm_tests::Columns &series,
                  const double        unbalanced_force = 0.)
  {
    unsigned int files = 0;
    bool         bound = true, slip = true, integral = true;
    for (const auto &entry : std::filesystem::directory_iterator(directory))
      {
        const std::string name = entry.path().filename().string();
        if (name.rfind("bottom_tractions_", 0) != 0)
          continue;
        ++files;
        const unsigned int step =
          std::stoi(name.substr(std::string("bottom_tractions_").size()));
        mpm_tests::Columns t = mpm_tests::read_csv(entry.path().string());
        double             largest = 0., sum = 0.;
        for (const double n : t["normal_traction"])
          largest = std::max(largest, n);
        // Interior nodes carry h of the floor, the end nodes h / 2.
        const double h = 0.05;
        for (unsigned int k = 0; k < t["x"].size(); ++k)
          {
            const double n   = t["normal_traction"][k];
            const double tt  = std::abs(t["tangential_traction"][k]);
            const bool   end = t["x"][k] < 1e-12 || t["x"][k] > 2. - 1e-12;
            const double share = end ? 0.5 * h : h;
            const double balance =
              unbalanced_force > 0. ? (1. + mu) * unbalanced_force / share :
                                      1e-12 * largest;
            bound &= n >= -balance && tt <= mu * n + balance;
            if (slides && n > 1e-6 * largest)
              slip &= std::abs(tt - mu * n) <=
                      std::max(balance, 1e-9 * largest);
            sum += n * share;
          }
        // The row of the time series at this step.
        for (unsigned int r = 0; r < series["step"].size(); ++r)
          if (static_cast<unsigned int>(series["step"][r]) == step)
            integral &= std::abs(sum - series["bottom_normal_force"][r]) <=
                        1e-9 * series["bottom_normal_force"][r];
      }
    mpm_tests::check("tractions: t_N >= 0 and |t_T| <= mu t_N at every "
                     "node of every traction file",
                     files > 0 && bound);
    if (slides)
      mpm_tests::check("tractions: |t_T| = mu t_N at every node that "
                       "carries load, while the block slides",
                       slip);
    mpm_tests::check("tractions: their integral over the floor is the "
                     "normal force of the time series",
                     integral);
    return files;
  }


  /** The Newmark runs: the same laws, solved by the active set. */
  void
  check_newmark()
  {
    const std::vector<std::string> newmark = {"Time stepping/Scheme=Newmark",
                                              "Time stepping/Time step=0.005",
                                              "Newmark/Bossak alpha=-0.3"};
    const auto with = [&](const std::vector<std::string> &more) {
      std::vector<std::string> settings = newmark;
      settings.insert(settings.end(), more.begin(), more.end());
      return settings;
    };
    const double exact = g * (std::sin(theta) - 0.2 * std::cos(theta));

    auto         slide = run("newmark_slide", with({}));
    const double a     = acceleration_along_plane(slide);
    double       bound = 0., slip_gap = 0.;
    for (unsigned int n = 1; n < slide["time"].size(); ++n)
      {
        const double N = slide["bottom_normal_force"][n];
        const double T = std::abs(slide["bottom_tangential_force"][n]);
        bound          = std::max(bound, T - 0.2 * N);
        slip_gap       = std::max(slip_gap, std::abs(T - 0.2 * N) / N);
      }
    deallog << "Newmark, mu = 0.2: a / (g (sin - mu cos)) = " << a / exact
            << "; largest |T - mu N| / N "
            << (slip_gap < 1e-9 ? "below 1e-9" : std::to_string(slip_gap))
            << std::endl;
    mpm_tests::check("Newmark, mu = 0.2: the block slides with g (sin 30 - "
                     "mu cos 30) within 1 %",
                     std::abs(a / exact - 1.) < 0.01);
    mpm_tests::check("Newmark, mu = 0.2: |T| = mu N at every step while it "
                     "slides, to 1e-9",
                     bound < 1e-9 * slide["mass"][0] * g && slip_gap < 1e-9);
    check_tractions(
      "output-newmark_slide", 0.2, true, slide, 1e-8 * slide["mass"][0] * g);

    const auto [a_slip, a_fixed] = slip_and_fixed_floors("newmark_", newmark);
    mpm_tests::check("Newmark: the slip and fixed floors miss the Coulomb "
                     "law by more than 10 %",
                     std::abs(a_slip / exact - 1.) > 0.1 &&
                       std::abs(a_fixed / exact - 1.) > 0.1);

    auto stick =
      run("newmark_stick",
          with({"Boundary conditions/Friction boundaries=bottom: 0.7"}));
    double travel;
    std::tie(travel, bound) = travel_and_bound(stick, 0.7);
    deallog << "Newmark, mu = 0.7: largest travel " << travel << " m"
            << std::endl;
    mpm_tests::check("Newmark, mu = 0.7: the block sticks, |x - x0| < 1e-4 "
                     "m, and |T| <= mu N at every step",
                     travel < 1e-4 && bound < 1e-9 * stick["mass"][0] * g);
    check_tractions(
      "output-newmark_stick", 0.7, false, stick, 1e-8 * stick["mass"][0] * g);

    // 3D: sliding along the floor's diagonal.
    {
      auto cube = run("newmark_cube", {}, "scenes/friction_cube.prm");
      // The slope of the diagonal momentum over the last 0.1 s, when the
      // block has settled on the floor.
      const unsigned int last = cube["time"].size() - 1, first = last - 10;
      const auto diagonal = [&](const unsigned int n) {
        return (cube["momentum_x"][n] + cube["momentum_z"][n]) /
               std::sqrt(2.);
      };
      const double a_cube = (diagonal(last) - diagonal(first)) /
                            (cube["time"][last] - cube["time"][first]) /
                            cube["mass"][0];
      double across = 0., slip_3d = 0.;
      for (unsigned int n = first; n <= last; ++n)
        {
          across = std::max(across,
                            std::abs(cube["momentum_x"][n] -
                                     cube["momentum_z"][n]) /
                              std::abs(diagonal(n)));
          slip_3d = std::max(slip_3d,
                             std::abs(cube["bottom_tangential_force"][n] -
                                      0.2 * cube["bottom_normal_force"][n]) /
                               cube["bottom_normal_force"][n]);
        }
      deallog << "Newmark, 3D cube: a / (g (sin - mu cos)) = "
              << a_cube / exact << std::endl;
      mpm_tests::check("Newmark, 3D cube: it slides along the diagonal "
                       "(momenta x and z equal to 1e-6) with g (sin 30 - mu "
                       "cos 30) within 1 %, |T| = mu N to 1e-9",
                       std::abs(a_cube / exact - 1.) < 0.01 &&
                         across < 1e-6 && slip_3d < 1e-9);
    }

    // Thrown up: against the same block with no floor at all.
    const std::vector<std::string> thrown = {
      "Bodies/block/Initial velocity=0.5; 2", "Time stepping/End time=0.2"};
    auto flight = run("newmark_flight",
                      with({thrown[0], thrown[1],
                            "Boundary conditions/Friction boundaries="}));
    for (const bool one_sided : {true, false})
      {
        auto csv = run(one_sided ? "newmark_thrown" : "newmark_thrown_slip",
                       with({thrown[0], thrown[1],
                             one_sided ?
                               "Boundary conditions/Friction boundaries="
                               "bottom: 0.5" :
                               "Boundary conditions/Friction boundaries=",
                             one_sided ?
                               "Boundary conditions/Slip boundaries=" :
                               "Boundary conditions/Slip boundaries="
                               "bottom"}));
        const double M   = csv["mass"][0];
        double       gap = 0.;
        for (unsigned int n = 0; n < csv["time"].size(); ++n)
          for (const char *column : {"momentum_x", "momentum_y"})
            gap = std::max(gap,
                           std::abs(csv[column][n] - flight[column][n]) /
                             (M * 2.));
        deallog << "Newmark, " << (one_sided ? "friction" : "slip")
                << " floor: momentum off the flight without a floor by "
                << (gap < 1e-10 ? "less than 1e-10" : std::to_string(gap))
                << " M v0" << std::endl;
        if (one_sided)
          mpm_tests::check("Newmark, thrown up: the friction floor lets the "
                           "block go (momentum of the flight to 1e-10)",
                           gap < 1e-10);
        else
          mpm_tests::check("Newmark, thrown up: a slip floor holds it back "
                           "(more than 1 % off the flight)",
                           gap > 0.01);
      }
  }


  /** A block pressed onto a rough and a frictionless base. */
  void
  check_quasi_static()
  {
    const double p = 1e5, B = 1., mu = 0.3;
    const auto   run_base = [](const std::string &name, const std::string &mu) {
      return run(name,
                 {"Boundary conditions/Friction boundaries=bottom: " + mu},
                 "../prm/rough_base.prm");
    };
    auto rough = run_base("rough_base", "0.3");
    auto smooth = run_base("smooth_base", "0");
    const unsigned int last = rough["time"].size() - 1;
    deallog << "quasi-static, rough base: normal force / (p B) = "
            << rough["bottom_normal_force"][last] / (p * B) << std::endl;
    mpm_tests::check("quasi-static: the base carries p B (1e-8)",
                     std::abs(rough["bottom_normal_force"][last] / (p * B) -
                              1.) < 1e-8 &&
                       std::abs(smooth["bottom_normal_force"][last] /
                                  (p * B) -
                                1.) < 1e-8);
    check_tractions(
      "output-rough_base", mu, false, rough, 1e-10 * p * B);

    // The last traction file: stick near the axis, slip at the edge.
    const std::string step =
      std::to_string(static_cast<unsigned int>(rough["step"][last]));
    const std::string file = "bottom_tractions_" +
                             std::string(6 - step.size(), '0') + step +
                             ".csv";
    mpm_tests::Columns t = mpm_tests::read_csv("output-rough_base/" + file);
    mpm_tests::Columns t0 = mpm_tests::read_csv("output-smooth_base/" + file);
    bool   sticks = false, slides = false, no_shear = true;
    for (unsigned int k = 0; k < t["x"].size(); ++k)
      {
        const double x  = t["x"][k];
        const double n  = t["normal_traction"][k];
        const double tt = std::abs(t["tangential_traction"][k]);
        if (std::abs(x - 0.05) < 1e-9)
          sticks = tt > 0. && tt < 0.5 * mu * n;
        if (std::abs(x - 0.9) < 1e-9)
          slides = std::abs(tt - mu * n) < 1e-9 * p;
        no_shear &= std::abs(t0["tangential_traction"][k]) < 1e-9 * p;
      }
    deallog << "quasi-static: right edge of the block " << rough["max_x"][last]
            << " m on the rough base, " << smooth["max_x"][last]
            << " m on the frictionless one" << std::endl;
    mpm_tests::check("quasi-static, rough base: it sticks near the axis "
                     "(0 < |t_T| < mu t_N / 2 at x = 0.05) and slides at "
                     "the edge (|t_T| = mu t_N at x = 0.9)",
                     sticks && slides);
    mpm_tests::check("quasi-static, frictionless base: no shear (1e-9 p), "
                     "and the block spreads wider than on the rough base",
                     no_shear && smooth["max_x"][last] > rough["max_x"][last]);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  // Sliding: mu = 0.2.
  {
    auto csv = run("slide", {});
    const double a     = acceleration_along_plane(csv);
    const double exact = g * (std::sin(theta) - 0.2 * std::cos(theta));
    deallog << "mu = 0.2: a / (g (sin - mu cos)) = " << a / exact
            << std::endl;
    mpm_tests::check("mu = 0.2: the block slides with g (sin 30 - mu cos 30) "
                     "within 1 %",
                     std::abs(a / exact - 1.) < 0.01);
    double bound = 0., normal_impulse = 0., tangential_impulse = 0.;
    for (unsigned int n = 1; n < csv["time"].size(); ++n)
      {
        bound = std::max(bound,
                         std::abs(csv["bottom_tangential_force"][n]) -
                           0.2 * csv["bottom_normal_force"][n]);
        normal_impulse += csv["dt"][n] * csv["bottom_normal_force"][n];
        tangential_impulse +=
          csv["dt"][n] * csv["bottom_tangential_force"][n];
      }
    deallog << "mu = 0.2: friction impulse / normal impulse = "
            << tangential_impulse / normal_impulse << std::endl;
    mpm_tests::check("mu = 0.2: |T| <= mu N at every step, to 1e-12 M g",
                     bound < 1e-12 * csv["mass"][0] * g);
    mpm_tests::check("mu = 0.2: friction impulse = mu x normal impulse "
                     "within 1 %",
                     std::abs(tangential_impulse / normal_impulse / 0.2 - 1.) <
                       0.01);
    mpm_tests::check("mu = 0.2: momentum changes by the sum of dt (M g - wall force), "
                     "to 1e-9",
                     mpm_tests::floor_momentum_balance(csv, g, theta) < 1e-9);
    check_tractions("output-slide", 0.2, true, csv);
  }

  // The same block where the floor has no friction, and where it is fixed.
  {
    const double exact = g * (std::sin(theta) - 0.2 * std::cos(theta));
    const auto [a_slip, a_fixed] = slip_and_fixed_floors("", {});
    mpm_tests::check("a frictionless floor gives g sin 30 (within 1 %), "
                     "not the Coulomb law",
                     std::abs(a_slip / (g * 0.5) - 1.) < 0.01 &&
                       std::abs(a_slip / exact - 1.) > 0.1);
    mpm_tests::check("a fixed floor holds the block, far from the Coulomb "
                     "law",
                     std::abs(a_fixed / exact - 1.) > 0.5);
  }

  // Sticking: mu = 0.7.
  {
    auto csv =
      run("stick",
          {"Boundary conditions/Friction boundaries=bottom: 0.7"});
    const auto [travel, bound] = travel_and_bound(csv, 0.7);
    deallog << "mu = 0.7: largest travel " << travel << " m" << std::endl;
    mpm_tests::check("mu = 0.7: the block sticks, |x - x0| < 1e-4 m over "
                     "0.5 s",
                     travel < 1e-4);
    mpm_tests::check("mu = 0.7: |T| <= mu N at every step, to 1e-12 M g",
                     bound < 1e-12 * csv["mass"][0] * g);
    mpm_tests::check("mu = 0.7: momentum changes by the sum of dt (M g - wall force), "
                     "to 1e-9",
                     mpm_tests::floor_momentum_balance(csv, g, theta) < 1e-9);
    check_tractions("output-stick", 0.7, false, csv);
  }

  check_newmark();
  check_quasi_static();

  // Thrown up off the floor, without and with a one-sided wall.
  for (const bool one_sided : {true, false})
    {
      auto csv = run(one_sided ? "thrown" : "thrown_slip",
                     {"Bodies/block/Initial velocity=0.5; 2",
                      "Time stepping/End time=0.2",
                      one_sided ? "Boundary conditions/Friction boundaries="
                                  "bottom: 0.5" :
                                  "Boundary conditions/Friction boundaries=",
                      one_sided ? "Boundary conditions/Slip boundaries=" :
                                  "Boundary conditions/Slip boundaries="
                                  "bottom"});
      const double M   = csv["mass"][0];
      double       gap = 0.;
      for (unsigned int n = 0; n < csv["time"].size(); ++n)
        {
          const double t = csv["time"][n];
          gap            = std::max(
            gap,
            std::max(std::abs(csv["momentum_x"][n] -
                              M * (0.5 + g * std::sin(theta) * t)),
                     std::abs(csv["momentum_y"][n] -
                              M * (2. - g * std::cos(theta) * t))) /
              (M * 2.));
        }
      deallog << (one_sided ? "friction floor" : "slip floor")
              << ": momentum off free flight by " << gap << " M v0"
              << std::endl;
      if (one_sided)
        mpm_tests::check("thrown up: the friction floor lets the block go; "
                         "momentum of free flight to the time series' 12 "
                         "digits",
                         gap < 1e-10);
      else
        mpm_tests::check("thrown up: a slip floor holds it back (more than "
                         "1 % off free flight)",
                         gap > 0.01);
    }
  return 0;
}
