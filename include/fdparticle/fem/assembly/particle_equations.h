#ifndef fdparticle_fem_assembly_particle_equations_h
#define fdparticle_fem_assembly_particle_equations_h

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/particle_integrals.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/solvers/newton_system.h>

#include <array>
#include <vector>

namespace fdparticle
{
  /**
   * The rows of the free particles in the Newton system (doc/method.md §0, §3), from the
   * integrals the cell loop summed:
   *   translation (ρ_k − ρ_f)|P_k|(dV_k/dt − g) + <λ, e_i>_{P_k}            (F4)
   *   rotation    (ρ_k − ρ_f) J_k dω_k/dt + <λ, e_j × r>_{P_k}, or the seed's
   *               kinematic closure |P_k| ω_k − ½ ∫_{P_k} ∇ × u              (F5)
   * Their dependence on λ and u is the border row C the cell loop assembles; here the
   * residual r_p and the particle block D.
   */
  template <int dim>
  class ParticleEquations
  {
  public:
    ParticleEquations(const Fluid<dim> &fluid, const ParticleSet<dim> &particles)
      : fluid(fluid)
      , particles(particles)
    {}
    void assemble(const std::vector<ParticleIntegrals<dim>> &integrals,
                  const std::array<double, 3> &c, const bool with_matrix,
                  NewtonSystem &system) const;

  private:
    const Fluid<dim> &      fluid;
    const ParticleSet<dim> &particles;
  };
} // namespace fdparticle

#endif
