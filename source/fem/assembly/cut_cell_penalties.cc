#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/fem/assembly/cut_cell_penalties.h>

namespace fdparticle
{
  template <int dim>
  void CutCellPenalties<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    prm.declare_entry("Fluid penalty", "0.01", Patterns::Anything(),
                      "s >= 0 in the term s*alpha^2/(alpha + mu/R^2)*int(lambda.eta) over the fluid part of cut "
                      "cells (the seed's weak lambda = 0 in the fluid, 3.18a). It keeps the "
                      "rows of multipliers that barely meet a particle well posed.");
    prm.declare_entry("Strain penalty", "0.15", Patterns::Anything(),
                      "s_e >= 0 in the term s_e*mu*int(2 eps(lambda):eps(eta)) over the fluid "
                      "part of cut cells. It softens the rigidity constraint of multipliers "
                      "that lie mostly in the fluid (0: the cut cells lock, the particle acts "
                      "O(h) too large) without touching the rigid modes of lambda, which "
                      "carry force and torque (doc/method.md, 'Strain penalty').");
    prm.declare_entry("Penalty ramp", "0.2", Patterns::Anything(),
                      "theta_0 >= 0: in a cut cell whose particle fraction theta is below "
                      "theta_0, both penalties above are scaled by theta/theta_0, so they "
                      "switch on continuously as a cell starts to be cut (smoother particle "
                      "velocities, doc/smoothness.md). 0: off, the penalties switch on at "
                      "full strength (then Strain penalty = 0.05 was the accurate choice, "
                      "doc/method.md §4).");
    prm.leave_subsection();
  }

  template <int dim>
  void CutCellPenalties<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    const auto get = [&](const std::string &name) {
      return ParameterTools::get_non_negative(prm, name, "Multiplier/" + name);
    };
    fluid_penalty = get("Fluid penalty");
    strain_penalty = get("Strain penalty");
    penalty_ramp = get("Penalty ramp");
    prm.leave_subsection();
  }

  template <int dim>
  void CutCellPenalties<dim>::assemble_point(const AssemblyScratch<dim> &s,
                                             AssemblyCopy<dim> &         copy) const
  {
    if (s.particle >= 0 || s.kind != CellKind::cut || !(fluid_penalty > 0 || strain_penalty > 0))
      return;
    const double                     mu = fluid.viscosity, alpha = s.alpha;
    const auto &                     N = s.N;
    const auto &                     dN = s.dN;
    const std::vector<unsigned int> &comp = s.component;
    const Tensor<1, dim> &           l = s.lambda[s.q];
    const Tensor<2, dim> &           gl = s.grad_lambda[s.q];
    // Optional ramp with the cell's particle fraction θ (Penalty ramp): without it the
    // penalties switch on at full strength when a cell starts to be cut.
    const double ramp = (penalty_ramp > 0 ? std::min(1.0, s.particle_fraction / penalty_ramp) : 1.0);
    // Weak λ = 0 on the fluid part of a cut cell (seed 3.18a), weighted by α²/(α + μ/R²).
    // The rigid mode of λ carries the particle's force through α∫λ, so it grows like 1/α;
    // a weight that does not vanish like α² for α ≪ μ/R² lets the particle leak in
    // proportion to Δt (weight α + μ/R²: settling 10x too fast at Δt = 1). For α ≫ μ/R²
    // the weight is sα, a fixed fraction of the pairing (doc/method.md, "Fluid penalty").
    const double R = particles[s.cut_particle].radius;
    const double fluid_weight = ramp * fluid_penalty * alpha * alpha / (alpha + mu / (R * R)) * s.JxW;
    // Strain penalty s_e μ (2ε(λ), ε(η)): softens the rigidity of λ DoFs that live mostly
    // in the fluid (without it the cut cells lock, the particle looks O(h) larger) and is
    // blind to λ's rigid modes, ε(V + θ × r) = 0. Only in cells that own particle points:
    // elsewhere those rigid modes would be held by the vanishing α² term alone
    // (doc/method.md §4, "Strain penalty").
    const double strain_weight = (s.has_particle ? ramp * strain_penalty * mu * s.JxW : 0.0);
    for (const unsigned int a : s.multiplier_dofs)
      {
        const unsigned int ca = comp[a];
        copy.rhs(a) += fluid_weight * l[ca] * N[a];
        if (strain_weight != 0)
          for (unsigned int j = 0; j < dim; ++j)
            copy.rhs(a) += strain_weight * (gl[ca][j] + gl[j][ca]) * dN[a][j];
        if (s.with_matrix)
          for (const unsigned int b : s.multiplier_dofs)
            {
              const unsigned int cb = comp[b];
              double value = strain_weight * dN[a][cb] * dN[b][ca];
              if (ca == cb)
                value += fluid_weight * N[a] * N[b] + strain_weight * (dN[a] * dN[b]);
              copy.matrix(a, b) += value;
            }
      }
  }

  template class CutCellPenalties<2>;
  template class CutCellPenalties<3>;
} // namespace fdparticle
