// The K0 procedure (Bodies/.../Initial stress = geostatic), on a
// Mohr-Coulomb layer 2 m deep between smooth walls:
// - the stored energy at t = 0 equals the integral of the elastic energy
//   density of sigma_v = -rho g (H - y), sigma_h = sigma_zz = K0 sigma_v,
//   w = (sigma:sigma - lambda/(3 lambda + 2 mu) tr(sigma)^2) / (4 mu), over
//   the layer: (rho g)^2 H^3/3 W times the density's factor. The points
//   sum it by the midpoint rule, whose relative error is (dy / H)^2 / 4 =
//   2.4e-4 here;
// - that state is in equilibrium with gravity, and discretely so: in each
//   cell the integrands sigma grad N and rho g N are linear in y, which
//   the two midpoints per cell and direction integrate exactly, and the
//   top is traction-free in both. So the layer stays at rest to round-off
//   (largest speed below 1e-9 m/s, against 0.5 m/s when gravity is
//   switched on from rest) and its strain energy does not change (1e-9).

#include <deal.II/base/mpi.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  const double E = 1.8e6, nu = 0.3, rho = 1850, g = 9.81, H = 2, W = 1;
  const double K0     = 0.5774;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu     = E / (2 * (1 + nu));
  const double factor = ((1 + 2 * K0 * K0) - lambda / (3 * lambda + 2 * mu) *
                                               (1 + 2 * K0) * (1 + 2 * K0)) /
                        (4 * mu);
  const double expected = factor * rho * g * rho * g * H * H * H / 3 * W;

  auto geostatic =
    mpm_tests::run_scene("scenes/geostatic.prm", "output-geostatic");
  auto from_rest = mpm_tests::run_scene(
    "scenes/geostatic.prm", "output-from-rest",
    {"Bodies/layer/Initial stress=none"});

  const double energy = geostatic["strain_energy"][0];
  deallog << "stored energy at t = 0: " << energy << " J/m, expected "
          << expected << std::endl;
  mpm_tests::check("geostatic energy = integral of the K0 energy density "
                   "to 1e-3",
                   std::abs(energy - expected) / expected < 1e-3);

  double speed = 0., speed_from_rest = 0., energy_change = 0.;
  for (const double v : geostatic["max_speed"])
    speed = std::max(speed, v);
  for (const double v : from_rest["max_speed"])
    speed_from_rest = std::max(speed_from_rest, v);
  for (const double e : geostatic["strain_energy"])
    energy_change = std::max(energy_change, std::abs(e - energy) / energy);
  deallog << "largest speed from rest: " << speed_from_rest << " m/s"
          << std::endl;
  mpm_tests::check("start from rest moves (largest speed above 0.1 m/s)",
                   speed_from_rest > 0.1);
  mpm_tests::check("geostatic start stays at rest: largest speed below "
                   "1e-9 m/s",
                   speed < 1e-9);
  mpm_tests::check("geostatic start: strain energy unchanged to 1e-9",
                   energy_change < 1e-9);
}
