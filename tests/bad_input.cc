// Bad input of every kind stops with one clear message and a non-zero exit:
// exit code 2 for input errors (before the run starts), 3 for runs that
// cannot go on. Each case prints its exit code and message; the expected
// messages name the entry (Section/entry) and the allowed values.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "tests.h"

using namespace dealii;

void
run_case(const std::string &title, std::vector<std::string> arguments)
{
  // Error messages go to std::cerr on rank 0; capture them.
  std::ostringstream captured;
  std::streambuf *   old = std::cerr.rdbuf(captured.rdbuf());
  const int          code = mpm::run_command_line(arguments);
  std::cerr.rdbuf(old);

  // Paths differ between machines: show them relative to tests/.
  std::string message = captured.str();
  const std::string source = SOURCE_DIR;
  for (auto pos = message.find(source); pos != std::string::npos;
       pos = message.find(source))
    message.replace(pos, source.size(), "<tests>");
  deallog << "--- " << title << std::endl
          << "exit code " << code << std::endl;
  std::istringstream lines(message);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty())
      deallog << line << std::endl;
  mpm_tests::check(title + ": non-zero exit", code != 0);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const std::string base = mpm_tests::source_file("bad_input/base.prm");
  auto with = [&](const std::vector<std::string> &settings) {
    std::vector<std::string> arguments;
    for (const auto &s : settings)
      {
        arguments.push_back("--set");
        arguments.push_back(s);
      }
    arguments.push_back(base);
    return arguments;
  };

  // The base scene runs.
  {
    const int code = mpm::run_command_line(with({}));
    deallog << "base scene: exit code " << code << std::endl;
  }

  run_case("missing file", {"no_such_scene.prm"});
  run_case("no file given", {});
  run_case("unknown option", {"--frobnicate", base});
  run_case("not a parameter file",
           {mpm_tests::source_file("bad_input/not_a_prm_file.prm")});
  run_case("misspelt entry",
           {mpm_tests::source_file("bad_input/unknown_entry.prm")});
  run_case("no bodies", {mpm_tests::source_file("bad_input/no_bodies.prm")});
  run_case("--set of an unknown entry", with({"Output/Colour=blue"}));
  run_case("--set without '='", with({"Output/Directory"}));
  run_case("value outside the pattern",
           with({"Time stepping/Update scheme=RK4"}));
  run_case("Poisson's ratio 0.5", with({"Materials/rubber/Poisson's ratio=0.5"}));
  run_case("zero Young's modulus", with({"Materials/rubber/Young's modulus=0"}));
  run_case("a Young's modulus beyond any solid",
           with({"Materials/rubber/Young's modulus=1e300"}));
  run_case("a Young's modulus below any solid",
           with({"Materials/rubber/Young's modulus=1e-300"}));
  run_case("a density beyond any material",
           with({"Materials/rubber/Density=1e300"}));
  run_case("a snapshot at every step",
           with({"Output/Interval=1e-300"}));
  run_case("unknown material", with({"Bodies/block/Material=steel"}));
  run_case("softening that raises the cohesion",
           with({"Materials/rubber/Model=Mohr-Coulomb",
                 "Materials/rubber/Mohr-Coulomb/Cohesion=1000",
                 "Materials/rubber/Mohr-Coulomb/Softening plastic strain=0.1",
                 "Materials/rubber/Mohr-Coulomb/Residual cohesion=2000"}));
  run_case("geostatic stress without gravity",
           with({"Materials/rubber/Model=linear elastic",
                 "Bodies/block/Initial stress=geostatic"}));
  run_case("geostatic stress in a hyperelastic law",
           with({"Gravity=0, -9.81", "Bodies/block/Initial stress=geostatic"}));
  run_case("geostatic stress outside the yield surface",
           with({"Gravity=0, -9.81",
                 "Materials/rubber/Model=Mohr-Coulomb",
                 "Materials/rubber/Mohr-Coulomb/Friction angle=30",
                 "Bodies/block/Initial stress=geostatic",
                 "Bodies/block/K0=0.1"}));
  run_case("tension cut-off beyond the apex",
           with({"Materials/rubber/Model=Mohr-Coulomb",
                 "Materials/rubber/Mohr-Coulomb/Cohesion=1000",
                 "Materials/rubber/Mohr-Coulomb/Tension cut-off=true",
                 "Materials/rubber/Mohr-Coulomb/Tensile strength=5000"}));
  run_case("unknown boundary name",
           with({"Boundary conditions/Fixed boundaries=floor"}));
  run_case("boundary id not in the grid",
           with({"Grid/Arguments=4, 4 : 0, 0 : 1, 1 : false"}));
  run_case("unknown grid generator", with({"Grid/Generator=hyper_banana"}));
  run_case("missing mesh file", with({"Grid/Mesh file=no_such_mesh.msh"}));
  run_case("smooth shape functions on a grid of slanted cells",
           with({"Grid/Shape functions=quadratic B-spline",
                 "Grid/Generator=hyper_ball",
                 "Grid/Arguments=0.5, 0.5 : 1 : false",
                 "Boundary conditions/Fixed boundaries="}));
  run_case("smooth shape functions on a grid that does not fill a box",
           with({"Grid/Shape functions=uGIMP",
                 "Grid/Generator=hyper_L",
                 "Grid/Arguments=0 : 1 : false",
                 "Grid/Global refinements=2",
                 "Boundary conditions/Fixed boundaries="}));
  run_case("cell-averaged dilatation rate in plane stress",
           with({"Grid/Geometry=plane stress",
                 "Time stepping/Dilatation rate=cell average"}));
  run_case("smooth shape functions with a meshfree method",
           with({"Time stepping/Scheme=quasi-static",
                 "Method=GMM-LME",
                 "Grid/Shape functions=cpGIMP"}));
  run_case("disk in 3D", with({"Dimension=3", "Bodies/block/Shape=disk",
                               "Grid/Arguments=2 : 0 : 1 : true",
                               "Grid/Generator=subdivided_hyper_cube",
                               "Bodies/block/Center=0.5, 0.5, 0.5",
                               "Bodies/block/Radius=0.2",
                               "Gravity=0, 0, 0"}));
  run_case("cylinder in 2D", with({"Bodies/block/Shape=cylinder",
                                   "Bodies/block/Center=0.5, 0.5",
                                   "Bodies/block/Axis=0, 0.2",
                                   "Bodies/block/Radius=0.2"}));
  run_case("cylinder without an axis",
           with({"Dimension=3", "Bodies/block/Shape=cylinder",
                 "Grid/Arguments=2 : 0 : 1 : true",
                 "Grid/Generator=subdivided_hyper_cube",
                 "Bodies/block/Center=0.5, 0.5, 0.5",
                 "Bodies/block/Axis=0, 0, 0",
                 "Bodies/block/Radius=0.2",
                 "Gravity=0, 0, 0"}));
  run_case("a body mesh of a polygon",
           with({"Bodies/block/Shape=polygon",
                 "Bodies/block/Vertices=0.2, 0.2; 0.8, 0.2; 0.5, 0.7",
                 "Bodies/block/Point placement=body mesh"}));
  run_case("a body mesh of more than 2^21 cells",
           with({"Bodies/block/Upper corner=1000, 1000",
                 "Bodies/block/Point placement=body mesh"}));
  run_case("box corners with the wrong dimension",
           with({"Bodies/block/Lower corner=0.25, 0, 0"}));
  run_case("bad velocity expression",
           with({"Bodies/block/Initial velocity=sin(; 0"}));
  run_case("body outside the grid",
           with({"Bodies/block/Lower corner=2, 2",
                 "Bodies/block/Upper corner=3, 3"}));
  run_case("time step above the stability limit",
           with({"Time stepping/Time step=0.1"}));
  run_case("contact boundary with the explicit scheme",
           with({"Boundary conditions/Contact boundaries=bottom"}));
  run_case("contact walls meeting at a corner",
           with({"Time stepping/Scheme=quasi-static",
                 "Boundary conditions/Fixed boundaries=",
                 "Boundary conditions/Contact boundaries=bottom, left"}));
  run_case("friction boundary without a coefficient",
           with({"Boundary conditions/Fixed boundaries=",
                 "Boundary conditions/Friction boundaries=bottom"}));
  run_case("negative friction coefficient",
           with({"Boundary conditions/Fixed boundaries=",
                 "Boundary conditions/Friction boundaries=bottom: -0.1"}));
  run_case("friction coefficient that is not a number",
           with({"Boundary conditions/Fixed boundaries=",
                 "Boundary conditions/Friction boundaries=bottom: rough"}));
  run_case("friction boundary that is also fixed",
           with({"Boundary conditions/Fixed boundaries=bottom",
                 "Boundary conditions/Friction boundaries=bottom: 0.3"}));
  run_case("unknown friction boundary",
           with({"Boundary conditions/Friction boundaries=floor: 0.3"}));
  run_case("friction boundary with a meshfree method",
           with({"Time stepping/Scheme=quasi-static",
                 "Method=GMM-MLS",
                 "Boundary conditions/Fixed boundaries=",
                 "Boundary conditions/Friction boundaries=bottom: 0.3"}));
  run_case("obstacle outside the grid",
           with({"Obstacles/Names=ram",
                 "Obstacles/ram/Lower corner=5, 5",
                 "Obstacles/ram/Upper corner=6, 6"}));
  run_case("negative friction coefficient of an obstacle",
           with({"Obstacles/Names=ram",
                 "Obstacles/ram/Lower corner=0.1, 0.1",
                 "Obstacles/ram/Upper corner=0.2, 0.2",
                 "Obstacles/ram/Friction coefficient=-1"}));
  run_case("obstacle with the quasi-static scheme",
           with({"Time stepping/Scheme=quasi-static",
                 "Obstacles/Names=ram",
                 "Obstacles/ram/Lower corner=0.1, 0.1",
                 "Obstacles/ram/Upper corner=0.2, 0.2"}));
  run_case("outflow boundary that does not exist",
           with({"Boundary conditions/Outflow boundaries=orifice"}));
  run_case("a wall's end time that is not a number",
           with({"Boundary conditions/Fixed boundaries=bottom until soon"}));
  run_case("a wall that ends, with the quasi-static scheme",
           with({"Time stepping/Scheme=quasi-static",
                 "Boundary conditions/Fixed boundaries=bottom until 1"}));
  const std::string axisymmetric = "Grid/Geometry=axisymmetric";
  run_case("axisymmetric grid at negative radius",
           with({axisymmetric, "Grid/Arguments=4, 4 : -0.5, 0 : 1, 1 : true",
                 "Boundary conditions/Slip boundaries=left"}));
  run_case("axisymmetric 3D scene",
           with({axisymmetric, "Dimension=3",
                 "Grid/Arguments=2 : 0 : 1 : true",
                 "Grid/Generator=subdivided_hyper_cube",
                 "Bodies/block/Lower corner=0.25, 0, 0.25",
                 "Bodies/block/Upper corner=0.75, 0.5, 0.75",
                 "Gravity=0, 0, 0"}));
  run_case("axisymmetric grid whose axis is not held", with({axisymmetric}));
  run_case("axisymmetric axis that ends",
           with({axisymmetric,
                 "Boundary conditions/Slip boundaries=left until 0.005"}));
  run_case("axisymmetric gravity along the radius",
           with({axisymmetric, "Boundary conditions/Slip boundaries=left",
                 "Gravity=-9.81, 0"}));
  run_case("axisymmetric obstacle moving radially",
           with({axisymmetric, "Boundary conditions/Slip boundaries=left",
                 "Obstacles/Names=ram",
                 "Obstacles/ram/Lower corner=0.8, 0.1",
                 "Obstacles/ram/Upper corner=0.9, 0.2",
                 "Obstacles/ram/Displacement=-0.1*t; 0"}));
  run_case("axisymmetric scene with a meshfree method",
           with({axisymmetric, "Time stepping/Scheme=quasi-static",
                 "Method=GMM-MLS",
                 "Boundary conditions/Slip boundaries=left"}));
  run_case("axisymmetric traction normal to the radius without a side",
           with({axisymmetric, "Time stepping/Scheme=quasi-static",
                 "Boundary conditions/Slip boundaries=left",
                 "Loads/Traction=-1000, 0",
                 "Loads/Traction normal=x",
                 "Loads/Region lower corner=0.7, 0",
                 "Loads/Region upper corner=0.75, 0.5"}));
  const std::string plane_stress = "Grid/Geometry=plane stress";
  run_case("plane stress in a 3D scene",
           with({plane_stress, "Dimension=3",
                 "Grid/Arguments=2 : 0 : 1 : true",
                 "Grid/Generator=subdivided_hyper_cube",
                 "Bodies/block/Lower corner=0.25, 0, 0.25",
                 "Bodies/block/Upper corner=0.75, 0.5, 0.75",
                 "Gravity=0, 0, 0"}));
  run_case("plane stress with a negative thickness",
           with({plane_stress, "Grid/Thickness=-0.002"}));
  run_case("a thickness outside plane stress",
           with({"Grid/Thickness=0.002"}));
  run_case("plane stress with a law for loose fill",
           with({plane_stress,
                 "Materials/rubber/Model=Wieckowski granular"}));
  run_case("both a total force and a traction",
           with({"Time stepping/Scheme=quasi-static",
                 "Loads/Total force=0, -1",
                 "Loads/Traction=0, -1",
                 "Loads/Region lower corner=0.25, 0.4",
                 "Loads/Region upper corner=0.75, 0.5"}));
  run_case("load factor that is not an expression",
           with({"Time stepping/Scheme=quasi-static",
                 "Loads/Load factor=t*(2"}));
  run_case("load factor that is not finite",
           with({"Time stepping/Scheme=quasi-static",
                 "Loads/Load factor=sqrt(-1-t)"}));
  run_case("quasi-static loads on no point",
           with({"Time stepping/Scheme=quasi-static",
                 "Loads/Total force=0, -1",
                 "Loads/Region lower corner=0.9, 0.9",
                 "Loads/Region upper corner=1, 1"}));
  run_case("line search with the linear Newton variant",
           with({"Time stepping/Scheme=quasi-static",
                 "Newton/Variant=linear", "Newton/Line search=true"}));
  run_case("meshfree method with the explicit scheme",
           with({"Method=GMM-LME"}));
  run_case("MLS dilation that reaches no neighbour",
           with({"Method=GMM-MLS", "Time stepping/Scheme=quasi-static",
                 "Meshfree/MLS dilation=0.9"}));
  run_case("LME gamma of zero",
           with({"Method=GMM-LME", "Time stepping/Scheme=quasi-static",
                 "Meshfree/LME gamma=0"}));
  run_case("Newmark without a time step",
           with({"Time stepping/Scheme=Newmark"}));
  run_case("points leave the grid",
           with({"Boundary conditions/Fixed boundaries=",
                 "Bodies/block/Initial velocity=0; -2",
                 "Time stepping/End time=1"}));
  run_case("points leave the grid, with checkpoints: the message names the "
           "last one",
           with({"Boundary conditions/Fixed boundaries=",
                 "Bodies/block/Initial velocity=0; -2",
                 "Time stepping/End time=1",
                 "Checkpoint/Wall time interval=1e-9",
                 "Output/Directory=output-left-grid"}));
  run_case("points would skip cells",
           with({"Gravity=0, -1e5", "Boundary conditions/Fixed boundaries=",
                 "Bodies/block/Lower corner=0.25, 0.5",
                 "Bodies/block/Upper corner=0.75, 1",
                 "Time stepping/Time step=0.0015",
                 "Time stepping/End time=1"}));
  run_case("granular fill and Mohr-Coulomb in one scene",
           with({"Materials/Names=rubber, fill",
                 "Materials/rubber/Model=Mohr-Coulomb",
                 "Materials/fill/Model=Wieckowski granular"}));
  run_case("a body Density for a law whose stress does not follow it",
           with({"Bodies/block/Density=1000"}));
  run_case("a negative body Density",
           with({"Materials/rubber/Model=Wieckowski granular",
                 "Bodies/block/Density=-5"}));
  run_case("Releases without a Release interval",
           with({"Bodies/block/Releases=3"}));
  run_case("an inflow with the quasi-static scheme",
           with({"Bodies/block/First release=0.1",
                 "Time stepping/Scheme=quasi-static"}));
  run_case("density from positions with the quasi-static scheme",
           with({"Materials/rubber/Model=Wieckowski granular",
                 "Materials/rubber/Wieckowski granular/Density from "
                 "positions=true",
                 "Time stepping/Scheme=quasi-static"}));
  run_case("an inflow under geostatic stress",
           with({"Bodies/block/Releases=2",
                 "Bodies/block/Release interval=0.5",
                 "Bodies/block/Initial stress=geostatic"}));
  run_case("a release into cells that still hold the last portion",
           {"--set", "Bodies/portion/Release interval=0.02",
            "--set", "Output/Write ParaView output=false",
            "--set", "Output/Directory=output-crowded-release",
            mpm_tests::source_file("scenes/inflow.prm")});
  run_case("tracked points in a grid that an inflow fills later",
           {"--set", "Output/Tracked points=0.5, 0.9",
            "--set", "Output/Write ParaView output=false",
            "--set", "Output/Directory=output-tracked-inflow",
            mpm_tests::source_file("scenes/inflow.prm")});
  run_case("a release whose region lies outside the grid",
           with({"Bodies/block/First release=0.01",
                 "Bodies/block/Lower corner=5, 5",
                 "Bodies/block/Upper corner=6, 6"}));
  run_case("Stop after without checkpoints",
           with({"Checkpoint/Stop after=60"}));
  run_case("load balancing with no weight on cells or points",
           with({"Load balance/Cell weight=0",
                 "Load balance/Point weight=0"}));
  run_case("an adaptive grid with the meshfree method",
           with({"Adaptive grid/Refinement levels=1",
                 "Time stepping/Scheme=quasi-static",
                 "Method=GMM-MLS"}));
  run_case("an adaptive grid with smooth shape functions",
           with({"Adaptive grid/Refinement levels=1",
                 "Grid/Shape functions=uGIMP"}));
  run_case("finer levels that say not where",
           with({"Adaptive grid/Finer levels=1"}));
  run_case("a finer region with no finer levels",
           with({"Adaptive grid/Finer where=region"}));
  run_case("a finer region whose corners are swapped",
           with({"Adaptive grid/Finer levels=1",
                 "Adaptive grid/Finer where=region",
                 "Adaptive grid/Finer region/Lower corner=1, 1",
                 "Adaptive grid/Finer region/Upper corner=0, 0"}));
  run_case("finer levels by plastic flow in an elastic body",
           with({"Adaptive grid/Finer levels=1",
                 "Adaptive grid/Finer where=plastic flow"}));
  run_case("finer levels in a region with no periodic check",
           with({"Adaptive grid/Finer levels=1",
                 "Adaptive grid/Finer where=region",
                 "Adaptive grid/Finer region/Lower corner=0, 0",
                 "Adaptive grid/Finer region/Upper corner=1, 1",
                 "Adaptive grid/Check interval=0"}));
  {
    // A run that leaves a checkpoint (at its end), to continue wrongly.
    const std::vector<std::string> checkpointed = {
      "Output/Directory=output-checkpointed",
      "Checkpoint/Wall time interval=1e-9"};
    auto restart = [&](const std::vector<std::string> &settings) {
      std::vector<std::string> all = checkpointed;
      all.insert(all.end(), settings.begin(), settings.end());
      auto arguments = with(all);
      arguments.insert(arguments.begin(), "--restart");
      return arguments;
    };
    run_case("--restart without a checkpoint",
             restart({"Output/Directory=output-never-checkpointed"}));
    mpm::run_command_line(with(checkpointed));
    run_case("--restart of a scene whose material changed",
             restart({"Materials/rubber/Young's modulus=2e5",
                      "Output/Write grid=true"}));
    run_case("--restart of a checkpoint of another scheme",
             restart({"Time stepping/Scheme=quasi-static"}));
    const std::string quasi_static = "Time stepping/Scheme=quasi-static";
    mpm::run_command_line(with({quasi_static, checkpointed[0], checkpointed[1]}));
    run_case("--restart of a quasi-static run with another End time",
             restart({quasi_static, "Time stepping/End time=2"}));
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::resize_file("output-checkpointed/checkpoint/rank-0.bin",
                                   100);
    MPI_Barrier(MPI_COMM_WORLD);
    run_case("--restart of a cut checkpoint file", restart({quasi_static}));
  }
  // Contact between bodies, on the block on the slope.
  {
    const auto slope = [&](const std::string &setting) {
      return std::vector<std::string>{
        "--set", setting,
        "--set", "Output/Directory=output-bad-contact",
        mpm_tests::source_file("../prm/block_on_slope.prm")};
    };
    run_case("a contact pair that names a group no body is in",
             slope("Contact/Pairs=block-wall: 0.3"));
    run_case("a negative contact friction",
             slope("Contact/Pairs=block-slope: -0.1"));
    run_case("a contact pair of a group with itself",
             slope("Contact/Pairs=block-block: 0.3"));
    run_case("a contact pair without a coefficient",
             slope("Contact/Pairs=block-slope"));
    run_case("a contact group name with a dash",
             slope("Bodies/block/Contact group=the-block"));
    run_case("contact groups with the quasi-static scheme",
             slope("Time stepping/Scheme=quasi-static"));
    run_case("contact groups with the blended mass",
             slope("Time stepping/Mass matrix=blended"));
  }
  // Stable for the loose fill at the start (limit 1.82e-4 s), not once the
  // bottom has compacted and stiffened.
  run_case("fixed time step the compacting fill outgrows",
           {"--set", "Time stepping/Time step=1.75e-4",
            "--set", "Output/Write ParaView output=false",
            "--set", "Output/Directory=output-outgrown",
            mpm_tests::source_file("../prm/granular_fill_settling.prm")});
}
