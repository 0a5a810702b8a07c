// Points on a mesh of the body's own (Point placement = body mesh,
// scenes/body_mesh.prm, h = 0.05): a disk of radius 0.2 and a box whose
// sides lie off the grid lines, then a sphere in 3D. Checked against the
// geometry:
// - the disk: deal.II's balanced ball (12 cells) refined twice, 192 cells
//   of 0.065 m^2 / 100 on average (no larger than h^2), 2 x 2 Gauss points
//   each: 768 points. Their mass is rho pi R^2 within 1e-5 (the cubic
//   mapping follows the circle; straight-sided cells would lose 0.6 %),
//   their centre of mass is the disk's centre and their extent is the same
//   in the four directions (1e-12: the ball mesh is symmetric);
// - the box, 0.33 x 0.28 m: 7 x 6 cells (no wider than h), 168 points,
//   mass rho times its area and centre of mass at its centre (1e-12), and
//   the outermost points half a Gauss offset inside each side: the
//   lowest at y = 0.13 + (1 - 1/sqrt 3) / 2 times 0.28 / 6 (1e-12);
// - both at once: the sum of the two;
// - a box seeded on the grid's sub-cells across the disk, after it: the
//   disk's points and those of the box's lattice that lie outside the disk
//   (counted here from the lattice's geometry);
// - axisymmetric, the box from the axis and the disk away from it: a
//   cylinder and a torus, mass rho (pi R^2 H + 2 pi^2 R_c r^2) within 1e-5;
// - inflow: a disk of radius 0.1 released three times, each release
//   building its mesh afresh: k times its 192 points and its mass after
//   the k-th;
// - a box of 7 x 7 cells of one point each, whose points all lie on grid
//   nodes, across the two ranks' cells: 49 points, each seeded once, on
//   the grid as 400 coarse cells and as 25 refined twice;
// - the sphere (R = 0.3, h = 0.1): the balanced ball (32 cells) refined
//   once, 256 cells of 2 x 2 x 2 points: 2048 points, mass 4/3 pi R^3 rho
//   within 1e-4, centre of mass at its centre (1e-12).
// On two ranks each point is seeded by one rank only: the same counts and
// masses.

#include <deal.II/base/mpi.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

namespace {
constexpr double rho = 1000.;

/** Either body alone: the other moved out of the grid. */
const std::vector<std::string> box_away = {"Bodies/box/Lower corner=2, 2",
                                           "Bodies/box/Upper corner=3, 3"};
const std::vector<std::string> disk_away = {"Bodies/disk/Center=5, 5"};

/** The time series of the scene (one step) with `settings`. */
mpm_tests::Columns seeded(const std::string &directory,
                          const std::vector<std::string> &settings) {
  std::vector<std::string> all;
  all.insert(all.end(), settings.begin(), settings.end());
  return mpm_tests::run_scene("scenes/body_mesh.prm", directory, all);
}
} // namespace

