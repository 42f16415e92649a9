#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <fdparticle/fem/q2_cell_kernel.h>
#include <fdparticle/fem/velocity_operator.h>

#include <array>

namespace fdparticle
{
  namespace
  {
    template <int dim>
    using Evaluation =
      FEEvaluation<dim, VelocityOperator<dim>::degree, VelocityOperator<dim>::n_points_1d, dim, double>;
  }

  template <int dim>
  void VelocityOperator<dim>::reinit(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler,
                                     const AffineConstraints<double> &constraints,
                                     const unsigned int               level)
  {
    // A cut cell is multiplied by its matrix, cell by cell: each batch must hold one cell.
    // Debian's deal.II is built without SIMD (VectorizedArray<double> has one lane).
    AssertThrow(VectorizedArray<double>::size() == 1,
                ExcMessage("VelocityOperator needs deal.II's VectorizedArray<double> to hold "
                           "one number (a build without SIMD)."));
    typename MatrixFree<dim, double>::AdditionalData data;
    data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags  = update_values | update_gradients | update_JxW_values;
    data.mg_level              = level;
    matrix_free.reinit(mapping, dof_handler, constraints, QGauss<1>(n_points_1d), data);

    // FEEvaluation holds the values component by component, each lexicographic; the cut
    // cells' matrices are ordered (component, FE_Q shape function).
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    const auto &lexicographic = matrix_free.get_shape_info().lexicographic_numbering;
    matrix_row_of_evaluation_index.resize(fe.n_dofs_per_cell());
    const unsigned int n = fe.base_element(0).n_dofs_per_cell();
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      {
        const auto [c, a] = fe.system_to_component_index(lexicographic[i]);
        matrix_row_of_evaluation_index[i] = c * n + a;
      }
    batch_is_cut.assign(matrix_free.n_cell_batches(), false);
    cut_matrices.clear();
    convection = false;

    // The cells are axis-aligned boxes: Q2CellKernel needs 1/h per direction and the volume.
    Evaluation<dim> phi(matrix_free);
    cell_inverse_lengths.resize(matrix_free.n_cell_batches() * dim);
    cell_volumes.resize(matrix_free.n_cell_batches());
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
      {
        phi.reinit(cell);
        const auto inverse_jacobian = phi.inverse_jacobian(0);
        double     volume = 0;
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          volume += phi.JxW(q)[0];
        for (unsigned int d = 0; d < dim; ++d)
          {
            for (unsigned int e = 0; e < dim; ++e)
              AssertThrow(e == d || inverse_jacobian[d][e][0] == 0,
                          ExcMessage("VelocityOperator needs axis-aligned box cells."));
            cell_inverse_lengths[cell * dim + d] = inverse_jacobian[d][d][0];
          }
        cell_volumes[cell] = volume;
      }
  }

  template <int dim>
  void VelocityOperator<dim>::set_coefficients(const double density, const double viscosity,
                                               const double c0, const VectorType *iterate)
  {
    this->density   = density;
    this->viscosity = viscosity;
    this->c0        = c0;
    convection      = (iterate != nullptr);
    if (!convection)
      {
        iterate_values.clear();
        iterate_gradients.clear();
        return;
      }
    iterate->update_ghost_values();
    Evaluation<dim>    phi(matrix_free);
    const unsigned int nq = phi.n_q_points;
    iterate_values.resize(matrix_free.n_cell_batches() * nq);
    iterate_gradients.resize(matrix_free.n_cell_batches() * nq);
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
      {
        phi.reinit(cell);
        phi.read_dof_values_plain(*iterate);
        phi.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
        for (unsigned int q = 0; q < nq; ++q)
          {
            iterate_values[cell * nq + q]    = phi.get_value(q);
            iterate_gradients[cell * nq + q] = phi.get_gradient(q);
          }
      }
  }

