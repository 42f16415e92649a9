#ifndef fdparticle_fem_navier_stokes_assembler_h
#define fdparticle_fem_navier_stokes_assembler_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/assembly_term.h>
#include <fdparticle/fem/assembly/cut_cell_penalties.h>
#include <fdparticle/fem/assembly/fluid_momentum.h>
#include <fdparticle/fem/assembly/interior_pressure.h>
#include <fdparticle/fem/assembly/multiplier_pairing.h>
#include <fdparticle/fem/assembly/particle_equations.h>
#include <fdparticle/fem/assembly/particle_integrals.h>
#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/solvers/newton_system.h>

#include <array>
#include <memory>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Residual and exact Jacobian of equations (F1)–(F5) (doc/method.md §0, §3) at t^{n+1},
   * with the particle geometry frozen during the step. Sign convention: the residual R is
   * the left-hand side of each equation; Newton solves J δ = −R.
   *
   * The cell loop chooses each cell's quadrature (CutCellQuadrature), evaluates the iterate
   * at its points (AssemblyScratch) and lets the terms add to the cell's matrix and vectors
   * (AssemblyCopy), point by point in this order:
   *   FluidMomentum      (F1)–(F2) without λ
   *   InteriorPressure   the pressure level inside rigid bodies
   *   MultiplierPairing  −<λ, v> in (F1), (F3), the border of the free particles
   *   CutCellPenalties   the fluid and strain penalties of (F3) on cut cells
   * then the particle rows (F4)–(F5) come from the integrals (ParticleEquations). The
   * pairing is <λ, v>_P = ∫_P α λ·v + μ ∇λ:∇v with α = ρ_f c0 (3ρ_f/(2Δt) for BDF2), or
   * from Multiplier/Pairing time step.
   */
  template <int dim>
  class NavierStokesAssembler
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    NavierStokesAssembler(const FESystem<dim> &fe, const Fluid<dim> &fluid,
                          const ParticleSet<dim> &particles,
                          const CutCellQuadrature<dim> &quadrature);
    /// The term list points into this object.
    NavierStokesAssembler(const NavierStokesAssembler &) = delete;
    NavierStokesAssembler &operator=(const NavierStokesAssembler &) = delete;

    /**
     * Assemble R (and J if with_matrix) at the iterate (solution, particle unknowns as
     * stored in the ParticleSet). history = c1 u^n + c2 u^{n−1}; c are the BDF weights.
     * Returns the particle integrals (summed over all ranks).
     *
     * With the matrix and cut_velocity_matrices given, it also returns the velocity block
     * of each owned cut cell's matrix (before the constraints), indexed by the cell's
     * active_cell_index() and ordered (component c, FE_Q shape function a) → c n + a; other
     * cells get an empty matrix (VelocityOperator::set_cut_cell_matrices), and A gets no
     * velocity block: the caller applies it without a matrix (VelocityBlock).
     */
    std::vector<ParticleIntegrals<dim>>
    assemble(const DoFHandler<dim> &dof_handler, const TrilinosWrappers::MPI::Vector &solution,
             const TrilinosWrappers::MPI::Vector &history, const std::array<double, 3> &c,
             const AffineConstraints<double> &constraints, const bool with_matrix,
             NewtonSystem &                   system,
             std::vector<FullMatrix<double>> *cut_velocity_matrices = nullptr) const;

    /// Where the particles are, as the constraints of a step need it.
    struct ParticleSupport
    {
      /// λ DoFs whose support (as basis functions of the conforming space, after the mesh
      /// constraints) contains a quadrature point inside a particle; the others are
      /// constrained to zero (λ = 0 in the fluid, seed 3.15a).
      IndexSet active_multipliers;
      /// True when the interior-pressure penalty acts on some cell (on any rank): it then
      /// fixes the pressure level, and no pressure DoF may be pinned (doc/method.md §4).
      bool pressure_level_fixed = false;
      /// The owned cells with quadrature points of a free particle, each with that
      /// particle: where its columns of B and Cᵀ have entries.
      std::vector<std::pair<typename DoFHandler<dim>::active_cell_iterator, unsigned int>>
        free_particle_cells;
    };

    /// mesh_constraints: the hanging-node and periodicity constraints (closed).
    ParticleSupport particle_support(const DoFHandler<dim> &         dof_handler,
                                     const IndexSet &                 locally_relevant,
                                     const AffineConstraints<double> &mesh_constraints) const;

    /// The pattern of B and Cᵀ (NewtonSystem::border_pattern): the velocity and multiplier
    /// DoFs of each cell in support.free_particle_cells against its particle's unknowns,
    /// after the constraints of the step. Collective.
    TrilinosWrappers::SparsityPattern border_pattern(const ParticleSupport &          support,
                                                     const AffineConstraints<double> &constraints,
                                                     const IndexSet &                 locally_owned,
                                                     const IndexSet &locally_relevant,
                                                     const MPI_Comm   comm) const;

    /// Per-cell volume fraction of particles (for output).
    Vector<float> particle_fraction(const DoFHandler<dim> &dof_handler) const;

    const MappingQ<dim> &get_mapping() const { return mapping; }

    /// The point where the hydrostatic pressure is zero (the pressure level's cell centre).
    void set_pressure_reference(const Point<dim> &x) { interior_pressure.set_reference_point(x); }

  private:
    const FESystem<dim> &         fe;
    const Fluid<dim> &            fluid;
    const ParticleSet<dim> &      particles;
    const CutCellQuadrature<dim> &quadrature;
    MappingQ<dim>                 mapping{1};
    double                        pairing_time_step = 0.0; // 0: α = ρ c0 of the current step
    double                        pairing_viscous_weight = 0.0; // c of κ = α + c μ/R²

    FluidMomentum<dim>     fluid_momentum;
    InteriorPressure<dim>  interior_pressure;
    MultiplierPairing<dim> multiplier_pairing;
    CutCellPenalties<dim>  cut_cell_penalties;
    ParticleEquations<dim> particle_equations;
    /// The terms of the cell loop, in the order they are called at each point.
    std::vector<const AssemblyTerm<dim> *> terms;
  };
} // namespace fdparticle

#endif