int main(int argc, char **argv) {
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const double pi = numbers::PI;

  // Each body alone, run once: the cases below that put them together
  // compare with these.
  auto disk = seeded("output-disk", box_away);
  auto box  = seeded("output-box", disk_away);
  {
    auto &csv = disk;
    deallog << "disk: " << static_cast<unsigned int>(csv["points"][0])
            << " points" << std::endl;
    const double R = 0.2, cx = 0.3, cy = 0.5;
    const double extents[4] = {csv["max_x"][0] - cx, cx - csv["min_x"][0],
                               csv["max_y"][0] - cy, cy - csv["min_y"][0]};
    bool symmetric = true;
    for (const double e : extents)
      symmetric = symmetric && std::abs(e - extents[0]) < 1e-12 && e < R;
    mpm_tests::check("disk: 768 points, mass rho pi R^2 within 1e-5",
                     csv["points"][0] == 768. &&
                         std::abs(csv["mass"][0] / (rho * pi * R * R) - 1.) <
                             1e-5);
    mpm_tests::check("disk: centre of mass at its centre, extent the same "
                     "in four directions (1e-12)",
                     std::abs(csv["centre_of_mass_x"][0] - cx) < 1e-12 &&
                         std::abs(csv["centre_of_mass_y"][0] - cy) < 1e-12 &&
                         symmetric);
  }

  {
    auto &csv = box;
    deallog << "box: " << static_cast<unsigned int>(csv["points"][0])
            << " points" << std::endl;
    const double offset = (1. - 1. / std::sqrt(3.)) / 2.;
    mpm_tests::check(
        "box: 168 points, mass rho times its area, centre of mass at its "
        "centre, outermost points half a Gauss offset inside (1e-12)",
        csv["points"][0] == 168. &&
            std::abs(csv["mass"][0] - rho * 0.33 * 0.28) < 1e-12 * rho &&
            std::abs(csv["centre_of_mass_x"][0] - 0.765) < 1e-12 &&
            std::abs(csv["centre_of_mass_y"][0] - 0.27) < 1e-12 &&
            std::abs(csv["min_x"][0] - (0.6 + offset * 0.33 / 7.)) < 1e-12 &&
            std::abs(csv["min_y"][0] - (0.13 + offset * 0.28 / 6.)) < 1e-12 &&
            std::abs(csv["max_y"][0] - (0.41 - offset * 0.28 / 6.)) < 1e-12);
  }

  {
    auto both = seeded("output-both", {});
    mpm_tests::check(
        "disk and box together: the sum of the two",
        both["points"][0] == disk["points"][0] + box["points"][0] &&
            std::abs(both["mass"][0] - disk["mass"][0] - box["mass"][0]) <
                1e-12 * rho);
  }

  // A body on the grid's sub-cells (centres) across the disk, named after
  // it: it keeps the points of its lattice outside the disk, which the
  // disk's mesh fills.
  {
    auto csv = seeded("output-overlap",
                      {"Bodies/box/Point placement=centres",
                       "Bodies/box/Lower corner=0.2, 0.3",
                       "Bodies/box/Upper corner=0.6, 0.7"});
    const double a       = 0.025; // 2 x 2 points per cell of h = 0.05
    unsigned int outside = 0;
    for (unsigned int i = 0; i < 16; ++i)
      for (unsigned int j = 0; j < 16; ++j)
        {
          const double x = 0.2 + a * (i + 0.5), y = 0.3 + a * (j + 0.5);
          outside += (x - 0.3) * (x - 0.3) + (y - 0.5) * (y - 0.5) >= 0.04;
        }
    deallog << "overlap: " << static_cast<unsigned int>(csv["points"][0])
            << " points, " << outside << " of the box's lattice outside the "
            << "disk" << std::endl;
    mpm_tests::check(
      "a lattice box across the disk keeps its points outside the disk: "
      "the disk's mass plus theirs (1e-12)",
      csv["points"][0] == disk["points"][0] + outside &&
        std::abs(csv["mass"][0] - disk["mass"][0] - rho * a * a * outside) <
          1e-12 * rho);
  }

  // Axisymmetric (x the radius): the box from the axis is a cylinder, the
  // disk a torus; each point is the ring its area sweeps.
  {
    auto csv = seeded("output-axisymmetric",
                      {"Grid/Geometry=axisymmetric",
                       "Boundary conditions/Slip boundaries=left",
                       "Bodies/box/Lower corner=0, 0.13",
                       "Bodies/box/Upper corner=0.33, 0.41",
                       "Bodies/disk/Center=0.6, 0.7"});
    const double cylinder = pi * 0.33 * 0.33 * 0.28;
    const double torus    = 2. * pi * 0.6 * pi * 0.2 * 0.2;
    mpm_tests::check("axisymmetric: a cylinder and a torus, mass rho (pi "
                     "R^2 H + 2 pi^2 R_c r^2) within 1e-5",
                     std::abs(csv["mass"][0] / (rho * (cylinder + torus)) -
                              1.) < 1e-5);
  }

  // Inflow: a disk of radius 0.1 released three times, 0.06 s apart, at
  // 4 m/s downwards, so that each release finds its region empty; each
  // release builds the disk's mesh afresh.
  {
    auto csv = seeded("output-inflow",
                      {"Bodies/box/Lower corner=2, 2",
                       "Bodies/box/Upper corner=3, 3",
                       "Bodies/disk/Center=0.3, 0.85",
                       "Bodies/disk/Radius=0.1",
                       "Bodies/disk/Initial velocity=0; -4",
                       "Bodies/disk/Releases=3",
                       "Bodies/disk/Release interval=0.06",
                       "Time stepping/End time=0.13",
                       "Time stepping/Time step=0.001"});
    const double one     = csv["mass"][0];
    bool         counted = csv["points"][0] == 192.;
    for (unsigned int r = 0; r < csv["time"].size(); ++r)
      {
        // A release at t enters the step that starts at t: the row at
        // t still has the releases before it.
        const double k =
          std::max(1., std::ceil(csv["time"][r] / 0.06 - 1e-9));
        counted        = counted && csv["points"][r] == k * 192. &&
                  std::abs(csv["mass"][r] - k * one) < 1e-12 * rho;
      }
    mpm_tests::check("inflow: after the k-th release of the disk, k times "
                     "its 192 points and its mass (1e-12), three in all",
                     counted && csv["points"].back() == 3. * 192. &&
                       std::abs(one / (rho * pi * 0.01) - 1.) < 1e-4);
  }

  // The same grid as 400 coarse cells and as 25 refined twice: on the
  // refined one each rank has ghost and artificial cells of its own.
  for (const std::string grid : {"20, 20", "5, 5"})
    {
      auto csv =
        seeded("output-on-nodes",
               {"Grid/Arguments=" + grid + " : 0, 0 : 1, 1 : true",
                std::string("Grid/Global refinements=") +
                  (grid == "5, 5" ? "2" : "0"),
                "Bodies/disk/Center=5, 5",
                "Bodies/box/Lower corner=0.575, 0.325",
                "Bodies/box/Upper corner=0.925, 0.675",
                "Bodies/box/Points per cell direction=1"});
      mpm_tests::check("points on grid nodes (" + grid +
                         " coarse cells): 49, each seeded once",
                       csv["points"][0] == 49. &&
                         std::abs(csv["mass"][0] - rho * 0.35 * 0.35) <
                           1e-12 * rho);
    }


  {
    auto csv = seeded(
        "output-sphere",
        {"Dimension=3", "Grid/Arguments=10, 10, 10 : 0, 0, 0 : 1, 1, 1 : true",
         "Bodies/box/Lower corner=2, 2, 2", "Bodies/box/Upper corner=3, 3, 3",
         "Bodies/disk/Shape=sphere", "Bodies/disk/Center=0.5, 0.5, 0.5",
         "Bodies/disk/Radius=0.3"});
    deallog << "sphere: " << static_cast<unsigned int>(csv["points"][0])
            << " points" << std::endl;
    const double R = 0.3;
    mpm_tests::check(
        "sphere: 2048 points, mass 4/3 pi R^3 rho within 1e-4, centre of "
        "mass at its centre (1e-12)",
        csv["points"][0] == 2048. &&
            std::abs(csv["mass"][0] / (rho * 4. / 3. * pi * R * R * R) - 1.) <
                1e-4 &&
            std::abs(csv["centre_of_mass_x"][0] - 0.5) < 1e-12 &&
            std::abs(csv["centre_of_mass_y"][0] - 0.5) < 1e-12 &&
            std::abs(csv["centre_of_mass_z"][0] - 0.5) < 1e-12);
  }
}
