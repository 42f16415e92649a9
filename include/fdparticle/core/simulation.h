#ifndef fdparticle_core_simulation_h
#define fdparticle_core_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/io/checkpointer.h>
#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/navier_stokes_assembler.h>
#include <fdparticle/fem/pressure_agglomeration.h>
#include <fdparticle/io/output_writer.h>
#include <fdparticle/fem/particle_refinement.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/io/smoothness_meter.h>
#include <fdparticle/base/time_stepper.h>
#include <fdparticle/particles/particle_interactions.h>
#include <fdparticle/solvers/linear_solver_factory.h>
#include <fdparticle/solvers/newton_solver.h>
#include <fdparticle/solvers/newton_system.h>

#include <memory>

namespace fdparticle
{
  template <int dim>
  class VelocityMultigrid;
  template <int dim>
  class VelocityBlock;

  using namespace dealii;

  /// Declare every parameter of the program (all dimensions share one declaration).
  void declare_all_parameters(ParameterHandler &prm);

  /**
   * One run of a scene: the mesh and the (u, λ, p) finite element, the constraints that
   * change with the particles, the time loop and, inside each step, Newton's method on
   * the bordered system (doc/method.md §3, §5, §8). Stokes scenes take a single linear
   * solve a step.
   *
   * The members are defined by job, as ASPECT splits its Simulator, in
   * source/core/simulation/: core.cc (parameters, the run and its time loop), setup.cc
   * (mesh, DoFs, constraints, matrix layout, adaptation), time_step.cc (one step: Newton,
   * recovery of failed steps, particle forces), checkpoint_restart.cc, diagnostics.cc
   * (statistics and output of a step).
   */
  template <int dim>
  class Simulation
  {
  public:
    /// Reads and checks every parameter; throws a one-sentence error on bad input.
    Simulation(ParameterHandler &prm, const MPI_Comm comm);
    void run();

  private:
    /// Mesh, DoFs and initial state at t = 0, and the first output.
    void   start();
    /// Mesh, vectors and state from the last checkpoint (Checkpointing/Resume).
    void   resume();
    void   write_checkpoint();
    /// Advance by one accepted step, retrying with smaller steps when Newton fails.
    void   do_time_step();
    /// Where the residual is largest, in words (for failure messages).
    std::string describe_residual() const;
    void   setup_dofs();
    /// Refine around the particles (with transfer of the solution and its history).
    void   adapt_mesh(const bool transfer);
    /// Execute the flagged refinement and the weighted partition, with transfer of the
    /// solution and its history if asked.
    void   change_mesh(const bool transfer);
    /// Repartition the mesh if the cut cells' load has drifted out of balance between the
    /// ranks (it says so in a line of its own).
    void   rebalance();
    /// " (min-max cells each)" on several ranks, "" on one.
    std::string partition_summary() const;
    /// The constraints of a step; returns where the particles are, as setup_matrix needs it.
    typename NavierStokesAssembler<dim>::ParticleSupport make_constraints();
    void setup_matrix(const typename NavierStokesAssembler<dim>::ParticleSupport &support);
    void   set_initial_pressure();
    /// Newton's method for the step prepared by do_time_step(); on success the particle
    /// forces are updated and the statistics get the iterations and residuals.
    NewtonSolver::Result solve_time_step();
    void   update_particle_forces(const std::vector<ParticleIntegrals<dim>> &integrals);
    double max_velocity() const;
    /// The columns of statistics.csv: Simulation's own (the step, its solve, the fields),
    /// then those of the classes that compute the others.
    void   declare_statistics();
    /// hydrostatic_deviation and mean_v of the statistics, in one pass over the cells.
    void   field_statistics();
    void   write_output(const bool fields);
    /// The time loop of run(), from the start (or the checkpoint) to End time.
    void   run_time_loop();
    /// Load of the most loaded rank over the mean (cell weights of Quadrature/Cut cell
    /// cost) above which rebalance() repartitions. A fresh weighted partition is balanced
    /// to a cell or two; a repartition costs a mesh change with the transfer of three
    /// solution vectors and a new DoF numbering, about as much as a refinement pass. 10 %
    /// of the assembly, which is a fifth to a half of a step on the scenes of
    /// doc/particles.md, is where waiting costs more than that.
    static constexpr double max_partition_imbalance = 1.1;

    MPI_Comm            comm;
    ConditionalOStream  pcout;
    std::unique_ptr<TimerOutput> timer;
    ParameterHandler &  prm;

    Domain<dim>            domain;
    Fluid<dim>             fluid;
    ParticleSet<dim>       particles;
    TimeStepper            time;
    CutCellQuadrature<dim> quadrature;
    OutputWriter<dim>      output;
    StatisticsTable        statistics;
    ParticleRefinement<dim> refinement;
    SmoothnessMeter<dim>   smoothness;
    Checkpointer<dim>      checkpointer;
    ParticleInteractions<dim> interactions;
    unsigned int           base_level = 0;
    NewtonSystem                  system;
    /// Declared after the system it refers to, so that it is destroyed first.
    std::unique_ptr<LinearSolver> linear_solver;
    NewtonSolver                  newton;

    bool hydrostatic_start = false;

    parallel::distributed::Triangulation<dim> triangulation;
    FESystem<dim>                             fe;
    DoFHandler<dim>                           dof_handler;
    NavierStokesAssembler<dim>                assembler;
    PressureAgglomeration<dim>                pressure_agglomeration;
    /// The velocity block without a matrix, and its multigrid, if the linear solver asks
    /// for them.
    std::shared_ptr<VelocityBlock<dim>>       velocity_block;
    std::shared_ptr<VelocityMultigrid<dim>>   velocity_multigrid;

    IndexSet                  owned_dofs, relevant_dofs, velocity_dofs, multiplier_dofs;
    AffineConstraints<double> static_constraints;  ///< hanging nodes + periodicity
    AffineConstraints<double> update_constraints;  ///< homogeneous: Newton corrections
    AffineConstraints<double> state_constraints;   ///< wall velocities: the solution itself
    /// The DoFs that update_constraints fixed when A's pattern was built (empty after new
    /// DoFs): setup_matrix keeps the pattern while they stay the same.
    IndexSet                  pattern_constrained;
    /// The pressure agglomeration's ties when A's pattern was built, flattened (each
    /// cell's first pressure DoF, then its masters), and those of this step's constraints.
    std::vector<types::global_dof_index> pattern_links, current_links;
    types::global_dof_index   pressure_reference_dof = 0;
    Point<dim>                pressure_reference_point;

    TrilinosWrappers::MPI::Vector solution, old_solution, old_old_solution;
    TrilinosWrappers::MPI::Vector solution_ghost, history_ghost;
    std::vector<ParticleIntegrals<dim>> last_integrals;
    double                              wall_start = 0;
  };
} // namespace fdparticle

#endif
