#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/fem/assembly/cut_cell_penalties.h>

#include <cmath>

namespace fdparticle
{
  template <int dim>
  void CutCellPenalties<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    prm.declare_entry("Fluid penalty", "0.004", Patterns::Anything(),
                      "s >= 0 in the term s*kappa^2/(alpha + mu/R^2)*int(lambda.eta) over the "
                      "fluid part of cut cells, kappa the pairing weight (Pairing viscous "
                      "weight); the seed's weak lambda = 0 in the fluid. It keeps the rows of "
                      "multipliers that barely meet a particle well posed (doc/method.md §4).");
    prm.declare_entry("Strain penalty", "0.15", Patterns::Anything(),
                      "s_e >= 0 in the term s_e*mu*int(2 eps(lambda):eps(eta)) over the fluid "
                      "part of cut cells. It softens the rigidity constraint of multipliers "
                      "mostly in the fluid without touching the rigid modes that carry force and "
                      "torque; 0: the cut cells lock and the particle acts O(h) too large "
                      "(doc/method.md §4).");
    prm.declare_entry("Penalty ramp", "0.2", Patterns::Anything(),
                      "theta_0 >= 0: in a cut cell whose particle fraction theta is below "
                      "theta_0, both penalties above are scaled by theta/theta_0, so they switch "
                      "on continuously as a cell starts to be cut (smoother particle velocities, "
                      "doc/smoothness.md). 0: full strength at once (doc/method.md §4).");
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
    const auto &                     N = s.N;
    const auto &                     dN = s.dN;
    const std::vector<unsigned int> &comp = s.component;
    const Tensor<1, dim> &           l = s.lambda[s.q];
    const Tensor<2, dim> &           gl = s.grad_lambda[s.q];
    const auto [fluid_weight, strain_weight] = weights(s, s.cut_particle, s.JxW);
    for (const unsigned int a : s.multiplier_dofs)
      {
        const unsigned int ca = comp[a];
        copy.rhs(a) += fluid_weight * l[ca] * N[a];
        if (strain_weight != 0)
          for (unsigned int j = 0; j < dim; ++j)
            copy.rhs(a) += strain_weight * (gl[ca][j] + gl[j][ca]) * dN[a][j];
      }
  }

  template <int dim>
  std::pair<double, double> CutCellPenalties<dim>::weights(const AssemblyScratch<dim> &s,
                                                           const unsigned int nearest_surface,
                                                           const double       JxW) const
  {
    const double mu = fluid.viscosity;
    // Optional ramp with the cell's particle fraction θ (Penalty ramp): without it the
    // penalties switch on at full strength when a cell starts to be cut.
    const double ramp = (penalty_ramp > 0 ? std::min(1.0, s.particle_fraction / penalty_ramp) : 1.0);
    // Weak λ = 0 on the fluid part of a cut cell (seed 3.18a), weighted by κ²/(α + μ/R²).
    // The rigid mode of λ carries the particle's force through κ∫λ, so it grows like 1/κ;
    // the weight must scale like κ² where κ ≪ μ/R² (only with the seed's κ = α, c = 0)
    // or the particle leaks in proportion to Δt (as it does with the weight α + μ/R²).
    // For α ≫ μ/R² it is sκ, a fixed fraction of the pairing
    // (doc/method.md §4, "Fluid penalty" and "Pairing viscous weight").
    const double R = particles[nearest_surface].bounding_radius();
    const double kappa = s.pairing_weight(R);
    const double fluid_weight = ramp * fluid_penalty * kappa * kappa / (s.alpha + mu / (R * R)) * JxW;
    // Strain penalty s_e μ (2ε(λ), ε(η)): softens the rigidity of λ DoFs that live mostly
    // in the fluid (without it the cut cells lock, the particle looks O(h) larger) and is
    // blind to λ's rigid modes, ε(V + θ × r) = 0. Only in cells that own particle points:
    // elsewhere those rigid modes would be held by the vanishing α² term alone
    // (doc/method.md §4, "Strain penalty").
    const double strain_weight = (s.has_particle ? ramp * strain_penalty * mu * JxW : 0.0);
    return {fluid_weight, strain_weight};
  }

  template <int dim>
  void CutCellPenalties<dim>::assemble_cell_matrix(const AssemblyScratch<dim> &s,
                                                   AssemblyCopy<dim> &         copy) const
  {
    if (s.kind != CellKind::cut || !(fluid_penalty > 0 || strain_penalty > 0))
      return;
    // Over the fluid points: the mass matrix under the fluid weight and every
    // ∂_d ψ_s ∂_e ψ_t under the strain weight, as Gram matrices of the rows scaled by the
    // weights' roots.
    const CellShapes<dim> &L  = s.multiplier_shapes;
    const unsigned int     nf = L.n_functions(), nc = L.n_columns();
    std::vector<double> &  weighted = copy.weighted;
    weighted.clear();
    for (unsigned int q = 0; q < L.n_points(); ++q)
      if (s.owners[q] < 0)
        {
          const auto [fluid_weight, strain_weight] = weights(s, s.nearest_surfaces[q], s.weights[q]);
          const double root_fluid = std::sqrt(fluid_weight), root_strain = std::sqrt(strain_weight);
          for (unsigned int k = 0; k < nc; ++k)
            weighted.push_back((k < nf ? root_fluid : root_strain) * L.row(q)[k]);
        }
    const unsigned int  n_fluid = weighted.size() / nc;
    std::vector<double> mass(nf * nf, 0.0), derivatives(dim * nf * dim * nf, 0.0);
    add_gram(n_fluid, nf, weighted.data(), nc, mass.data());
    add_gram(n_fluid, dim * nf, weighted.data() + L.column(1, 0), nc, derivatives.data());
    const auto D = [&](const unsigned int d, const unsigned int a, const unsigned int e,
                       const unsigned int b) { return derivatives[(d * nf + a) * dim * nf + e * nf + b]; };
    // s κ²/(α + μ/R²) δ ψ_a ψ_b + s_e μ (δ ∇ψ_a·∇ψ_b + ∂_cb ψ_a ∂_ca ψ_b)
    for (unsigned int ca = 0; ca < dim; ++ca)
      for (unsigned int cb = 0; cb < dim; ++cb)
        for (unsigned int a = 0; a < nf; ++a)
          for (unsigned int b = 0; b < nf; ++b)
            {
              double value = D(cb, a, ca, b);
              if (ca == cb)
                {
                  value += mass[a * nf + b];
                  for (unsigned int d = 0; d < dim; ++d)
                    value += D(d, a, d, b);
                }
              copy.matrix(L.dof(ca, a), L.dof(cb, b)) += value;
            }
  }

  template class CutCellPenalties<2>;
  template class CutCellPenalties<3>;
} // namespace fdparticle
