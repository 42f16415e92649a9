#include <deal.II/base/mpi.h>
#include <deal.II/distributed/solution_transfer.h>

#include <fdparticle/io/checkpointer.h>
#include <fdparticle/base/parameter_tools.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    const std::string magic = "fdparticle-checkpoint-1";
  }

  template <int dim>
  void Checkpointer<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    {
      prm.declare_entry("Interval", "0", Patterns::Integer(0),
                        "Write a checkpoint every N steps and at the end of the run; 0: never "
                        "(a run that stops on an error still writes one, of its last good step).");
      prm.declare_entry("Resume", "false", Patterns::Bool(),
                        "Continue from the last checkpoint in 'Directory' instead of starting at "
                        "t = 0. The tables in the output directory keep their rows up to the "
                        "checkpoint. End time, Time step and solver settings may differ from the "
                        "interrupted run; the scene (dimension, particles, mesh) must not.");
      prm.declare_entry("Directory", "", Patterns::Anything(),
                        "Where checkpoints go; empty: the 'checkpoint' folder of the output "
                        "directory.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Checkpointer<dim>::parse_parameters(ParameterHandler &prm, const std::string &output_directory)
  {
    prm.enter_subsection("Checkpointing");
    interval = prm.get_integer("Interval");
    resume_run = prm.get_bool("Resume");
    checkpoint_directory = prm.get("Directory");
    prm.leave_subsection();
    if (checkpoint_directory.empty())
      checkpoint_directory = output_directory + "/checkpoint";
    // Each checkpoint replaces its directory as a whole (write()): one that is or holds
    // the output directory would take the tables with it.
    const auto normal = [](const std::string &name) {
      std::filesystem::path p = std::filesystem::absolute(name).lexically_normal();
      return p.has_filename() ? p : p.parent_path();
    };
    const std::filesystem::path checkpoint = normal(checkpoint_directory),
                                output = normal(output_directory);
    AssertThrow(std::mismatch(checkpoint.begin(), checkpoint.end(), output.begin(), output.end())
                    .first != checkpoint.end(),
                ExcMessage("Checkpointing/Directory '" + checkpoint_directory +
                           "' is or contains the output directory '" + output_directory +
                           "'; each checkpoint replaces its directory as a whole. Choose a "
                           "directory of its own (empty: 'checkpoint' in the output "
                           "directory)."));
  }

  template <int dim>
  std::string Checkpointer<dim>::readable_directory() const
  {
    if (std::filesystem::exists(checkpoint_directory + "/state.txt"))
      return checkpoint_directory;
    if (std::filesystem::exists(checkpoint_directory + ".old/state.txt"))
      return checkpoint_directory + ".old";
    return "";
  }

  template <int dim>
  void Checkpointer<dim>::check_directory(const MPI_Comm comm) const
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(comm) == 0 &&
        std::filesystem::exists(checkpoint_directory) &&
        !std::filesystem::is_directory(checkpoint_directory))
      error = "Checkpointing/Directory '" + checkpoint_directory +
              "' is a file, not a directory; a checkpoint would replace it. Choose another "
              "directory.";
    error = Utilities::MPI::broadcast(comm, error, 0);
    if (!error.empty())
      throw CollectiveError(error);
  }

  template <int dim>
  void Checkpointer<dim>::write(const parallel::distributed::Triangulation<dim> &tria,
                                const DoFHandler<dim> &                           dof_handler,
                                const std::vector<const TrilinosWrappers::MPI::Vector *> &vectors,
                                const unsigned int n_particles,
                                const std::string &state) const
  {
    const MPI_Comm    comm = tria.get_communicator();
    const bool        root = Utilities::MPI::this_mpi_process(comm) == 0;
    const std::string fresh = checkpoint_directory + ".new", old = checkpoint_directory + ".old";
    std::string       error;
    if (root)
      {
        std::error_code ec;
        std::filesystem::remove_all(fresh, ec);
        std::filesystem::create_directories(fresh, ec);
        if (ec)
          error = "Cannot create checkpoint directory '" + fresh + "' (" + ec.message() + ").";
      }
    // Errors found on rank 0 are shared, so that every rank ends normally (main.cc)
    // instead of the others waiting for rank 0 or being aborted with it.
    error = Utilities::MPI::broadcast(comm, error, 0);
    if (!error.empty())
      throw CollectiveError(error);

    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer(dof_handler);
    transfer.prepare_for_serialization(vectors);
    tria.save(fresh + "/mesh");

    if (root)
      try
        {
          std::ofstream out(fresh + "/state.txt.tmp");
          out << magic << ' ' << dim << ' ' << n_particles << '\n' << state;
          out.close();
          if (!out)
            throw std::runtime_error("Cannot write the checkpoint state in '" + fresh + "'.");
          std::filesystem::rename(fresh + "/state.txt.tmp", fresh + "/state.txt");
          // The swap: at every moment DIR or DIR.old is a complete checkpoint.
          std::filesystem::remove_all(old);
          if (std::filesystem::exists(checkpoint_directory))
            std::filesystem::rename(checkpoint_directory, old);
          std::filesystem::rename(fresh, checkpoint_directory);
          std::filesystem::remove_all(old);
        }
      catch (const std::exception &e)
        {
          error = e.what();
        }
    error = Utilities::MPI::broadcast(comm, error, 0);
    if (!error.empty())
      throw CollectiveError(error);
  }

  template <int dim>
  std::string Checkpointer<dim>::read_state(const MPI_Comm comm, const unsigned int n_particles) const
  {
    std::string state;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        const std::string dir = readable_directory();
        if (!dir.empty())
          {
            std::ifstream     in(dir + "/state.txt");
            std::stringstream buffer;
            buffer << in.rdbuf();
            state = buffer.str();
          }
      }
    state = Utilities::MPI::broadcast(comm, state, 0);
    AssertThrow(!state.empty(),
                ExcMessage("Checkpointing/Resume = true, but there is no checkpoint in '" +
                           checkpoint_directory + "'."));
    std::istringstream in(state);
    std::string        tag;
    unsigned int       file_dim = 0, file_particles = 0;
    in >> tag >> file_dim >> file_particles;
    AssertThrow(tag == magic, ExcMessage("'" + checkpoint_directory +
                                         "/state.txt' is not an fdparticle checkpoint."));
    AssertThrow(file_dim == dim,
                ExcMessage("The checkpoint in '" + checkpoint_directory + "' is from a " +
                           std::to_string(file_dim) + "D run; this scene is " +
                           std::to_string(dim) + "D."));
    AssertThrow(file_particles == n_particles,
                ExcMessage("The checkpoint in '" + checkpoint_directory + "' has " +
                           std::to_string(file_particles) + " particle(s); this scene has " +
                           std::to_string(n_particles) + "."));
    return state.substr(state.find('\n') + 1);
  }

  template <int dim>
  void Checkpointer<dim>::load_mesh(parallel::distributed::Triangulation<dim> &tria) const
  {
    std::string dir = (Utilities::MPI::this_mpi_process(tria.get_communicator()) == 0 ?
                         readable_directory() :
                         std::string());
    dir = Utilities::MPI::broadcast(tria.get_communicator(), dir, 0);
    tria.load(dir + "/mesh");
  }

  template <int dim>
  void Checkpointer<dim>::load_vectors(const DoFHandler<dim> &                            dof_handler,
                                       const std::vector<TrilinosWrappers::MPI::Vector *> &vectors) const
  {
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer(dof_handler);
    std::vector<TrilinosWrappers::MPI::Vector *> out = vectors;
    transfer.deserialize(out);
  }

  template class Checkpointer<2>;
  template class Checkpointer<3>;
} // namespace fdparticle
