#include <mpm/core/checkpoint.h>
#include <mpm/base/input_error.h>

#include <boost/crc.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace mpm
{
  namespace
  {
    // Bumped whenever what the classes save changes.
    constexpr unsigned int format_version = 11;
  } // namespace



  void
  Checkpoint::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    prm.declare_entry(
      "Wall time interval", "0", Patterns::Double(0.),
      "Save the whole state of the run every this many minutes of wall time, "
      "and at its end, into <Output/Directory>/checkpoint/, replacing the "
      "previous checkpoint. 0: no checkpoints. Continue a run with "
      "'mpm --restart scene.prm' on the same number of ranks. Besides these "
      "entries, only Output/Directory and the steps may change: End time, "
      "Time step and CFL number (explicit), End time and Time step "
      "(Newmark), Load steps (quasi-static, whose load ramps over End "
      "time).");
    prm.declare_entry(
      "Stop after", "0", Patterns::Double(0.),
      "End the run early, after a checkpoint, once its time loop has run "
      "this many minutes of wall time (0: never; the setup before the loop, "
      "usually seconds, is not counted): for machines that limit a job's "
      "time. "
      "Continue it with 'mpm --restart scene.prm'. Needs Wall time interval "
      "above 0.");
    prm.leave_subsection();
  }



  Checkpoint::Checkpoint(ParameterHandler &              prm,
                         const std::string &             output_directory,
                         const std::vector<std::string> &entries_that_may_change,
                         const MPI_Comm                  communicator)
    : communicator(communicator)
    , checkpoint_directory(output_directory + "/checkpoint")
    , scene(scene_entries(prm, &entries_at_default))
    , entries_that_may_change(
        with_checkpoint_entries(entries_that_may_change))
  {
    prm.enter_subsection("Checkpoint");
    interval_seconds = 60. * prm.get_double("Wall time interval");
    stop_seconds     = 60. * prm.get_double("Stop after");
    prm.leave_subsection();
    if (stop_seconds > 0. && !enabled())
      throw InputError("Checkpoint/Stop after needs Checkpoint/Wall time "
                       "interval above 0: the run would stop without a "
                       "checkpoint to continue from.");
  }



  bool
  Checkpoint::due(const double wall_seconds) const
  {
    const bool due = enabled() && (wall_seconds - last_write_wall_seconds >= interval_seconds ||
                                   stop_due(wall_seconds));
    return Utilities::MPI::broadcast(communicator, due, 0);
  }



  bool
  Checkpoint::stop_due(const double wall_seconds) const
  {
    const bool stop = stop_seconds > 0. && wall_seconds >= stop_seconds;
    return Utilities::MPI::broadcast(communicator, stop, 0);
  }



  std::string
  Checkpoint::rank_file(const std::string &directory) const
  {
    return directory + "/rank-" +
           std::to_string(Utilities::MPI::this_mpi_process(communicator)) +
           ".bin";
  }



  void
  Checkpoint::discard_previous() const
  {
    std::error_code error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      for (const std::string suffix : {"", ".new", ".old"})
        std::filesystem::remove_all(checkpoint_directory + suffix, error);
    if (Utilities::MPI::max(error ? 1 : 0, communicator) != 0)
      throw InputError("The checkpoint '" + checkpoint_directory +
                       "' of an earlier run cannot be removed.");
  }



  void
  Checkpoint::write(
    const double                                                  wall_seconds,
    const std::function<void(boost::archive::binary_oarchive &)> &save)
  {
    const std::string fresh  = checkpoint_directory + ".new";
    const bool        root   = Utilities::MPI::this_mpi_process(communicator) == 0;
    std::error_code   error;
    if (root)
      {
        std::filesystem::remove_all(fresh, error);
        std::filesystem::create_directories(fresh, error);
      }
    if (Utilities::MPI::max(error ? 1 : 0, communicator) != 0)
      throw RunError("Cannot create the checkpoint directory '" + fresh + "'.",
                     false);

    // The state goes into memory first, so that its length and checksum
    // can be written before it: a restart then tells a damaged or cut file
    // from a good one before it reads any of it.
    std::ostringstream state;
    {
      boost::archive::binary_oarchive archive(state);
      save(archive);
    }
    const std::string state_bytes = state.str();
    bool              written     = false;
    {
      std::ofstream file(rank_file(fresh), std::ios::binary);
      if (file)
        {
          boost::archive::binary_oarchive archive(file);
          const unsigned int n_ranks =
            Utilities::MPI::n_mpi_processes(communicator);
          archive << format_version << n_ranks << scene << state_bytes
                  << checksum(state_bytes);
        }
      written = static_cast<bool>(file);
    }
    if (Utilities::MPI::logical_or(!written, communicator))
      throw RunError("Cannot write the checkpoint into '" + fresh + "'.",
                     false);

    // Every rank's file is complete: swap the directories.
    if (root)
      {
        const std::string old = checkpoint_directory + ".old";
        std::filesystem::remove_all(old, error);
        if (!error && std::filesystem::exists(checkpoint_directory, error))
          std::filesystem::rename(checkpoint_directory, old, error);
        if (!error)
          std::filesystem::rename(fresh, checkpoint_directory, error);
        // The new checkpoint is in place; a previous one left behind does
        // no harm.
        std::error_code ignored;
        if (!error)
          std::filesystem::remove_all(old, ignored);
      }
    if (Utilities::MPI::max(error ? 1 : 0, communicator) != 0)
      throw RunError("Cannot move the checkpoint into '" +
                       checkpoint_directory + "'.",
                     false);
    last_write_wall_seconds = wall_seconds;
  }



  Checkpoint::RankFile
  Checkpoint::read_rank_file(const std::string &directory) const
  {
    RankFile      contents;
    std::ifstream file(rank_file(directory), std::ios::binary);
    contents.found = static_cast<bool>(file);
    if (!contents.found)
      return contents;
    try
      {
        boost::archive::binary_iarchive archive(file);
        archive >> contents.version;
        if (contents.version == format_version)
          {
            std::uint32_t saved_checksum = 0;
            archive >> contents.n_ranks >> contents.scene >> contents.state >>
              saved_checksum;
            contents.intact = saved_checksum == checksum(contents.state);
          }
      }
    catch (...)
      {
        // A cut or overwritten file: not intact, which read() reports on
        // every rank at once.
      }
    return contents;
  }



  void
  Checkpoint::read(
    const std::function<void(boost::archive::binary_iarchive &)> &load) const
  {
    // A run killed between the two renames of write() has no checkpoint/,
    // but a complete checkpoint.new/ or checkpoint.old/.
    RankFile    contents;
    std::string directory;
    for (const std::string suffix : {"", ".new", ".old"})
      {
        contents = read_rank_file(checkpoint_directory + suffix);
        if (!Utilities::MPI::logical_or(!contents.intact, communicator))
          {
            directory = checkpoint_directory + suffix;
            break;
          }
      }
    if (directory.empty())
      {
        const RankFile primary = read_rank_file(checkpoint_directory);
        const std::string where =
          "--restart: the checkpoint in '" + checkpoint_directory + "' ";
        if (Utilities::MPI::logical_or(!primary.found, communicator))
          throw InputError("--restart: no checkpoint in '" +
                           checkpoint_directory +
                           "' for every rank: a run writes one when "
                           "Checkpoint/Wall time interval is above 0, and it "
                           "is continued on as many ranks as wrote it.");
        if (Utilities::MPI::logical_or(primary.version != format_version &&
                                         primary.version != 0,
                                       communicator))
          throw InputError(where + "was written by another version of mpm.");
        throw InputError(where + "is damaged or incomplete.");
      }

    const std::string where =
      "--restart: the checkpoint in '" + directory + "' ";
    if (contents.n_ranks != Utilities::MPI::n_mpi_processes(communicator))
      throw InputError(where + "was written by " +
                       std::to_string(contents.n_ranks) +
                       " rank(s); continue it on as many.");

    // Checkpoints written before the PRM form was parsed here kept an
    // entry whose value is empty under its name padded and followed by
    // '=' (the short form prints no ' = ' for it).
    std::map<std::string, std::string> saved_scene;
    for (const auto &[name, value] : contents.scene)
      saved_scene[name.back() == '=' ?
                    Utilities::trim(name.substr(0, name.size() - 1)) :
                    name] = value;
    auto        union_of_entries = saved_scene;
    union_of_entries.insert(scene.begin(), scene.end());
    std::string changed;
    for (const auto &entry : union_of_entries)
      {
        const auto  saved = saved_scene.find(entry.first);
        const auto  now   = scene.find(entry.first);
        const std::string was =
          saved == saved_scene.end() ? "(no such entry)" : saved->second;
        const std::string is =
          now == scene.end() ? "(no such entry)" : now->second;
        // An entry added to mpm since the checkpoint was written, at its
        // default, keeps the behaviour the checkpoint was written with.
        if (saved == saved_scene.end() && entries_at_default.count(entry.first))
          continue;
        if (was != is && !may_change(entry.first))
          changed += "\n  " + entry.first + ": was '" + was + "', is '" + is +
                     "'";
      }
    if (!changed.empty())
      throw InputError(where + "is of a scene with other values of:" +
                       changed + "\nOnly " + may_change_list() +
                       " may change when a run is continued.");

    std::istringstream              state(contents.state);
    boost::archive::binary_iarchive archive(state);
    load(archive);
  }



  std::map<std::string, std::string>
  Checkpoint::scene_entries(const ParameterHandler &prm,
                            std::set<std::string> * at_default)
  {
    // The PRM form has one 'set entry = value' per line, inside
    // 'subsection' ... 'end' blocks, and marks a value that is not the
    // entry's default with '# default: ...' after it.
    std::ostringstream text;
    prm.print_parameters(text, ParameterHandler::PRM);
    std::map<std::string, std::string> entries;
    std::vector<std::string>           sections;
    std::istringstream                 lines(text.str());
    const std::string                  default_mark = "# default:";
    for (std::string line; std::getline(lines, line);)
      {
        line = Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          sections.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !sections.empty())
          sections.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            const auto  mark   = line.find(default_mark);
            const auto  equals = line.find(" =");
            std::string path;
            for (const auto &section : sections)
              path += section + "/";
            path += Utilities::trim(line.substr(4, equals - 4));
            entries[path] =
              equals == std::string::npos ?
                "" :
                Utilities::trim(line.substr(equals + 2, mark - equals - 2));
            if (at_default != nullptr && mark == std::string::npos)
              at_default->insert(path);
          }
      }
    return entries;
  }



  std::vector<std::string>
  Checkpoint::with_checkpoint_entries(std::vector<std::string> entries)
  {
    entries.push_back("Checkpoint/");
    return entries;
  }



  bool
  Checkpoint::may_change(const std::string &entry) const
  {
    for (const std::string &allowed : entries_that_may_change)
      if (allowed == entry ||
          (allowed.back() == '/' && entry.rfind(allowed, 0) == 0))
        return true;
    return false;
  }



  std::string
  Checkpoint::may_change_list() const
  {
    // The Checkpoint entries come last: 'a, b, the X entries and the
    // Checkpoint entries'.
    std::string list;
    for (const auto &entry : entries_that_may_change)
      {
        if (&entry != &entries_that_may_change.front())
          list += &entry == &entries_that_may_change.back() ? " and " : ", ";
        list += entry.back() == '/' ?
                  "the " + entry.substr(0, entry.size() - 1) + " entries" :
                  entry;
      }
    return list;
  }



  std::uint32_t
  Checkpoint::checksum(const std::string &bytes)
  {
    boost::crc_32_type crc;
    crc.process_bytes(bytes.data(), bytes.size());
    return crc.checksum();
  }
} // namespace mpm
