#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>

#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/velocity_block.h>
#include <fdparticle/fem/velocity_multigrid.h>

namespace fdparticle
{
  namespace
  {
    /// The coarse solve: one application of a preconditioner.
    template <typename VectorType, typename Preconditioner>
    class ApplyPreconditioner : public MGCoarseGridBase<VectorType>
    {
    public:
      explicit ApplyPreconditioner(const Preconditioner &preconditioner)
        : preconditioner(preconditioner)
      {}
      void operator()(const unsigned int, VectorType &dst, const VectorType &src) const override
      {
        preconditioner.vmult(dst, src);
      }

    private:
      const Preconditioner &preconditioner;
    };

    /// The level operators for Multigrid: VelocityOperator on the Q2 levels 1, 2, …;
    /// level 0 (Q1) has none, the coarse solve acts there alone.
    template <int dim, typename VectorType>
    class LevelOperators : public MGMatrixBase<VectorType>
    {
    public:
      explicit LevelOperators(const MGLevelObject<VelocityOperator<dim>> &operators)
        : operators(operators)
      {}
      void vmult(const unsigned int level, VectorType &dst, const VectorType &src) const override
      {
        operators[level].vmult(dst, src);
      }
      void vmult_add(const unsigned int level, VectorType &dst,
                     const VectorType &src) const override
      {
        VectorType product;
        product.reinit(dst);
        operators[level].vmult(product, src);
        dst += product;
      }
      void Tvmult(const unsigned int level, VectorType &dst, const VectorType &src) const override
      {
        operators[level].Tvmult(dst, src);
      }
      void Tvmult_add(const unsigned int level, VectorType &dst,
                      const VectorType &src) const override
      {
        operators[level].Tvmult(dst, src);
      }
      unsigned int get_minlevel() const override { return 0; }
      unsigned int get_maxlevel() const override { return operators.max_level(); }

    private:
      const MGLevelObject<VelocityOperator<dim>> &operators;
    };
  } // namespace

  template <int dim>
  VelocityMultigrid<dim>::VelocityMultigrid(const Mapping<dim> &mapping, const Domain<dim> &domain,
                                            const VelocityBlock<dim> &fine)
    : mapping(mapping)
    , domain(domain)
    , fine(fine)
    , fe(FE_Q<dim>(VelocityOperator<dim>::degree), dim)
    , coarse_fe(FE_Q<dim>(1), dim)
  {}

  template <int dim>
  VelocityMultigrid<dim>::~VelocityMultigrid() = default;

  template <int dim>
  void VelocityMultigrid<dim>::reinit()
  {
    levels_current = false;
  }

  template <int dim>
  void VelocityMultigrid<dim>::build_levels()
  {
    preconditioner.reset();
    multigrid.reset();
    level_matrix.reset();
    coarse.reset();
    transfer.reset();
    const auto &fine_mesh = dynamic_cast<const parallel::distributed::Triangulation<dim> &>(
      fine.get_dof_handler().get_triangulation());
    // Level 0: Q1 on the base mesh; level l > 0: Q2 on the mesh coarsened l − 1 times
    // less than the system's (the last level is the system's mesh).
    const unsigned int n_levels = fine_mesh.n_global_levels() + 1;
    meshes.assign(n_levels, nullptr);
    meshes.back().reset(&fine_mesh, [](const auto *) {});
    for (unsigned int level = n_levels - 1; level > 1; --level)
      {
        auto coarser = std::make_shared<parallel::distributed::Triangulation<dim>>(
          fine_mesh.get_communicator(), fine_mesh.get_mesh_smoothing());
        domain.create_coarsened_copy(*meshes[level], *coarser);
        meshes[level - 1] = coarser;
      }
    meshes[0] = meshes[1];

    dof_handlers.clear();
    constraints.resize(0, n_levels - 1);
    operators.resize(1, n_levels - 1);
    transfers.resize(0, n_levels - 1);
    level_iterates.resize(0, n_levels - 1);
    for (unsigned int level = 0; level < n_levels; ++level)
      {
        AffineConstraints<double> &c = constraints[level];
        if (level + 1 == n_levels)
          {
            dof_handlers.emplace_back(&fine.get_dof_handler(), [](const auto *) {});
            c.copy_from(fine.get_constraints());
          }
        else
          {
            auto dofs = std::make_shared<DoFHandler<dim>>(*meshes[level]);
            dofs->distribute_dofs(level == 0 ? coarse_fe : fe);
            make_velocity_constraints(domain, *dofs, c);
            dof_handlers.push_back(dofs);
          }
        const DoFHandler<dim> &dofs = *dof_handlers.back();
        if (level == 0)
          {
            // Level 0 has no operator to lay out its vectors.
            base_partitioner = std::make_shared<Utilities::MPI::Partitioner>(
              dofs.locally_owned_dofs(), c.get_local_lines(), dofs.get_communicator());
            continue;
          }
        operators[level].reinit(mapping, dofs, c);
        operators[level].initialize_dof_vector(level_iterates[level]);
        if (level == 1)
          transfers[level].reinit_polynomial_transfer(dofs, *dof_handlers[0], c, constraints[0]);
        else
          transfers[level].reinit_geometric_transfer(dofs, *dof_handlers[level - 1], c,
                                                     constraints[level - 1]);
      }
    transfer = std::make_unique<MGTransferGlobalCoarsening<dim, VectorType>>(
      transfers, [this](const unsigned int level, VectorType &v) {
        if (level == 0)
          v.reinit(base_partitioner);
        else
          operators[level].initialize_dof_vector(v);
      });

    operators.back().initialize_dof_vector(in);
    operators.back().initialize_dof_vector(out);
    levels_current = true;
  }

