// The Galerkin meshfree method on several ranks: every rank holds the whole
// node cloud, the ranks split the points (and with them the supports and
// the assembly) and the unknowns (a node's belong to the lowest rank whose
// points reach it). The same runs on one
// and on two ranks must give the same answer to round-off, and the
// references meshfree_ranks.output and meshfree_ranks.mpirun=2.output are
// the same file: the values are logged to 7 digits, which round-off does
// not reach and a lost contribution of another rank's points would.
// - the rolling disk of prm/rolling_disk.prm (Newmark, a no-slip contact
//   plane, whose active set of held nodes the ranks must agree on) with
//   GMM-MLS and GMM-LME on h = 0.05 m to 0.06 s: the centre of mass and
//   the energies at the end, and the rolling check of meshfree_methods
//   (75 % to 105 % of the exact rolling a t^2 / 2);
// - the cantilever of prm/cantilever.prm at h = 0.5 m (quasi-static,
//   5 load steps) with GMM-MLS, whose walls tie held nodes to their
//   neighbours (MLS constraints that every rank builds alike): the tracked
//   points' deflections at full load, and the tip within 5 % of the
//   reference 0.67433 m ([I] 5.1), as in meshfree_methods;
// - the points are partitioned by the grid's cells and balanced by their
//   number before the first step (Load balance; the checks every 10 steps
//   find them within 10 % of the mean), so on two ranks each rank's points reach nodes whose
//   unknowns the other rank owns.

#include <deal.II/base/mpi.h>

#include <iomanip>

#include "tests.h"

using namespace dealii;

namespace
{
  /** Log `value` to 7 significant digits. */
  void
  log_value(const std::string &name, const double value)
  {
    deallog << name << " = " << std::setprecision(7) << value
            << std::setprecision(6) << std::endl;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  for (const std::string method : {"GMM-MLS", "GMM-LME"})
    {
      deallog << "--- rolling disk, " << method << std::endl;
      auto csv = mpm_tests::run_scene("../prm/rolling_disk.prm",
                                      "output-rolling-" + method,
                                      {"Method=" + method,
                                       "Time stepping/End time=0.06",
                                       "Load balance/Check interval=10"});
      if (!root)
        continue;
      for (const std::string column : {"centre_of_mass_x",
                                       "centre_of_mass_y",
                                       "kinetic_energy",
                                       "strain_energy",
                                       "momentum_x"})
        log_value(column, csv[column].back());
      auto balance = mpm_tests::read_csv("output-rolling-" + method +
                                         "/load_balance.csv");
      mpm_tests::check(method + ": every rank holds points, within 10 % of "
                                "the mean number",
                       balance["point_imbalance"].back() < 1.1);
      const auto [ratio, drift] = mpm_tests::rolling_disk_ratio_and_drift(csv);
      mpm_tests::check(method + ": the disk rolls (75 % to 105 % of a t^2 / "
                                "2; sliding gives 150 %)",
                       csv["time"].back() > 0.06 - 1e-9 && ratio > 0.75 &&
                         ratio < 1.05);
      mpm_tests::check(method + ": its centre stays within 0.01 m of its "
                                "height",
                       drift < 0.01);
    }

  deallog << "--- cantilever, GMM-MLS" << std::endl;
  auto csv = mpm_tests::run_scene("../prm/cantilever.prm",
                                  "output-cantilever",
                                  {"Method=GMM-MLS"});
  if (root)
    {
      double v[4];
      for (unsigned int k = 0; k < 4; ++k)
        {
          const auto &y = csv["point" + std::to_string(k) + "_y"];
          v[k]          = y.back() - y.front();
          log_value("point" + std::to_string(k) + " deflection", v[k]);
        }
      // Bilinear extrapolation to (8, 0.5), as in meshfree_methods.
      const auto & x0 = csv["point0_x"], x1 = csv["point1_x"];
      const auto & y0 = csv["point0_y"], y2 = csv["point2_y"];
      const double s  = (8. - x0[0]) / (x1[0] - x0[0]);
      const double r  = (0.5 - y0[0]) / (y2[0] - y0[0]);
      const double tip =
        -((1 - s) * (1 - r) * v[0] + s * (1 - r) * v[1] +
          (1 - s) * r * v[2] + s * r * v[3]);
      mpm_tests::check("the cantilever reaches full load",
                       std::abs(csv["time"].back() - 1.) < 1e-12);
      mpm_tests::check("its tip within 5 % of 0.67433 m",
                       std::abs(tip - 0.67433) < 0.05 * 0.67433);
    }
}
