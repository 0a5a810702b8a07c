#ifndef mpm_core_checkpoint_h
#define mpm_core_checkpoint_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Where and when a run saves its state, so that it can be continued
   * (`mpm --restart scene.prm`) after a machine's time limit, a crash, or
   * with a later End time. Each rank writes its own archive into
   * `<Output/Directory>/checkpoint.new/`, which then replaces
   * `checkpoint/` by two renames (the old one goes to `checkpoint.old/`
   * first); read() falls back to those two, so a run killed at any moment
   * leaves a complete checkpoint. The parts of the state are written by the
   * classes that own them (their serialize() functions); a stopped run
   * continued on the same number of ranks repeats the uninterrupted run to
   * the last bit.
   */
  class Checkpoint
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * `entries_that_may_change` ('Section/entry', or 'Section/' for a whole
     * subsection), besides the Checkpoint entries, may differ between the
     * run that wrote a checkpoint and the one that continues it; any other
     * entry of the scene must not.
     */
    Checkpoint(ParameterHandler &              prm,
               const std::string &             output_directory,
               const std::vector<std::string> &entries_that_may_change,
               const MPI_Comm                  communicator);

    /** Whether this run writes checkpoints at all. */
    bool
    enabled() const
    {
      return interval_seconds > 0.;
    }

    /**
     * Whether the wall-time interval has passed since the last checkpoint
     * (or the start): decided on rank 0, so that all ranks agree.
     */
    bool
    due(const double wall_seconds) const;

    /**
     * Whether the run should end now, after its checkpoint (Stop after):
     * decided on rank 0.
     */
    bool
    stop_due(const double wall_seconds) const;

    /**
     * Remove a checkpoint that an earlier run left in the output
     * directory: a run that starts afresh there rewrites its output, and
     * a later --restart must not go back to the earlier run.
     */
    void
    discard_previous() const;

    /** Write this rank's state with `save`, then swap the directories. */
    void
    write(const double                                              wall_seconds,
          const std::function<void(boost::archive::binary_oarchive &)> &save);

    /**
     * Read this rank's state with `load`. Throws InputError if there is no
     * checkpoint, or it is damaged, or was written by another version, by
     * another number of ranks, or for a scene with other entries.
     */
    void
    read(const std::function<void(boost::archive::binary_iarchive &)> &load)
      const;

  private:
    std::string rank_file(const std::string &directory) const;

    /** What one rank finds in its file of a checkpoint directory. */
    struct RankFile
    {
      bool                               found   = false;
      unsigned int                       version = 0;
      unsigned int                       n_ranks = 0;
      std::map<std::string, std::string> scene;
      std::string                        state;
      /** Read whole, of this format, and its checksum matches. */
      bool intact = false;
    };

    RankFile
    read_rank_file(const std::string &directory) const;

    /**
     * Every entry of the scene as 'Section/entry' -> value; with
     * `at_default`, the entries whose value is their default go there.
     */
    static std::map<std::string, std::string>
    scene_entries(const ParameterHandler &prm,
                  std::set<std::string> * at_default = nullptr);

    /** `entries` and, last, the whole Checkpoint subsection. */
    static std::vector<std::string>
    with_checkpoint_entries(std::vector<std::string> entries);

    bool
    may_change(const std::string &entry) const;

    std::string
    may_change_list() const;

    static std::uint32_t
    checksum(const std::string &bytes);

    const MPI_Comm                           communicator;
    const std::string                        checkpoint_directory;
    /** Declared before `scene`, which fills it. */
    std::set<std::string>                    entries_at_default;
    const std::map<std::string, std::string> scene;
    const std::vector<std::string>           entries_that_may_change;
    double                                   interval_seconds;
    double                                   stop_seconds;
    double                                   last_write_wall_seconds = 0.;
  };
} // namespace mpm

#endif
