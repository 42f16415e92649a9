// The velocity block assembled the classical way, for the benchmarks that hold
// VelocityOperator against it (velocity_operator.cc, velocity_multigrid.cc): the same
// bilinear form by FEValues with the same Gauss rule, into an Epetra matrix.
#ifndef fdparticle_benchmarks_velocity_matrix_h
#define fdparticle_benchmarks_velocity_matrix_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <vector>

/// Component by component (φ = N_a e_c): ρ c0 δ_ij N_a N_b + ρ N_a (δ_ij w·∇N_b + ∂_j w_i N_b)
/// + μ (δ_ij ∇N_a·∇N_b + ∂_j N_a ∂_i N_b), with the iterate w (ghosted).
template <int dim, typename VectorType>
void assemble_velocity_matrix(const dealii::Mapping<dim> &               mapping,
                              const dealii::DoFHandler<dim> &            dof_handler,
                              const dealii::AffineConstraints<double> &  constraints,
                              const VectorType &                         w,
                              const double density, const double viscosity, const double c0,
                              const unsigned int                         n_points_1d,
                              dealii::TrilinosWrappers::SparseMatrix &   matrix)
{
  using namespace dealii;
  const MPI_Comm comm = dof_handler.get_communicator();
  IndexSet       relevant;
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
  TrilinosWrappers::SparsityPattern sparsity(dof_handler.locally_owned_dofs(),
                                             dof_handler.locally_owned_dofs(), relevant, comm);
  DoFTools::make_sparsity_pattern(dof_handler, sparsity, constraints, false,
                                  Utilities::MPI::this_mpi_process(comm));
  sparsity.compress();
  matrix.reinit(sparsity);

  const FiniteElement<dim> &fe = dof_handler.get_fe();
  const QGauss<dim>         quadrature(n_points_1d);
  FEValues<dim> fv(mapping, fe, quadrature, update_values | update_gradients | update_JxW_values);
  const unsigned int nd = fe.n_dofs_per_cell(), nq = quadrature.size();
  FullMatrix<double> local(nd, nd);
  std::vector<types::global_dof_index> dofs(nd);
  std::vector<Tensor<1, dim>>          w_q(nq);
  std::vector<Tensor<2, dim>>          grad_w_q(nq);
  const FEValuesExtractors::Vector     u(0);
  std::vector<unsigned int>            component(nd);
  for (unsigned int i = 0; i < nd; ++i)
    component[i] = fe.system_to_component_index(i).first;
  std::vector<double>         N(nd), w_grad_N(nd);
  std::vector<Tensor<1, dim>> dN(nd);
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fv.reinit(cell);
        fv[u].get_function_values(w, w_q);
        fv[u].get_function_gradients(w, grad_w_q);
        local = 0;
        for (unsigned int q = 0; q < nq; ++q)
          {
            const double JxW = fv.JxW(q);
            for (unsigned int i = 0; i < nd; ++i)
              {
                N[i]        = fv.shape_value_component(i, q, component[i]);
                dN[i]       = fv.shape_grad_component(i, q, component[i]);
                w_grad_N[i] = w_q[q] * dN[i];
              }
            for (unsigned int i = 0; i < nd; ++i)
              for (unsigned int j = 0; j < nd; ++j)
                {
                  const unsigned int ci = component[i], cj = component[j];
                  double value = density * N[i] * grad_w_q[q][ci][cj] * N[j] +
                                 viscosity * dN[i][cj] * dN[j][ci];
                  if (ci == cj)
                    value += density * c0 * N[i] * N[j] + density * N[i] * w_grad_N[j] +
                             viscosity * (dN[i] * dN[j]);
                  local(i, j) += value * JxW;
                }
          }
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(local, dofs, matrix);
      }
  matrix.compress(VectorOperation::add);
}

#endif
