#ifndef fdparticle_solvers_velocity_block_product_h
#define fdparticle_solvers_velocity_block_product_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The velocity block K = A_uu of the Newton matrix where A leaves it out: the program
   * that owns the mesh applies it without a matrix (doc/method.md §8), and assembles it
   * on the few cells whose rows a solver needs as a matrix (the cut-cell patch). A holds
   * the constrained velocity rows' diagonal; K has nothing in them.
   */
  class VelocityBlockProduct
  {
  public:
    virtual ~VelocityBlockProduct() = default;

    /// dst += K src on the owned unconstrained velocity rows; both in A's layout (the
    /// whole finite-element vector, of which only the velocity block is read).
    virtual void vmult_add(TrilinosWrappers::MPI::Vector &      dst,
                           const TrilinosWrappers::MPI::Vector &src) const = 0;

    /**
     * K's entries from the owned cells marked in `cells` (indexed in the order of their
     * pressure DoFs, NewtonSystem::Blocks), summed over the ranks into `matrix`, laid out
     * as A (global numbering, owned rows). A row is K's whole row where all cells around
     * its DoF are marked on their owners. Collective.
     */
    virtual void assemble_on_cells(const std::vector<bool> &        cells,
                                   TrilinosWrappers::SparseMatrix &matrix) const = 0;
  };
} // namespace fdparticle

#endif
