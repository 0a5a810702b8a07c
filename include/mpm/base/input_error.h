#ifndef mpm_base_input_error_h
#define mpm_base_input_error_h

#include <deal.II/base/mpi.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace mpm
{
  /**
   * A problem with what the user gave us: a parameter value, a file, a
   * combination of settings. The message is shown to the user as it is, so
   * it names the entry (as `Section/entry`) and, where it helps, the values
   * that would be accepted.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * A run that was set up correctly but could not continue: a point that left
   * the grid, a non-finite velocity, a point that would skip a cell. The
   * message says what happened, where and when.
   */
  class RunError : public std::runtime_error
  {
  public:
    /**
     * `smaller_step_helps`: whether an implicit scheme may retry the step
     * with half the size (a Newton iteration that diverged), or not (a
     * point whose shape functions cannot be built where it stands).
     */
    explicit RunError(const std::string &message,
                      const bool         smaller_step_helps = true)
      : std::runtime_error(message)
      , smaller_step_helps(smaller_step_helps)
    {}

    const bool smaller_step_helps;
  };

  /** Names for a message: "a, b, c". */
  inline std::string
  comma_separated(const std::vector<std::string> &names)
  {
    std::string text;
    for (const auto &name : names)
      text += (text.empty() ? "" : ", ") + name;
    return text;
  }



  /**
   * For input errors that only some ranks can see (they depend on the
   * points a rank owns): every rank calls this with its message, empty if
   * it found nothing, and all throw the InputError of the lowest rank that
   * found one.
   */
  inline void
  throw_input_error_on_every_rank(const std::string &message,
                                  const MPI_Comm     communicator)
  {
    const unsigned int rank =
      dealii::Utilities::MPI::this_mpi_process(communicator);
    const unsigned int first = dealii::Utilities::MPI::min(
      message.empty() ? dealii::numbers::invalid_unsigned_int : rank,
      communicator);
    if (first != dealii::numbers::invalid_unsigned_int)
      throw InputError(
        dealii::Utilities::MPI::broadcast(communicator, message, first));
  }
} // namespace mpm

#endif
