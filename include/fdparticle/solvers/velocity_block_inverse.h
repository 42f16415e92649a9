#ifndef fdparticle_solvers_velocity_block_inverse_h
#define fdparticle_solvers_velocity_block_inverse_h

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_vector.h>

namespace fdparticle
{
  using namespace dealii;

  class NewtonSystem;

  /**
   * An approximate inverse of the velocity block K = A_uu of the Newton matrix, which the
   * block preconditioner applies in place of its AMG V-cycle (doc/method.md §8). The
   * program that owns the mesh supplies it (NewtonSystem::Blocks::velocity_inverse): an
   * implementation knows the mesh and the operator, the solver only the block numbering.
   */
  class VelocityBlockInverse
  {
  public:
    virtual ~VelocityBlockInverse() = default;

    /// Build for the system's current Jacobian (called when the preconditioner is rebuilt).
    /// amg: the ML settings the block preconditioner would use on A_uu, for an algebraic
    /// part (its constant modes are the implementation's to set).
    virtual void initialize(const NewtonSystem &                                   system,
                            const TrilinosWrappers::PreconditionAMG::AdditionalData &amg) = 0;

    /// Whether the last initialize() still holds: false once the mesh or the DoFs changed
    /// underneath it, when the block preconditioner must be rebuilt.
    virtual bool initialized() const = 0;

    /// dst ≈ K⁻¹ src. Both hold the velocity block's owned DoFs in the block numbering.
    virtual void vmult(TrilinosWrappers::MPI::Vector &      dst,
                       const TrilinosWrappers::MPI::Vector &src) const = 0;
  };
} // namespace fdparticle

#endif
