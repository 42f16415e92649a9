#ifndef fdparticle_fem_assembly_fluid_momentum_h
#define fdparticle_fem_assembly_fluid_momentum_h

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/assembly_term.h>

namespace fdparticle
{
  /**
   * The fluid on the whole box, (F1)–(F2) without the multiplier (doc/method.md §0, §3):
   *   momentum   ∫ ρ(∂_t u + u·∇u − g)·v − f·v + 2μ ε(u):ε(v) − p ∇·v
   *   continuity −∫ q ∇·u
   * The convection term only with Fluid/Convection.
   */
  template <int dim>
  class FluidMomentum : public AssemblyTerm<dim>
  {
  public:
    explicit FluidMomentum(const Fluid<dim> &fluid)
      : fluid(fluid)
    {}
    void assemble_point(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;
    void assemble_cell_matrix(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;

  private:
    const Fluid<dim> &fluid;
  };
} // namespace fdparticle

#endif