  template <int dim>
  void VelocityOperator<dim>::set_cut_cell_matrices(std::vector<FullMatrix<double>> matrices)
  {
    cut_matrices = std::move(matrices);
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
      {
        const unsigned int index = matrix_free.get_cell_iterator(cell, 0)->active_cell_index();
        batch_is_cut[cell] = index < cut_matrices.size() && cut_matrices[index].m() > 0;
        Assert(!batch_is_cut[cell] ||
                 cut_matrices[index].m() == matrix_row_of_evaluation_index.size(),
               ExcDimensionMismatch(cut_matrices[index].m(), matrix_row_of_evaluation_index.size()));
      }
  }

  template <int dim>
  void VelocityOperator<dim>::load_cell_data(const unsigned int cell, const unsigned int l,
                                             double *lengths, double *volumes, double *w,
                                             double *grad_w) const
  {
    using Kernel             = Q2CellKernel<dim>;
    constexpr unsigned int L = Kernel::lanes, nq = Kernel::n_points;
    for (unsigned int d = 0; d < dim; ++d)
      lengths[d * L + l] = cell_inverse_lengths[cell * dim + d];
    volumes[l] = cell_volumes[cell];
    if (convection)
      for (unsigned int q = 0; q < nq; ++q)
        for (unsigned int c = 0; c < dim; ++c)
          {
            w[(q * dim + c) * L + l] = iterate_values[cell * nq + q][c][0];
            for (unsigned int e = 0; e < dim; ++e)
              grad_w[((q * dim + c) * dim + e) * L + l] = iterate_gradients[cell * nq + q][c][e][0];
          }
  }

  template <int dim>
  void VelocityOperator<dim>::local_apply(const MatrixFree<dim, double> &data, VectorType &dst,
                                          const VectorType &                           src,
                                          const std::pair<unsigned int, unsigned int> &cell_range) const
  {
    using Kernel           = Q2CellKernel<dim>;
    constexpr unsigned int L = Kernel::lanes;
    Evaluation<dim>        phi(data);
    const unsigned int     nq = phi.n_q_points, n = phi.dofs_per_cell;
    Assert(n == dim * Kernel::n_dofs && nq == Kernel::n_points, ExcInternalError());
    Vector<double>      local_src(n), local_dst(n);
    std::vector<double> in(n * L), out(n * L), lengths(dim * L), volumes(L),
      w(convection ? nq * dim * L : 0), grad_w(convection ? nq * dim * dim * L : 0);
    std::array<unsigned int, L> batch;
    unsigned int                n_batch = 0;

    // The cells gathered so far through the kernel, lanes beyond them empty.
    const auto flush = [&]() {
      if (n_batch == 0)
        return;
      for (unsigned int l = n_batch; l < L; ++l)
        {
          for (unsigned int i = 0; i < n; ++i)
            in[i * L + l] = 0;
          for (unsigned int d = 0; d < dim; ++d)
            lengths[d * L + l] = 1;
          volumes[l] = 0;
        }
      Kernel::apply(in.data(), out.data(), lengths.data(), volumes.data(),
                    convection ? w.data() : nullptr, convection ? grad_w.data() : nullptr,
                    density * c0, density, viscosity);
      for (unsigned int l = 0; l < n_batch; ++l)
        {
          phi.reinit(batch[l]);
          for (unsigned int i = 0; i < n; ++i)
            phi.begin_dof_values()[i] = out[i * L + l];
          phi.distribute_local_to_global(dst);
        }
      n_batch = 0;
    };

    for (unsigned int cell = cell_range.first; cell < cell_range.second; ++cell)
      {
        phi.reinit(cell);
        phi.read_dof_values(src);
        if (batch_is_cut[cell])
          {
            // The cell's matrix on the values after the constraints, as FEEvaluation
            // would integrate them.
            for (unsigned int i = 0; i < n; ++i)
              local_src[matrix_row_of_evaluation_index[i]] = phi.begin_dof_values()[i][0];
            cut_matrices[data.get_cell_iterator(cell, 0)->active_cell_index()].vmult(local_dst,
                                                                                     local_src);
            for (unsigned int i = 0; i < n; ++i)
              phi.begin_dof_values()[i] = local_dst[matrix_row_of_evaluation_index[i]];
            phi.distribute_local_to_global(dst);
            continue;
          }
        const unsigned int l = n_batch;
        for (unsigned int i = 0; i < n; ++i)
          in[i * L + l] = phi.begin_dof_values()[i][0];
        load_cell_data(cell, l, lengths.data(), volumes.data(), w.data(), grad_w.data());
        batch[n_batch++] = cell;
        if (n_batch == L)
          flush();
      }
    flush();
  }

