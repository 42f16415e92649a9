#ifndef fdparticle_fem_assembly_multiplier_pairing_h
#define fdparticle_fem_assembly_multiplier_pairing_h

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/assembly_term.h>
#include <fdparticle/particles/particle_set.h>

namespace fdparticle
{
  /**
   * The coupling of fluid and particle at the points inside particle P_k (doc/method.md
   * §0, §3), with <λ, v>_P = ∫_P κ λ·v + μ ∇λ:∇v, κ = α + c μ/R² (§4, AssemblyScratch):
   *   momentum   − <λ, v>_{P_k}                      (in (F1))
   *   rigidity   <η, u − V_k − ω_k × r>_{P_k}         (F3)
   * and, for a free particle, the border of the Newton system: ∂(F3)/∂(V, ω) (column B)
   * and ∂(F4)–(F5)/∂(λ, u) (row C). It also sums the particle integrals (ParticleIntegrals)
   * that (F4)–(F5) and the reported forces need.
   */
  template <int dim>
  class MultiplierPairing : public AssemblyTerm<dim>
  {
  public:
    MultiplierPairing(const Fluid<dim> &fluid, const ParticleSet<dim> &particles)
      : fluid(fluid)
      , particles(particles)
    {}
    void assemble_point(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;
    void assemble_cell_matrix(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;

  private:
    const Fluid<dim> &      fluid;
    const ParticleSet<dim> &particles;
  };
} // namespace fdparticle

#endif
