#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return mpm::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
