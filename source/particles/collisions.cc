#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/particles/collisions.h>

#include <algorithm>

namespace fdparticle
{
  template <int dim>
  void Collisions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Collisions");
    {
      prm.declare_entry("Model", "none", Patterns::Selection("none|repulsion"),
                        "Contact between particles. none: the run stops when two particles "
                        "overlap. repulsion: a short-range force along the line of centres "
                        "(Glowinski et al. 2001) keeps them apart, with the law of the wall "
                        "repulsion.");
      prm.declare_entry("Range", "auto", Patterns::Anything(),
                        "Gap between two particle surfaces below which the force acts (a "
                        "length), or 'auto': the edge of the finest cells, as for the walls.");
      prm.declare_entry("Stiffness", "auto", Patterns::Anything(),
                        "Force at contact (gap 0), or 'auto': 100 times the apparent weight "
                        "|rho_P - rho_f| |P| |g| of the heavier particle of the pair, so a "
                        "particle resting on another sits 0.9 Range above it.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Collisions<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Collisions");
    contact_model = (prm.get("Model") == "repulsion" ? Model::repulsion : Model::none);
    range_entry = get_auto_or_number(prm, "Range", "Collisions/Range", Zero::refused);
    stiffness_entry =
      get_auto_or_number(prm, "Stiffness", "Collisions/Stiffness", Zero::refused);
    prm.leave_subsection();
  }

  template <int dim>
  void Collisions<dim>::initialize(const Domain<dim> &domain, const Fluid<dim> &fluid,
                                   const ParticleSet<dim> &particles,
                                   const double finest_cell_size)
  {
    range = range_entry.value_or(finest_cell_size);
    search = std::make_unique<PairSearch<dim>>(domain);
    weight.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      weight[k] = std::abs(particles[k].density - fluid.density) * particles[k].volume() *
                  fluid.gravity.norm();
    if (contact_model == Model::repulsion && !stiffness_entry)
      for (unsigned int i = 0; i < particles.size(); ++i)
        AssertThrow(weight[i] > 0 || particles.size() == 1 ||
                      particles[i].first_unknown == numbers::invalid_unsigned_int,
                    ExcMessage("Collisions/Stiffness = auto scales with the apparent weight of "
                               "the particles, and particle " + std::to_string(i + 1) +
                               " has none (no gravity, or the fluid's density): give the "
                               "force at contact as a number."));
  }

  template <int dim>
  RepulsionLaw Collisions<dim>::law(const unsigned int i, const unsigned int j) const
  {
    return RepulsionLaw{range, stiffness_entry.value_or(RepulsionLaw::stiffness_per_weight *
                                                        std::max(weight[i], weight[j]))};
  }

  namespace
  {
    template <int dim>
    void centres_and_radii(const ParticleSet<dim> &particles, const std::array<double, 3> *c,
                           std::vector<Point<dim>> &x, std::vector<double> &r)
    {
      x.resize(particles.size());
      r.resize(particles.size());
      for (unsigned int k = 0; k < particles.size(); ++k)
        {
          x[k] = (c != nullptr ? particles[k].position_after_step(*c) : particles[k].position);
          r[k] = particles[k].radius;
        }
    }
  } // namespace

  template <int dim>
  void Collisions<dim>::add_to_particle_rows(ParticleSet<dim> &particles,
                                             const std::array<double, 3> &c,
                                             Eigen::VectorXd &r_p, Eigen::MatrixXd *D) const
  {
    if (contact_model == Model::none)
      return;
    Assert(search, ExcMessage("Collisions::initialize was not called."));
    std::vector<Point<dim>> x;
    std::vector<double>     r;
    centres_and_radii(particles, &c, x, r);
    for (const auto &pair : search->pairs(x, r, range))
      {
        const RepulsionLaw   F_of = law(pair.i, pair.j);
        const double         distance = pair.offset.norm();
        const Tensor<1, dim> n = pair.offset / distance;
        const Tensor<1, dim> F = F_of.force(pair.gap) * n; // on i; −F on j
        // dF/d(X_i − X_j) = F'(g) n nᵀ + F(g)/|X_i − X_j| (I − n nᵀ): the first term from
        // the gap, the second from the turning normal. dX/dV = 1/c0.
        Tensor<2, dim> dF;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            dF[a][b] = F_of.derivative(pair.gap) * n[a] * n[b] +
                       F_of.force(pair.gap) / distance * ((a == b ? 1.0 : 0.0) - n[a] * n[b]);
        const std::array<unsigned int, 2> k{{pair.i, pair.j}};
        const std::array<double, 2>       sign{{1.0, -1.0}}; // ∂(X_i − X_j)/∂X_k
        for (unsigned int s = 0; s < 2; ++s)
          {
            Particle<dim> &P = particles[k[s]];
            P.contact_force += sign[s] * F;
            if (P.first_unknown == numbers::invalid_unsigned_int)
              continue;
            for (unsigned int d = 0; d < dim; ++d)
              r_p[P.first_unknown + d] -= sign[s] * F[d];
            if (D != nullptr)
              for (unsigned int t = 0; t < 2; ++t)
                {
                  const unsigned int column = particles[k[t]].first_unknown;
                  if (column == numbers::invalid_unsigned_int)
                    continue;
                  for (unsigned int a = 0; a < dim; ++a)
                    for (unsigned int b = 0; b < dim; ++b)
                      (*D)(P.first_unknown + a, column + b) -= sign[s] * sign[t] * dF[a][b] / c[0];
                }
          }
      }
  }

  template <int dim>
  void Collisions<dim>::statistics(const ParticleSet<dim> &particles, unsigned int &n_contacts,
                                   double &min_gap) const
  {
    Assert(search, ExcMessage("Collisions::initialize was not called."));
    n_contacts = 0;
    std::vector<Point<dim>> x;
    std::vector<double>     r;
    centres_and_radii<dim>(particles, nullptr, x, r);
    const double diameter = (r.empty() ? 0.0 : 2 * *std::max_element(r.begin(), r.end()));
    min_gap               = diameter;
    for (const auto &pair : search->pairs(x, r, diameter))
      {
        min_gap = std::min(min_gap, pair.gap);
        if (pair.gap < range)
          ++n_contacts;
      }
  }

  template class Collisions<2>;
  template class Collisions<3>;
} // namespace fdparticle
