#ifndef fdparticle_fem_navier_stokes_assembler_h
#define fdparticle_fem_navier_stokes_assembler_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/newton_system.h>
#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/core/fluid.h>
#include <fdparticle/particles/particle_set.h>

#include <array>
#include <memory>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// Integrals over each ball that the particle equations and the reported forces need.
  template <int dim>
  struct ParticleIntegrals
  {
    Tensor<1, dim> lambda_force;  ///< <λ, e_i>_P = ∫_P α λ_i
    Tensor<1, 3>   lambda_torque; ///< <λ, e_j × r>_P
    Tensor<1, 3>   curl_u;        ///< ∫_P ∇ × u
    double         volume = 0;    ///< ∫_P 1 by the cut-cell rule
  };

  /**
   * Residual and exact Jacobian of equations (F1)–(F5) (doc/method.md §0, §3) at t^{n+1}, with the
   * particle geometry frozen during the step. Sign convention: the residual R is the
   * left-hand side of each equation; Newton solves J δ = −R.
   *
   *  1. momentum   ∫ ρ(∂_t u + u·∇u − g)·v − f·v + 2μ ε(u):ε(v) − p ∇·v − Σ_k <λ, v>_{P_k}
   *  2. continuity −∫ q ∇·u  (− (δ/μ) ∫ (p − p_hydrostatic) q in cells inside a particle)
   *  3. rigidity   <η, u − V_k − ω_k × r>_{P_k}  (+ s α ∫_{Ω_f ∩ cut cells} λ·η)
   *  4. translation (ρ_k − ρ_f)|P_k|(dV_k/dt − g) + <λ, e_i>_{P_k}
   *  5. rotation   (ρ_k − ρ_f) J_k dω_k/dt + <λ, e_j × r>_{P_k}, or the seed's kinematic
   *                closure |P_k| ω_k − ½ ∫_{P_k} ∇ × u
   * with <λ, v>_P = ∫_P α λ·v + μ ∇λ:∇v and α = ρ_f c0 (3ρ_f/(2Δt) for BDF2).
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

    /**
     * Assemble R (and J if with_matrix) at the iterate (solution, particle unknowns as
     * stored in the ParticleSet). history = c1 u^n + c2 u^{n−1}; c are the BDF weights.
     * Returns the particle integrals (summed over all ranks).
     */
    std::vector<ParticleIntegrals<dim>>
    assemble(const DoFHandler<dim> &dof_handler, const TrilinosWrappers::MPI::Vector &solution,
             const TrilinosWrappers::MPI::Vector &history, const std::array<double, 3> &c,
             const AffineConstraints<double> &constraints, const bool with_matrix,
             NewtonSystem &system) const;

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
    };

    /// mesh_constraints: the hanging-node and periodicity constraints (closed).
    ParticleSupport particle_support(const DoFHandler<dim> &         dof_handler,
                                     const IndexSet &                 locally_relevant,
                                     const AffineConstraints<double> &mesh_constraints) const;

    /// Per-cell volume fraction of particles (for output).
    Vector<float> particle_fraction(const DoFHandler<dim> &dof_handler) const;

    const MappingQ<dim> &get_mapping() const { return mapping; }

    /// The point where the hydrostatic pressure is zero (the pressure level's cell centre).
    void set_pressure_reference(const Point<dim> &x) { pressure_reference = x; }

  private:
    const FESystem<dim> &         fe;
    const Fluid<dim> &            fluid;
    const ParticleSet<dim> &      particles;
    const CutCellQuadrature<dim> &quadrature;
    MappingQ<dim>                 mapping{1};
    double                        fluid_penalty = 0.01;
    double                        strain_penalty = 0.15;
    double                        penalty_ramp = 0.2;
    double                        pairing_time_step = 0.0; // 0: α = ρ c0 of the current step
    double                        interior_pressure_penalty = 1e-3;
    Point<dim>                    pressure_reference;
  };
} // namespace fdparticle

#endif
