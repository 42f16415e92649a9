#ifndef fdparticle_fem_velocity_block_h
#define fdparticle_fem_velocity_block_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/fem/domain.h>
#include <fdparticle/fem/velocity_operator.h>
#include <fdparticle/solvers/newton_system.h>
#include <fdparticle/solvers/velocity_block_product.h>

#include <memory>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// The homogeneous constraints of a velocity-only DoFHandler on the system's domain
  /// (hanging nodes, periodicity, walls): those of the Newton correction's velocity.
  template <int dim>
  void make_velocity_constraints(const Domain<dim> &domain, const DoFHandler<dim> &velocity_dofs,
                                 AffineConstraints<double> &constraints);

  /**
   * The velocity block K of the Newton matrix on the system's mesh, without a matrix
   * (doc/method.md §8): VelocityOperator at the current Jacobian, the cut cells by their
   * assembled matrices, in the system's numbering. It replaces A_uu in the iterative
   * solver's products, so the Newton matrix holds no velocity block.
   *
   * Use: reinit() whenever the system's DoFs change, set_jacobian() after each assembly
   * of the Jacobian.
   */
  template <int dim>
  class VelocityBlock : public VelocityBlockProduct
  {
  public:
    using VectorType = typename VelocityOperator<dim>::VectorType;

    VelocityBlock(const Mapping<dim> &mapping, const Domain<dim> &domain);

    /// The system's mesh or DoFs changed; constraints: the Newton correction's (its
    /// velocity rows are K's constrained rows), kept by reference.
    void reinit(const DoFHandler<dim> &system_dofs, const NewtonSystem::Blocks &blocks,
                const AffineConstraints<double> &constraints);

    /// The Jacobian's velocity block: ρ, μ, the BDF weight c0, the iterate (owned system
    /// layout; nullptr: Stokes) and the cut cells' matrices (NavierStokesAssembler).
    void set_jacobian(const double density, const double viscosity, const double c0,
                      const TrilinosWrappers::MPI::Vector *iterate,
                      std::vector<FullMatrix<double>>      cut_matrices);

    void vmult_add(TrilinosWrappers::MPI::Vector &      dst,
                   const TrilinosWrappers::MPI::Vector &src) const override;
    void assemble_on_cells(const std::vector<bool> &        cells,
                           TrilinosWrappers::SparseMatrix &matrix) const override;

    /// What a multigrid below it reads (after set_jacobian()): the velocity DoFs and
    /// their constraints, each owned one's place among the system's owned DoFs, the
    /// coefficients, the iterate on the velocity DoFs (nullptr: Stokes) and the operator.
    const DoFHandler<dim> &          get_dof_handler() const { return velocity_dofs; }
    const AffineConstraints<double> &get_constraints() const { return constraints; }
    const std::vector<unsigned int> &get_system_positions() const { return system_position; }
    double                           get_density() const { return density; }
    double                           get_viscosity() const { return viscosity; }
    double                           get_c0() const { return c0; }
    const VectorType *get_iterate() const { return convection ? &iterate : nullptr; }
    const VelocityOperator<dim> &    get_operator() const { return op; }

  private:
    void build();

    const Mapping<dim> &               mapping;
    const Domain<dim> &                domain;
    const FESystem<dim>                fe;
    const DoFHandler<dim> *            system_dofs        = nullptr;
    const NewtonSystem::Blocks *       blocks             = nullptr;
    const AffineConstraints<double> *  system_constraints = nullptr;
    types::global_dof_index            first_owned        = 0;
    bool                               current            = false;
    double                             density = 1, viscosity = 1, c0 = 0;
    bool                               convection = false;

    DoFHandler<dim>           velocity_dofs;
    AffineConstraints<double> constraints;
    VelocityOperator<dim>     op;
    /// For each owned velocity DoF, its place among the system's owned DoFs; the owned
    /// unconstrained DoFs among them.
    std::vector<unsigned int> system_position, unconstrained;
    /// The operator's cell batch of each active cell (invalid: not owned).
    std::vector<unsigned int> batch_of_cell;
    VectorType                      iterate;
    mutable VectorType              in, out;
  };
} // namespace fdparticle

#endif
