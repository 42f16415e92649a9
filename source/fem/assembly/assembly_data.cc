#include <fdparticle/fem/assembly/assembly_data.h>

namespace fdparticle
{
  template <int dim>
  AssemblyScratch<dim>::AssemblyScratch(const FESystem<dim> &fe, const std::array<double, 3> &c,
                                        const double alpha, const double viscous_pairing,
                                        const bool with_matrix)
    : c(c)
    , alpha(alpha)
    , viscous_pairing(viscous_pairing)
    , with_matrix(with_matrix)
    , component(fe.n_dofs_per_cell())
    , scalar_function(fe.n_dofs_per_cell())
    , velocity_shapes(fe, Introspection<dim>::Field::velocity)
    , multiplier_shapes(fe, Introspection<dim>::Field::multiplier)
    , N(fe.n_dofs_per_cell())
    , dN(fe.n_dofs_per_cell())
  {
    // Every shape function is primitive: one field, one vector component.
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      {
        const unsigned int c_i = fe.system_to_component_index(i).first;
        component[i] = c_i % dim;
        scalar_function[i] = fe.system_to_base_index(i).second;
        switch (Introspection<dim>::field(c_i))
          {
            case Introspection<dim>::Field::velocity:
              velocity_dofs.push_back(i);
              break;
            case Introspection<dim>::Field::multiplier:
              multiplier_dofs.push_back(i);
              break;
            case Introspection<dim>::Field::pressure:
              pressure_dofs.push_back(i);
              break;
          }
      }
  }

  template <int dim>
  void AssemblyScratch<dim>::reinit(const FEValues<dim> &scalar, const FEValues<dim> &pressure,
                                    const Vector<double> &solution, const Vector<double> &history)
  {
    Assert(scalar.get_fe().n_components() == 1 && pressure.get_fe().n_components() == 1,
           ExcMessage("AssemblyScratch::reinit takes the FEValues of scalar elements."));
    velocity_shapes.reinit(scalar);
    multiplier_shapes.reinit(scalar);
    const unsigned int nq = scalar.n_quadrature_points, n_p = pressure_dofs.size();
    pressure_values.resize(nq * n_p);
    pressure_gradients.resize(nq * n_p);
    for (unsigned int q = 0; q < nq; ++q)
      for (unsigned int j = 0; j < n_p; ++j)
        {
          pressure_values[q * n_p + j] = pressure.shape_value(scalar_function[pressure_dofs[j]], q);
          pressure_gradients[q * n_p + j] = pressure.shape_grad(scalar_function[pressure_dofs[j]], q);
        }

    // u, ∇u, the history's u, λ, ∇λ and p at the points: Σ coefficient × shape function.
    const CellShapes<dim> &V = velocity_shapes, &L = multiplier_shapes;
    u.assign(nq, Tensor<1, dim>());
    u_history.assign(nq, Tensor<1, dim>());
    lambda.assign(nq, Tensor<1, dim>());
    grad_u.assign(nq, Tensor<2, dim>());
    grad_lambda.assign(nq, Tensor<2, dim>());
    p.assign(nq, 0.0);
    for (unsigned int q = 0; q < nq; ++q)
      {
        const double *x = V.row(q);
        for (unsigned int comp = 0; comp < dim; ++comp)
          for (unsigned int s = 0; s < V.n_functions(); ++s)
            {
              const double u_s = solution[V.dof(comp, s)], l_s = solution[L.dof(comp, s)];
              u[q][comp] += u_s * x[s];
              u_history[q][comp] += history[V.dof(comp, s)] * x[s];
              lambda[q][comp] += l_s * x[s];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  grad_u[q][comp][d] += u_s * x[V.column(1 + d, s)];
                  grad_lambda[q][comp][d] += l_s * x[V.column(1 + d, s)];
                }
            }
        for (unsigned int j = 0; j < n_p; ++j)
          p[q] += solution[pressure_dofs[j]] * pressure_values[q * n_p + j];
      }
  }

  template <int dim>
  void AssemblyScratch<dim>::reinit_point(const unsigned int q)
  {
    // u and λ have the same scalar functions (velocity_shapes' row serves both).
    const double *x = velocity_shapes.row(q);
    for (const auto *dofs : {&velocity_dofs, &multiplier_dofs})
      for (const unsigned int i : *dofs)
        {
          const unsigned int s = scalar_function[i];
          N[i] = x[velocity_shapes.column(0, s)];
          for (unsigned int d = 0; d < dim; ++d)
            dN[i][d] = x[velocity_shapes.column(1 + d, s)];
        }
    const unsigned int n_p = pressure_dofs.size();
    for (unsigned int j = 0; j < n_p; ++j)
      {
        N[pressure_dofs[j]] = pressure_values[q * n_p + j];
        dN[pressure_dofs[j]] = pressure_gradients[q * n_p + j];
      }
  }

  template struct AssemblyScratch<2>;
  template struct AssemblyScratch<3>;
} // namespace fdparticle
