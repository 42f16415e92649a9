#ifndef fdparticle_io_output_writer_h
#define fdparticle_io_output_writer_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <fdparticle/particles/particle_set.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// One row of statistics.csv.
  struct StepStatistics
  {
    unsigned int step = 0;
    double       time = 0, dt = 0;
    unsigned long long cells = 0, dofs = 0;
    unsigned int nonlinear_iterations = 0;
    /// Iterations of the linear solves of the step (one per solve for the direct solver).
    unsigned int linear_iterations = 0;
    /// Iterations of the inner solves of the iterative solver's preconditioner.
    unsigned int inner_iterations = 0;
    /// Jacobians assembled, and factorizations (direct solver) or preconditioner builds
    /// (iterative solver) of the linear solver.
    unsigned int jacobians = 0, solver_setups = 0;
    double       residual = 0, wall_seconds = 0, initial_residual = 0;
    double       max_velocity = 0, hydrostatic_deviation = 0;
    /// Cells cut by a particle surface below the finest level (0 on a uniform mesh).
    unsigned int coarse_cut_cells = 0;
    /// Halvings of the time step this step needed (recovery from a failed step).
    unsigned int time_step_reductions = 0;
    /// Volume average of the fluid velocity over the box (superficial velocity).
    Tensor<1, 3> mean_velocity;
    /// Pairs of particles within the collision range, and the smallest gap between two
    /// particles, capped at a diameter (Collisions::statistics).
    unsigned int contacts = 0;
    double       min_gap  = 0;
    /// Mean velocity of the free particles (0 without any): a suspension's mean settling
    /// velocity.
    Tensor<1, 3> mean_particle_velocity;
  };

  /**
   * Everything a run leaves in its output directory (subsection Output): ParaView files
   * (solution-NNNNN.pvtu + solution.pvd, particles-NNNNN.vtu + particles.pvd), the complete
   * parameter set used (parameters.prm), and the tables particles.csv and statistics.csv.
   * Rank 0 writes the tables; every rank writes its piece of the field output.
   */
  template <int dim>
  class OutputWriter
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /// Create the directory, write parameters.prm and the table headers. On a restart
    /// (resume = true) the tables keep their rows up to the checkpoint's step and time,
    /// the later ones (from the run that was interrupted) are dropped, and rows are appended.
    void initialize(const ParameterHandler &prm, const MPI_Comm comm, const bool resume = false,
                    const unsigned int resume_step = 0, const double resume_time = 0);

    /// The ParaView record lists (.pvd), for checkpoints.
    void save(std::ostream &out) const;
    void load(std::istream &in);

    bool vtu_due(const unsigned int step) const
    {
      return vtu_interval > 0 && step % vtu_interval == 0;
    }

    void write_particles_row(const double time, const ParticleSet<dim> &particles);
    void write_statistics_row(const StepStatistics &s);
    void write_fields(const unsigned int step, const double time, const Mapping<dim> &mapping,
                      const DoFHandler<dim> &dof_handler,
                      const TrilinosWrappers::MPI::Vector &solution,
                      const Vector<float> &particle_fraction, const ParticleSet<dim> &particles);
    const std::string &directory() const { return output_directory; }

  private:
    std::string                              output_directory = "output";
    unsigned int                             vtu_interval = 1;
    MPI_Comm                                 comm = MPI_COMM_WORLD;
    bool                                     root = true;
    std::ofstream                            particles_csv, statistics_csv;
    std::vector<std::pair<double, std::string>> solution_records, particle_records;
  };
} // namespace fdparticle

#endif
