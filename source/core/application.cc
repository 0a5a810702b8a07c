#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/core/application.h>
#include <mpm/base/input_error.h>
#include <mpm/core/named_sections.h>
#include <mpm/core/simulator.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace mpm
{
  using namespace dealii;

  namespace
  {
    const char *usage =
      "Usage: mpm [options] scene.prm\n"
      "\n"
      "Runs the scene described by a deal.II parameter file (see prm/).\n"
      "\n"
      "Options:\n"
      "  --set 'Section/entry=value'  Override an entry of the file, e.g.\n"
      "                               --set 'Time stepping/End time=2'.\n"
      "                               Repeatable; applied after the file.\n"
      "  --restart                    Continue the run from the checkpoint in\n"
      "                               its output directory (see Checkpoint).\n"
      "  --print-parameters           List every entry with its default and\n"
      "                               documentation, then exit.\n"
      "  --help                       Show this text.\n"
      "\n"
      "Run in parallel with: mpirun -np N mpm scene.prm\n";

    struct Override
    {
      std::vector<std::string> path;
      std::string              entry;
      std::string              value;
      std::string              text;
    };

    std::string
    message_of(const ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string text = info.str();
      while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
        text.pop_back();
      while (!text.empty() && (text.front() == '\n' || text.front() == ' '))
        text.erase(text.begin());
      return text;
    }

    Override
    parse_override(const std::string &text)
    {
      const auto equals = text.find('=');
      if (equals == std::string::npos || equals == 0)
        throw InputError("--set '" + text +
                         "' must have the form 'Section/entry=value'.");
      Override o;
      o.text  = text;
      o.value = text.substr(equals + 1);
      std::vector<std::string> parts =
        Utilities::split_string_list(text.substr(0, equals), '/');
      o.entry = parts.back();
      parts.pop_back();
      o.path = parts;
      return o;
    }

    /**
     * Apply one override. An entry that is not declared is an error if
     * `strict`, and skipped otherwise (the first pass declares only a few).
     */
    void
    apply_override(ParameterHandler &prm, const Override &o, const bool strict)
    {
      for (const auto &section : o.path)
        prm.enter_subsection(section);
      try
        {
          prm.set(o.entry, o.value);
        }
      catch (const ParameterHandler::ExcEntryUndeclared &)
        {
          for (unsigned int i = 0; i < o.path.size(); ++i)
            prm.leave_subsection();
          if (strict)
            throw InputError("--set '" + o.text +
                             "': there is no such entry (see mpm "
                             "--print-parameters).");
          return;
        }
      catch (const ExceptionBase &e)
        {
          for (unsigned int i = 0; i < o.path.size(); ++i)
            prm.leave_subsection();
          throw InputError("--set '" + o.text + "': " + message_of(e));
        }
      for (unsigned int i = 0; i < o.path.size(); ++i)
        prm.leave_subsection();
    }

    /** Entries read before the rest can be declared. */
    void
    declare_first_pass(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "Space dimension of the scene: 2 (plane strain, or "
                        "axisymmetric with Grid/Geometry) or 3.");
      prm.enter_subsection("Materials");
      NamedSections::declare_names(
        prm,
        "",
        "Names of the materials of the scene. Each has a subsection of the "
        "same name inside Materials.");
      prm.leave_subsection();
      prm.enter_subsection("Bodies");
      NamedSections::declare_names(
        prm,
        "",
        "Names of the bodies of the scene. Each has a subsection of the same "
        "name inside Bodies.");
      prm.leave_subsection();
      prm.enter_subsection("Obstacles");
      NamedSections::declare_names(
        prm,
        "",
        "Names of the rigid obstacles of the scene (explicit scheme). Each "
        "has a subsection of the same name inside Obstacles.");
      prm.leave_subsection();
    }

    /**
     * Thrown for any error other than RunError once a scene has been set up:
     * it may have happened on one rank only (a file that cannot be written,
     * say), so the others cannot be trusted to stop.
     */
    class UnexpectedRunError : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    template <int dim>
    void
    run_scene(ParameterHandler &              prm,
              const SceneNames &              names,
              const bool                      restart)
    {
      Simulator<dim> simulator(
        prm, names, MPI_COMM_WORLD, restart);
      try
        {
          simulator.run();
        }
      catch (const RunError &e)
        {
          throw RunError(e.what() + simulator.restart_hint(),
                         e.smaller_step_helps);
        }
      // Input that only shows during the run (a release into occupied
      // cells) is still bad input.
      catch (const InputError &)
        {
          throw;
        }
      catch (const ExceptionBase &e)
        {
          throw UnexpectedRunError(message_of(e));
        }
      catch (const std::exception &e)
        {
          throw UnexpectedRunError(e.what());
        }
    }

    void
    print_parameters()
    {
      ParameterHandler prm;
      declare_first_pass(prm);
      Simulator<2>::declare_parameters(
        prm, {{"example material"}, {"example body"}, {"example obstacle"}});
      prm.print_parameters(std::cout, ParameterHandler::PRM);
    }

    int
    run(const std::vector<std::string> &arguments)
    {
      std::vector<Override> overrides;
      std::string           filename;
      bool                  restart = false;
      for (unsigned int i = 0; i < arguments.size(); ++i)
        {
          const std::string &a = arguments[i];
          if (a == "--help" || a == "-h")
            {
              if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
                std::cout << usage;
              return 0;
            }
          else if (a == "--print-parameters")
            {
              if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
                print_parameters();
              return 0;
            }
          else if (a == "--restart")
            restart = true;
          else if (a == "--set")
            {
              if (i + 1 == arguments.size())
                throw InputError("--set needs an argument "
                                 "'Section/entry=value'.");
              overrides.push_back(parse_override(arguments[++i]));
            }
          else if (a.rfind("--set=", 0) == 0)
            overrides.push_back(parse_override(a.substr(6)));
          else if (a.rfind("-", 0) == 0)
            throw InputError("unknown option '" + a + "'.\n" + usage);
          else if (filename.empty())
            filename = a;
          else
            throw InputError("more than one parameter file given ('" +
                             filename + "' and '" + a + "').");
        }
      if (filename.empty())
        throw InputError(std::string("no parameter file given.\n") + usage);
      if (!std::ifstream(filename))
        throw InputError("cannot open the parameter file '" + filename + "'.");

      // First pass: the dimension and the names of materials and bodies.
      ParameterHandler first;
      declare_first_pass(first);
      first.parse_input(filename, "", true);
      for (const auto &o : overrides)
        apply_override(first, o, false);
      const unsigned int dim = first.get_integer("Dimension");
      first.enter_subsection("Materials");
      SceneNames names;
      names.materials = NamedSections::parse_names(first, "Materials");
      first.leave_subsection();
      first.enter_subsection("Bodies");
      names.bodies = NamedSections::parse_names(first, "Bodies");
      first.leave_subsection();
      first.enter_subsection("Obstacles");
      names.obstacles =
        NamedSections::parse_names(first, "Obstacles", true);
      first.leave_subsection();

      // Second pass: everything, strictly.
      ParameterHandler prm;
      declare_first_pass(prm);
      if (dim == 2)
        Simulator<2>::declare_parameters(prm, names);
      else
        Simulator<3>::declare_parameters(prm, names);
      prm.parse_input(filename);
      for (const auto &o : overrides)
        apply_override(prm, o, true);

      // A relative mesh file is relative to the parameter file.
      prm.enter_subsection("Grid");
      const std::filesystem::path mesh = prm.get("Mesh file");
      if (!mesh.empty() && mesh.is_relative())
        prm.set("Mesh file",
                (std::filesystem::path(filename).parent_path() / mesh)
                  .string());
      prm.leave_subsection();

      if (dim == 2)
        run_scene<2>(prm, names, restart);
      else
        run_scene<3>(prm, names, restart);
      return 0;
    }
  } // namespace



  int
  run_command_line(const std::vector<std::string> &arguments)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    deal_II_exceptions::disable_abort_on_exception();
    deal_II_exceptions::suppress_stacktrace_in_exceptions();
    try
      {
        return run(arguments);
      }
    catch (const InputError &e)
      {
        if (is_root)
          std::cerr << "mpm: input error: " << e.what() << std::endl;
        return 2;
      }
    catch (const RunError &e)
      {
        if (is_root)
          std::cerr << "mpm: run stopped: " << e.what() << std::endl;
        return 3;
      }
    catch (const ExceptionBase &e)
      {
        // ParameterHandler reports bad files this way; its text names the
        // line, the entry and the allowed values.
        if (is_root)
          std::cerr << "mpm: input error: " << message_of(e) << std::endl;
        return 2;
      }
    catch (const std::exception &e)
      {
        // Possibly on this rank only: stop every rank.
        std::cerr << "mpm: error: " << e.what() << std::endl;
        const int code =
          dynamic_cast<const UnexpectedRunError *>(&e) != nullptr ? 3 : 1;
        if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
          MPI_Abort(MPI_COMM_WORLD, code);
        return code;
      }
  }
} // namespace mpm
