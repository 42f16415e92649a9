#ifndef fdparticle_io_output_writer_h
#define fdparticle_io_output_writer_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <fdparticle/base/statistics_table.h>
#include <fdparticle/particles/particle_set.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

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

    /// Create the directory, write parameters.prm and the table headers (statistics.csv:
    /// the columns declared in statistics). On a restart (resume = true) the tables keep
    /// their rows up to the checkpoint's step and time, the later ones (from the run that
    /// was interrupted) are dropped, and rows are appended.
    void initialize(const ParameterHandler &prm, const StatisticsTable &statistics,
                    const MPI_Comm comm, const bool resume = false,
                    const unsigned int resume_step = 0, const double resume_time = 0);

    /// The ParaView record lists (.pvd), for checkpoints.
    void save(std::ostream &out) const;
    void load(std::istream &in);

    bool vtu_due(const unsigned int step) const
    {
      return vtu_interval > 0 && step % vtu_interval == 0;
    }

    void write_particles_row(const double time, const ParticleSet<dim> &particles);
    /// The current row of statistics.
    void write_statistics_row(const StatisticsTable &statistics);
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
