#ifndef fdparticle_fem_velocity_multigrid_h
#define fdparticle_fem_velocity_multigrid_h

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/multigrid/mg_base.h>
#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include <fdparticle/fem/domain.h>
#include <fdparticle/fem/velocity_block.h>
#include <fdparticle/fem/velocity_operator.h>
#include <fdparticle/solvers/newton_system.h>
#include <fdparticle/solvers/velocity_block_inverse.h>

#include <memory>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * One geometric multigrid V-cycle for the velocity block K of the Newton matrix
   * (doc/method.md §8): VelocityOperator on every Q2 level, Chebyshev smoothing on its
   * diagonal, and below them Q1 on the base mesh, where one AMG V-cycle (ML, with the
   * block preconditioner's settings) works on the Galerkin projection of the base mesh's
   * Q2 operator, assembled. The Q2 levels are the mesh coarsened globally one level at a
   * time (Domain::create_coarsened_copy), each with its own hanging-node, periodicity and
   * wall constraints, so the particle-following refinement needs no interface terms;
   * MGTwoLevelTransfer moves between them (and from Q2 to Q1). The finest level is the
   * VelocityBlock's (its DoFs, constraints and cut cells' matrices), with the Jacobian
   * it held when the block preconditioner called initialize(); the coarser ones use the
   * Gauss rule in every cell.
   *
   * Use: reinit() whenever the system's DoFs change (after the VelocityBlock's); the
   * block preconditioner calls initialize() when it rebuilds. Vectors of vmult() are in
   * the system's velocity block numbering (NewtonSystem::Blocks); constrained rows are
   * divided by A's diagonal.
   */
  template <int dim>
  class VelocityMultigrid : public VelocityBlockInverse
  {
  public:
    using VectorType = typename VelocityOperator<dim>::VectorType;

    /// fine: the finest level, which must outlive the multigrid.
    VelocityMultigrid(const Mapping<dim> &mapping, const Domain<dim> &domain,
                      const VelocityBlock<dim> &fine);
    ~VelocityMultigrid() override;

    /// The system's mesh or DoFs changed: the levels are rebuilt by the next initialize().
    void reinit();

    void initialize(const NewtonSystem &                                   system,
                    const TrilinosWrappers::PreconditionAMG::AdditionalData &amg) override;
    /// Whether the V-cycle is built on the current levels (not between reinit() and the
    /// next initialize()).
    bool initialized() const override { return levels_current && preconditioner != nullptr; }
    void vmult(TrilinosWrappers::MPI::Vector &      dst,
               const TrilinosWrappers::MPI::Vector &src) const override;

  private:
    void build_levels();

    const Mapping<dim> &      mapping;
    const Domain<dim> &       domain;
    const VelocityBlock<dim> &fine;
    const FESystem<dim>       fe, coarse_fe;
    bool                      levels_current = false;

    /// Per level, coarsest first: the base mesh twice (Q1, then Q2), then the finer
    /// meshes; the last is the system's own mesh, with the VelocityBlock's DoFs.
    std::vector<std::shared_ptr<const parallel::distributed::Triangulation<dim>>> meshes;
    std::vector<std::shared_ptr<const DoFHandler<dim>>>                       dof_handlers;
    MGLevelObject<AffineConstraints<double>>                                 constraints;
    MGLevelObject<VelocityOperator<dim>>                                      operators;
    MGLevelObject<MGTwoLevelTransfer<dim, VectorType>>                        transfers;
    std::unique_ptr<MGTransferGlobalCoarsening<dim, VectorType>>              transfer;
    /// The layout of level 0's vectors (it has no operator).
    std::shared_ptr<const Utilities::MPI::Partitioner>                       base_partitioner;

    using Smoother = PreconditionChebyshev<VelocityOperator<dim>, VectorType>;
    mg::SmootherRelaxation<Smoother, VectorType>             smoother;
    /// The base mesh's operator assembled, and one ML V-cycle on it as the coarse solve.
    TrilinosWrappers::SparseMatrix                           coarse_matrix;
    TrilinosWrappers::PreconditionAMG                        coarse_amg;
    std::unique_ptr<MGCoarseGridBase<VectorType>>            coarse;
    std::unique_ptr<MGMatrixBase<VectorType>>                level_matrix;
    std::unique_ptr<Multigrid<VectorType>>                   multigrid;
    std::unique_ptr<PreconditionMG<dim, VectorType, MGTransferGlobalCoarsening<dim, VectorType>>>
      preconditioner;

    /// The finest level's constrained owned DoFs (local index) and 1 / A's diagonal there.
    std::vector<std::pair<unsigned int, double>> constrained_rows;
    /// The iterate of the Jacobian on each level (Navier–Stokes).
    MGLevelObject<VectorType> level_iterates;

    mutable VectorType in, out;
  };
} // namespace fdparticle

#endif
