#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/fem/assembly/interior_pressure.h>

namespace fdparticle
{
  template <int dim>
  void InteriorPressure<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    prm.declare_entry("Interior pressure penalty", "1e-3", Patterns::Anything(),
                      "delta >= 0 in the term -(delta/mu)*int((p - p_hydrostatic) q) over cells "
                      "inside a particle, where p and lambda are otherwise determined only "
                      "together: it picks the hydrostatic pressure. It switches on as a cell "
                      "becomes inside, so keep it small; 1e-3 avoids velocity jumps yet outweighs "
                      "round-off (doc/method.md §4).");
    prm.leave_subsection();
  }

  template <int dim>
  void InteriorPressure<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    penalty = ParameterTools::get_non_negative(prm, "Interior pressure penalty",
                                               "Multiplier/Interior pressure penalty");
    prm.leave_subsection();
  }

  template <int dim>
  void InteriorPressure<dim>::assemble_point(const AssemblyScratch<dim> &s,
                                             AssemblyCopy<dim> &         copy) const
  {
    if (s.kind != CellKind::inside || !enabled())
      return;
    // The sign makes it the stabilising −C block of the symmetric saddle point
    // [[A, Bᵀ], [B, −C]] (B = −(q, ∇·v)); where the mode is not exact the other sign
    // would destabilise.
    const double eps = -penalty / fluid.viscosity * s.JxW;
    const double p_static = fluid.hydrostatic_pressure(s.x, reference_point);
    for (const unsigned int i : s.pressure_dofs)
      {
        copy.rhs(i) += eps * (s.p[s.q] - p_static) * s.N[i];
        if (s.with_matrix)
          for (const unsigned int j : s.pressure_dofs)
            copy.matrix(i, j) += eps * s.N[i] * s.N[j];
      }
  }

  template class InteriorPressure<2>;
  template class InteriorPressure<3>;
} // namespace fdparticle
