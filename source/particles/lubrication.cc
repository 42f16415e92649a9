#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/lubrication.h>

#include <cmath>

namespace fdparticle
{
  template <int dim>
  void Lubrication<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Lubrication");
    {
      prm.declare_entry("Enabled", "false", Patterns::Bool(),
                        "Add the squeeze force of gaps thinner than the mesh resolves, "
                        "between particles and between a particle and a wall: the leading term "
                        "of lubrication theory at the gap g less its value at g + s, the wider "
                        "gap whose force the resolved flow carries (doc/particles.md, "
                        "Lubrication).");
      prm.declare_entry("Gap shift", "auto", Patterns::Anything(),
                        "s_0, the shift s of a gap below a cell (a length; s tapers from s_0 at "
                        "contact to 0 at Resolved gap), or 'auto', fitted to the resolved force: "
                        "0.033 a* at a wall (a* the reduced radius), 0.97 h between balls in 3D "
                        "and 0.85 h in 2D (h the finest cell edge; doc/particles.md, "
                        "Lubrication).");
      prm.declare_entry("Resolved gap", "auto", Patterns::Anything(),
                        "Gap below which the correction acts (a length), or 'auto': three "
                        "finest cell edges, from where the resolved squeeze force has "
                        "converged.");
      prm.declare_entry("Minimum gap", "auto", Patterns::Anything(),
                        "Gap below which the correction stays at its value there (surface "
                        "roughness; a length), or 'auto': 0.001 of the reduced radius "
                        "a_i a_j / (a_i + a_j) (of the radius at a wall).");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Lubrication<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Lubrication");
    on = prm.get_bool("Enabled");
    resolved_entry = get_auto_or_number(prm, "Resolved gap", "Lubrication/Resolved gap",
                                        Zero::refused);
    minimum_entry =
      get_auto_or_number(prm, "Minimum gap", "Lubrication/Minimum gap", Zero::refused);
    shift_entry = get_auto_or_number(prm, "Gap shift", "Lubrication/Gap shift", Zero::allowed);
    prm.leave_subsection();
  }

  template <int dim>
  void Lubrication<dim>::check_scene(const ParticleSet<dim> &particles) const
  {
    // The correction is the sphere's (and the cylinder's) near-contact asymptote.
    if (on)
      this->require_balls(particles, "Lubrication/Enabled", "the lubrication correction",
                          "set Lubrication/Enabled = false");
  }

  template <int dim>
  void Lubrication<dim>::initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                                    const ParticleSet<dim> & /*particles*/,
                                    const double finest_cell_size)
  {
    this->domain = domain;
    viscosity    = fluid.viscosity;
    resolved_gap = resolved_entry.value_or(resolved_gap_cells * finest_cell_size);
    finest_cell  = finest_cell_size;
    search       = std::make_unique<PairSearch<dim>>(domain);
  }

  template <int dim>
  double Lubrication<dim>::minimum_gap(const double reduced_radius) const
  {
    return minimum_entry.value_or(minimum_gap_fraction * reduced_radius);
  }

  template <int dim>
  double Lubrication<dim>::gap_shift(const double reduced_radius, const bool pair) const
  {
    if (shift_entry)
      return *shift_entry;
    return pair ? pair_shift_cells * finest_cell : shift_fraction * reduced_radius;
  }

  template <int dim>
  std::pair<double, double> Lubrication<dim>::coefficient(const double reduced_radius,
                                                          const double gap) const
  {
    const double minimum      = minimum_gap(reduced_radius);
    const double g            = std::max(gap, minimum);
    const double slope_factor = (gap > minimum ? 1.0 : 0.0); // C' = 0 where g is clamped
    if (dim == 3)
      {
        const double scale = 6 * numbers::PI * viscosity * reduced_radius * reduced_radius;
        return {scale / g, slope_factor * -scale / (g * g)};
      }
    const double scale =
      3 * std::sqrt(2.0) * numbers::PI * viscosity * std::pow(reduced_radius, 1.5);
    return {scale * std::pow(g, -1.5), slope_factor * -1.5 * scale * std::pow(g, -2.5)};
  }

  template <int dim>
  NormalLawValue Lubrication<dim>::law(const double reduced_radius, const bool pair,
                                       const double gap, const double normal_velocity) const
  {
    if (gap >= resolved_gap)
      return NormalLawValue{};
    // s(g) = s_0 (1 − g/g_r): the shift of the resolved flow, gone where it has converged.
    const double slope = -gap_shift(reduced_radius, pair) / resolved_gap;
    const double shift = slope * (gap - resolved_gap);
    const auto [C, dC] = coefficient(reduced_radius, gap);
    const auto [C_wide, dC_wide] = coefficient(reduced_radius, gap + shift);
    const double excess = C - C_wide, d_excess = dC - dC_wide * (1 + slope);
    return NormalLawValue{-excess * normal_velocity, -d_excess * normal_velocity, -excess};
  }

  template <int dim>
  void Lubrication<dim>::add_to_particle_rows(ParticleSet<dim> &particles,
                                             const std::array<double, 3> &c,
                                             Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const
  {
    if (!on)
      return;
    Assert(search, ExcMessage("Lubrication::initialize was not called."));
    std::vector<Point<dim>> x(particles.size());
    std::vector<double>     r(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        x[k] = particles[k].position_after_step(c);
        r[k] = particles[k].bounding_radius();
        for (const auto &wall : domain.walls_near(x[k], r[k], resolved_gap))
          {
            const auto contact = NormalContact<dim>::wall(particles, k, wall.normal, wall.gap);
            contact.add(particles, law(r[k], false, wall.gap, contact.normal_velocity()), c, r_p, D);
          }
      }
    for (const auto &pair : search->pairs(x, r, resolved_gap))
      {
        const auto contact =
          NormalContact<dim>::pair(particles, pair.i, pair.j, pair.offset, pair.gap);
        const double reduced = r[pair.i] * r[pair.j] / (r[pair.i] + r[pair.j]);
        contact.add(particles, law(reduced, true, pair.gap, contact.normal_velocity()), c, r_p, D);
      }
  }

  template class Lubrication<2>;
  template class Lubrication<3>;
} // namespace fdparticle