  template <int dim>
  void VelocityMultigrid<dim>::initialize(
    const NewtonSystem &                                     system,
    const TrilinosWrappers::PreconditionAMG::AdditionalData &amg_settings)
  {
    if (!levels_current)
      build_levels();
    const unsigned int n_levels  = operators.max_level() + 1;
    const VectorType * iterate   = fine.get_iterate();
    const double density = fine.get_density(), viscosity = fine.get_viscosity(), c0 = fine.get_c0();
    if (iterate)
      {
        iterate->update_ghost_values();
        transfer->interpolate_to_mg(level_iterates, *iterate);
      }
    MGLevelObject<typename Smoother::AdditionalData> smoother_data(1, n_levels - 1);
    for (unsigned int level = 1; level < n_levels; ++level)
      {
        VelocityOperator<dim> &op = operators[level];
        op.set_coefficients(density, viscosity, c0, iterate ? &level_iterates[level] : nullptr);
        op.set_cut_cell_matrices(level + 1 == n_levels ?
                                   fine.get_operator().get_cut_cell_matrices() :
                                   std::vector<FullMatrix<double>>());
        auto inverse_diagonal = std::make_shared<DiagonalMatrix<VectorType>>();
        op.compute_diagonal(inverse_diagonal->get_vector());
        for (auto &entry : inverse_diagonal->get_vector())
          entry = 1. / entry;
        auto &data                = smoother_data[level];
        data.preconditioner       = inverse_diagonal;
        data.smoothing_range      = 15;
        // Degree 3: about the outer iterations of degree 4 for three quarters of the
        // smoothing work (doc/history.md).
        data.degree               = 3;
        data.eig_cg_n_iterations  = 12;
        data.eigenvalue_algorithm = Smoother::AdditionalData::EigenvalueAlgorithm::power_iteration;
        data.constraints.copy_from(constraints[level]);
      }
    smoother.initialize(operators, smoother_data);

    // Q1 on the base mesh: the Galerkin projection of the Q2 operator there, and ML as the
    // block preconditioner sets it up for the velocity block (but for linear elements),
    // the velocity components as near null space.
    operators[1].compute_matrix(*dof_handlers[0], constraints[0], coarse_matrix);
    TrilinosWrappers::PreconditionAMG::AdditionalData amg = amg_settings;
    amg.higher_order_elements = false;
    DoFTools::extract_constant_modes(*dof_handlers[0], ComponentMask(dim, true),
                                     amg.constant_modes);
    coarse_amg.initialize(coarse_matrix, amg);
    coarse = std::make_unique<ApplyPreconditioner<VectorType, TrilinosWrappers::PreconditionAMG>>(
      coarse_amg);
    level_matrix = std::make_unique<LevelOperators<dim, VectorType>>(operators);
    multigrid =
      std::make_unique<Multigrid<VectorType>>(*level_matrix, *coarse, *transfer, smoother, smoother);
    preconditioner = std::make_unique<
      PreconditionMG<dim, VectorType, MGTransferGlobalCoarsening<dim, VectorType>>>(
      *dof_handlers.back(), *multigrid, *transfer);

    // A's constrained velocity rows hold only their diagonal.
    constrained_rows.clear();
    const IndexSet &owned = operators.back().get_matrix_free().get_vector_partitioner()->locally_owned_range();
    const std::vector<unsigned int> &system_position = fine.get_system_positions();
    const types::global_dof_index    first_owned =
      system.blocks.range[Utilities::MPI::this_mpi_process(system.r_fe.get_mpi_communicator())][0];
    for (unsigned int i = 0; i < system_position.size(); ++i)
      if (constraints.back().is_constrained(owned.nth_index_in_set(i)))
        constrained_rows.emplace_back(
          i, 1. / system.A.diag_element(first_owned + system_position[i]));
  }

  template <int dim>
  void VelocityMultigrid<dim>::vmult(TrilinosWrappers::MPI::Vector &      dst,
                                     const TrilinosWrappers::MPI::Vector &src) const
  {
    const double *                   s               = src.trilinos_vector()[0];
    double *                         d               = dst.trilinos_vector()[0];
    const std::vector<unsigned int> &system_position = fine.get_system_positions();
    for (unsigned int i = 0; i < system_position.size(); ++i)
      in.local_element(i) = s[system_position[i]];
    for (const auto &[i, inverse] : constrained_rows)
      in.local_element(i) = 0;
    preconditioner->vmult(out, in);
    for (unsigned int i = 0; i < system_position.size(); ++i)
      d[system_position[i]] = out.local_element(i);
    for (const auto &[i, inverse] : constrained_rows)
      d[system_position[i]] = inverse * s[system_position[i]];
  }

  template class VelocityMultigrid<2>;
  template class VelocityMultigrid<3>;
} // namespace fdparticle