  template <int dim>
  void VelocityOperator<dim>::vmult(VectorType &dst, const VectorType &src) const
  {
    matrix_free.cell_loop(&VelocityOperator::local_apply, this, dst, src, true);
    for (const unsigned int i : matrix_free.get_constrained_dofs())
      dst.local_element(i) = src.local_element(i);
  }

  template <int dim>
  void VelocityOperator<dim>::compute_diagonal(VectorType &diagonal) const
  {
    matrix_free.initialize_dof_vector(diagonal);
    Evaluation<dim>    phi(matrix_free);
    const unsigned int nq = phi.n_q_points, n = phi.dofs_per_cell, n_scalar = n / dim;
    // The scalar Q2 functions and their reference gradients at the Gauss points, from
    // one cell's evaluation of unit vectors (the same on every axis-aligned cell up to 1/h).
    std::vector<double>         value(n_scalar * nq);
    std::vector<Tensor<1, dim>> reference_gradient(n_scalar * nq);
    if (matrix_free.n_cell_batches() > 0) // a rank may own no cell of a coarse level
      phi.reinit(0);
    for (unsigned int i = 0; i < n_scalar && matrix_free.n_cell_batches() > 0; ++i)
      {
        for (unsigned int k = 0; k < n; ++k)
          phi.begin_dof_values()[k] = (k == i ? 1.0 : 0.0);
        phi.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
        for (unsigned int q = 0; q < nq; ++q)
          {
            value[i * nq + q] = phi.get_value(q)[0][0];
            for (unsigned int d = 0; d < dim; ++d)
              reference_gradient[i * nq + q][d] =
                phi.get_gradient(q)[0][d][0] / cell_inverse_lengths[d];
          }
      }
    Vector<double> local(n);
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
      {
        phi.reinit(cell);
        if (batch_is_cut[cell])
          {
            const FullMatrix<double> &m =
              cut_matrices[matrix_free.get_cell_iterator(cell, 0)->active_cell_index()];
            for (unsigned int k = 0; k < n; ++k)
              phi.begin_dof_values()[k] =
                m(matrix_row_of_evaluation_index[k], matrix_row_of_evaluation_index[k]);
            phi.distribute_local_to_global(diagonal);
            continue;
          }
        for (unsigned int c = 0; c < dim; ++c)
          for (unsigned int i = 0; i < n_scalar; ++i)
            {
              double sum = 0;
              for (unsigned int q = 0; q < nq; ++q)
                {
                  const double JxW = phi.JxW(q)[0], N = value[i * nq + q];
                  Tensor<1, dim> dN;
                  for (unsigned int d = 0; d < dim; ++d)
                    dN[d] = reference_gradient[i * nq + q][d] * cell_inverse_lengths[cell * dim + d];
                  double a = density * c0 * N * N + viscosity * (dN * dN + dN[c] * dN[c]);
                  if (convection)
                    {
                      double w_grad = 0;
                      for (unsigned int d = 0; d < dim; ++d)
                        w_grad += iterate_values[cell * nq + q][d][0] * dN[d];
                      a += density * N * (w_grad + iterate_gradients[cell * nq + q][c][c][0] * N);
                    }
                  sum += a * JxW;
                }
              phi.begin_dof_values()[c * n_scalar + i] = sum;
            }
        phi.distribute_local_to_global(diagonal);
      }
    diagonal.compress(VectorOperation::add);
    for (const unsigned int i : matrix_free.get_constrained_dofs())
      diagonal.local_element(i) = 1;
    diagonal_entries = diagonal;
  }

