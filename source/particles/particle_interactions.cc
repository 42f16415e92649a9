#include <fdparticle/particles/collisions.h>
#include <fdparticle/particles/lubrication.h>
#include <fdparticle/particles/particle_interactions.h>
#include <fdparticle/particles/wall_repulsion.h>

namespace fdparticle
{
  template <int dim>
  void ParticleInteractions<dim>::declare_parameters(ParameterHandler &prm)
  {
    WallRepulsion<dim>::declare_parameters(prm);
    Collisions<dim>::declare_parameters(prm);
    Lubrication<dim>::declare_parameters(prm);
  }

  template <int dim>
  void ParticleInteractions<dim>::parse_parameters(ParameterHandler &prm)
  {
    // The order is the order of the sums into the particle rows.
    list.clear();
    list.push_back(std::make_unique<WallRepulsion<dim>>());
    list.push_back(std::make_unique<Collisions<dim>>());
    list.push_back(std::make_unique<Lubrication<dim>>());
    for (const auto &interaction : list)
      interaction->parse_parameters(prm);
  }

  template <int dim>
  void ParticleInteractions<dim>::check_scene(const ParticleSet<dim> &particles) const
  {
    for (const auto &interaction : list)
      interaction->check_scene(particles);
  }

  template <int dim>
  void ParticleInteractions<dim>::initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                                             const ParticleSet<dim> &particles,
                                             const double            finest_cell_size)
  {
    for (const auto &interaction : list)
      interaction->initialize(domain, fluid, particles, finest_cell_size);
  }

  template <int dim>
  std::vector<std::string> ParticleInteractions<dim>::describe(const double dt) const
  {
    std::vector<std::string> lines;
    for (const auto &interaction : list)
      if (interaction->enabled())
        if (const std::string line = interaction->describe(dt); !line.empty())
          lines.push_back(line);
    return lines;
  }

  template <int dim>
  void ParticleInteractions<dim>::add_to_particle_rows(ParticleSet<dim> &           particles,
                                                       const std::array<double, 3> &c,
                                                       Eigen::VectorXd &            r_p,
                                                       Eigen::SparseMatrix<double> *D) const
  {
    for (unsigned int k = 0; k < particles.size(); ++k)
      particles[k].contact_force = Tensor<1, dim>();
    for (const auto &interaction : list)
      if (interaction->enabled())
        interaction->add_to_particle_rows(particles, c, r_p, D);
  }

  template <int dim>
  void ParticleInteractions<dim>::declare_columns(StatisticsTable &statistics) const
  {
    for (const auto &interaction : list)
      interaction->declare_columns(statistics);
  }

  template <int dim>
  void ParticleInteractions<dim>::statistics(const ParticleSet<dim> &particles,
                                             StatisticsTable &       statistics) const
  {
    for (const auto &interaction : list)
      interaction->statistics(particles, statistics);
  }

  template class ParticleInteractions<2>;
  template class ParticleInteractions<3>;
} // namespace fdparticle
