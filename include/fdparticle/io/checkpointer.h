#ifndef fdparticle_io_checkpointer_h
#define fdparticle_io_checkpointer_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Checkpoint and restart (subsection Checkpointing). A checkpoint is a directory with the
   * p4est mesh and the solution vectors attached to its cells (deal.II serialization), and
   * state.txt: the time stepper, the particles and the tables' bookkeeping, written by the
   * caller as exact text. It is written atomically: into DIR.new, then DIR is moved to
   * DIR.old, DIR.new to DIR, and DIR.old removed, so an interrupted write leaves either
   * DIR or DIR.old complete; reading falls back to DIR.old when DIR is missing.
   */
  template <int dim>
  class Checkpointer
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    /// The default directory is OUTPUT_DIRECTORY/checkpoint.
    void        parse_parameters(ParameterHandler &prm, const std::string &output_directory);

    bool               resume() const { return resume_run; }
    bool               due(const unsigned int step) const { return interval > 0 && step % interval == 0; }
    bool               enabled() const { return interval > 0; }
    const std::string &directory() const { return checkpoint_directory; }

    /**
     * Throw a CollectiveError, on every rank, if the directory is an existing file: the
     * swap in write() would replace it (a run that stops on an error writes a checkpoint
     * too). Called before anything is written.
     */
    void check_directory(const MPI_Comm comm) const;

    /**
     * Write a checkpoint of the mesh, the given vectors (with ghost entries) and the text
     * state. n_particles is recorded so a restart of a different scene is refused.
     */
    void write(const parallel::distributed::Triangulation<dim> &   triangulation,
               const DoFHandler<dim> &                             dof_handler,
               const std::vector<const TrilinosWrappers::MPI::Vector *> &vectors,
               const unsigned int                                  n_particles,
               const std::string &                                 state) const;

    /**
     * Read the text state of the last checkpoint on every rank, after checking that it was
     * written by a run of this dimension with n_particles particles. Throws a one-sentence
     * error otherwise (before anything is created or written).
     */
    std::string read_state(const MPI_Comm comm, const unsigned int n_particles) const;

    /// Load the mesh onto the coarse mesh in triangulation (no refinement yet).
    void load_mesh(parallel::distributed::Triangulation<dim> &triangulation) const;

    /// After dof_handler.distribute_dofs(): the vectors, in the order they were written.
    void load_vectors(const DoFHandler<dim> &                       dof_handler,
                      const std::vector<TrilinosWrappers::MPI::Vector *> &vectors) const;

  private:
    /// DIR, or DIR.old if an interrupted write left only that one.
    std::string readable_directory() const;

    std::string  checkpoint_directory;
    unsigned int interval = 0;
    bool         resume_run = false;
  };
} // namespace fdparticle

#endif