  template <int dim>
  void VelocityOperator<dim>::compute_matrix(const DoFHandler<dim> &          dof_handler,
                                             const AffineConstraints<double> &constraints,
                                             TrilinosWrappers::SparseMatrix & matrix) const
  {
    const DoFHandler<dim> &own_dofs = matrix_free.get_dof_handler();
    AssertThrow(matrix_free.get_mg_level() == numbers::invalid_unsigned_int &&
                  &dof_handler.get_triangulation() == &own_dofs.get_triangulation(),
                ExcMessage("VelocityOperator::compute_matrix works on the active cells of "
                           "the operator's own mesh."));
    const MPI_Comm comm = dof_handler.get_communicator();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    TrilinosWrappers::SparsityPattern sparsity(dof_handler.locally_owned_dofs(),
                                               dof_handler.locally_owned_dofs(), relevant, comm);
    DoFTools::make_sparsity_pattern(dof_handler, sparsity, constraints, false,
                                    Utilities::MPI::this_mpi_process(comm));
    sparsity.compress();
    matrix.reinit(sparsity);

    // A coarser element's cell matrix is Eᵀ A_K E, E its interpolation into the
    // operator's element (a Galerkin projection: the coarser space lies in the finer).
    const FiniteElement<dim> &coarse_fe = dof_handler.get_fe();
    const bool                project   = coarse_fe != own_dofs.get_fe();
    FullMatrix<double>        embedding;
    if (project)
      {
        embedding.reinit(own_dofs.get_fe().n_dofs_per_cell(), coarse_fe.n_dofs_per_cell());
        FETools::get_interpolation_matrix(coarse_fe, own_dofs.get_fe(), embedding);
      }
    const unsigned int n_coarse = coarse_fe.n_dofs_per_cell();
    FullMatrix<double> projected(n_coarse, n_coarse);
    std::vector<types::global_dof_index> coarse_dofs(n_coarse);

    const unsigned int     n = own_dofs.get_fe().n_dofs_per_cell();
    const auto &lexicographic = matrix_free.get_shape_info().lexicographic_numbering;
    // E's rows in FEEvaluation's order: a cell that is not cut projects as Eᵀ (A_K E),
    // the operator applied to E's columns, without A_K.
    FullMatrix<double> embedding_evaluated(n, n_coarse), applied;
    for (unsigned int i = 0; i < n && project; ++i)
      for (unsigned int a = 0; a < n_coarse; ++a)
        embedding_evaluated(i, a) = embedding(lexicographic[i], a);
    FullMatrix<double>                   local(n, n), cell_matrix_of_batch(n, n);
    std::vector<types::global_dof_index> dofs(n);
    for (unsigned int cell = 0; cell < matrix_free.n_cell_batches(); ++cell)
      {
        const auto cell_iterator = matrix_free.get_cell_iterator(cell, 0);
        if (project && !batch_is_cut[cell])
          {
            apply_to_columns(cell, embedding_evaluated, applied);
            embedding_evaluated.Tmmult(projected, applied);
          }
        else
          {
            cell_matrix(cell, cell_matrix_of_batch);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                local(lexicographic[i], lexicographic[j]) =
                  cell_matrix_of_batch(matrix_row_of_evaluation_index[i],
                                       matrix_row_of_evaluation_index[j]);
            if (project)
              {
                projected = 0;
                projected.triple_product(local, embedding, embedding, true, false);
              }
          }
        if (project)
          {
            typename DoFHandler<dim>::active_cell_iterator(&dof_handler.get_triangulation(),
                                                           cell_iterator->level(),
                                                           cell_iterator->index(), &dof_handler)
              ->get_dof_indices(coarse_dofs);
            constraints.distribute_local_to_global(projected, coarse_dofs, matrix);
          }
        else
          {
            cell_iterator->get_dof_indices(dofs);
            constraints.distribute_local_to_global(local, dofs, matrix);
          }
      }
    matrix.compress(VectorOperation::add);
  }

