#ifndef fdparticle_fem_assembly_assembly_term_h
#define fdparticle_fem_assembly_assembly_term_h

#include <fdparticle/fem/assembly/assembly_data.h>

namespace fdparticle
{
  /**
   * One term of the weak form (doc/method.md §3): its residual (the left-hand side of its
   * equation, Newton solves J δ = −R) and, when scratch.with_matrix, its exact Jacobian.
   * NavierStokesAssembler calls assemble_point at every point of a cell, then, with the
   * matrix, assemble_cell_matrix once for the cell, every term in a fixed order; a term
   * decides itself whether it acts (a penalty only in cut cells, the pairing only at points
   * inside a particle). A new physics term is a new class.
   */
  template <int dim>
  class AssemblyTerm
  {
  public:
    virtual ~AssemblyTerm() = default;
    virtual void assemble_point(const AssemblyScratch<dim> &scratch,
                                AssemblyCopy<dim> &         copy) const = 0;
    /// The Jacobian blocks between u and λ shape functions, for all points of the cell at
    /// once as products of CellShapes: one point at a time they cost O(shape functions²)
    /// per point, which dominated the 3D assembly. Only called with the matrix.
    virtual void assemble_cell_matrix(const AssemblyScratch<dim> & /*scratch*/,
                                      AssemblyCopy<dim> & /*copy*/) const
    {}
  };
} // namespace fdparticle

#endif
