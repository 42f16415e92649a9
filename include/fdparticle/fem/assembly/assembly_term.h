#ifndef fdparticle_fem_assembly_assembly_term_h
#define fdparticle_fem_assembly_assembly_term_h

#include <fdparticle/fem/assembly/assembly_data.h>

namespace fdparticle
{
  /**
   * One term of the weak form (doc/method.md §3): its residual (the left-hand side of its
   * equation, Newton solves J δ = −R) and, when scratch.with_matrix, its exact Jacobian,
   * at one quadrature point. NavierStokesAssembler calls every term at every point, in a
   * fixed order; a term decides itself whether it acts there (a penalty only in cut cells,
   * the pairing only at points inside a particle). A new physics term is a new class.
   */
  template <int dim>
  class AssemblyTerm
  {
  public:
    virtual ~AssemblyTerm() = default;
    virtual void assemble_point(const AssemblyScratch<dim> &scratch,
                                AssemblyCopy<dim> &         copy) const = 0;
  };
} // namespace fdparticle

#endif