  template <int dim>
  void VelocityOperator<dim>::cell_matrix(const unsigned int cell, FullMatrix<double> &matrix) const
  {
    const unsigned int n = matrix_row_of_evaluation_index.size();
    matrix.reinit(n, n);
    if (batch_is_cut[cell])
      {
        matrix = cut_matrices[matrix_free.get_cell_iterator(cell, 0)->active_cell_index()];
        return;
      }
    // Column j is the operator applied to the unit vector e_j.
    FullMatrix<double> unit(n, n), columns;
    for (unsigned int i = 0; i < n; ++i)
      unit(i, i) = 1;
    apply_to_columns(cell, unit, columns);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        matrix(matrix_row_of_evaluation_index[i], matrix_row_of_evaluation_index[j]) =
          columns(i, j);
  }

  template <int dim>
  void VelocityOperator<dim>::apply_to_columns(const unsigned int        cell,
                                               const FullMatrix<double> &in_columns,
                                               FullMatrix<double> &      out_columns) const
  {
    Assert(!batch_is_cut[cell], ExcInternalError());
    // The cell fills all lanes of the kernel, one column in each.
    using Kernel             = Q2CellKernel<dim>;
    constexpr unsigned int L = Kernel::lanes, nq = Kernel::n_points;
    const unsigned int     n = in_columns.m(), m = in_columns.n();
    out_columns.reinit(n, m);
    std::vector<double> in(n * L), out(n * L), lengths(dim * L), volumes(L),
      w(convection ? nq * dim * L : 0), grad_w(convection ? nq * dim * dim * L : 0);
    for (unsigned int l = 0; l < L; ++l)
      load_cell_data(cell, l, lengths.data(), volumes.data(), w.data(), grad_w.data());
    for (unsigned int first = 0; first < m; first += L)
      {
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int l = 0; l < L; ++l)
            in[i * L + l] = (first + l < m ? in_columns(i, first + l) : 0.0);
        Kernel::apply(in.data(), out.data(), lengths.data(), volumes.data(),
                      convection ? w.data() : nullptr, convection ? grad_w.data() : nullptr,
                      density * c0, density, viscosity);
        for (unsigned int l = 0; l < L && first + l < m; ++l)
          for (unsigned int i = 0; i < n; ++i)
            out_columns(i, first + l) = out[i * L + l];
      }
  }

  template <int dim>
  double VelocityOperator<dim>::el(const types::global_dof_index i,
                                   const types::global_dof_index j) const
  {
    AssertThrow(i == j && diagonal_entries.size() == m(),
                ExcMessage("VelocityOperator::el gives the diagonal after compute_diagonal()."));
    return diagonal_entries(i);
  }

  template <int dim>
  void VelocityOperator<dim>::Tvmult(VectorType &, const VectorType &) const
  {
    AssertThrow(false, ExcMessage("VelocityOperator has no transpose product."));
  }

  template <int dim>
  double VelocityOperator<dim>::cut_cell_fraction() const
  {
    const MPI_Comm comm = matrix_free.get_vector_partitioner()->get_mpi_communicator();
    double         counts[2] = {0, double(matrix_free.n_physical_cells())};
    for (const bool cut : batch_is_cut)
      counts[0] += cut;
    Utilities::MPI::sum(ArrayView<const double>(counts, 2), comm, ArrayView<double>(counts, 2));
    return counts[1] > 0 ? counts[0] / counts[1] : 0.0;
  }

  template <int dim>
  std::size_t VelocityOperator<dim>::memory_consumption() const
  {
    std::size_t bytes = matrix_free.memory_consumption() + iterate_values.memory_consumption() +
                        iterate_gradients.memory_consumption();
    for (const auto &m : cut_matrices)
      bytes += m.memory_consumption();
    return Utilities::MPI::sum(bytes, matrix_free.get_vector_partitioner()->get_mpi_communicator());
  }

  template class VelocityOperator<2>;
  template class VelocityOperator<3>;
} // namespace fdparticle
