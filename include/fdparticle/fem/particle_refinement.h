#ifndef fdparticle_fem_particle_refinement_h
#define fdparticle_fem_particle_refinement_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria.h>

#include <fdparticle/base/statistics_table.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/particles/particle_set.h>

#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Mesh refinement that follows the particles (subsection Refinement): cells within
   * 'Band width' of their own size from a particle surface are refined up to 'Particle
   * refinement levels' levels above the base mesh; cells that left the band are coarsened.
   * Hanging nodes are handled by the AffineConstraints of the simulation.
   */
  template <int dim>
  class ParticleRefinement
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    unsigned int levels() const { return n_levels; }
    bool         enabled() const { return n_levels > 0; }
    bool         due(const unsigned int step) const
    {
      return enabled() && step % interval == 0;
    }

    /// Flag cells for one pass of refinement/coarsening; true if any cell on any rank
    /// keeps a flag after the triangulation's smoothing, i.e. if the mesh will change.
    /// The caller executes it (with its solution transfer).
    bool mark(parallel::distributed::Triangulation<dim> &triangulation,
              const ParticleSet<dim> &particles, const unsigned int base_level) const;

    /// The number of cells once the mesh is adapted to the particles at their present
    /// positions, estimated before building it, to refuse an unaffordable mesh.
    double estimated_cells(const Domain<dim> &domain, const ParticleSet<dim> &particles) const;

    /// Whether the cell lies within the band around some particle surface (of any of
    /// its periodic images).
    bool in_band(const typename Triangulation<dim>::cell_iterator &cell,
                 const ParticleSet<dim> &particles) const;

    /// statistics.csv's coarse_cut_cells: cut cells below the finest level (0 without
    /// particle refinement), a check that the band keeps up with the particles.
    void declare_columns(StatisticsTable &statistics) const;
    void statistics(const parallel::distributed::Triangulation<dim> &triangulation,
                    const ParticleSet<dim> &particles, const unsigned int base_level,
                    StatisticsTable &statistics) const;

    /// Cells cut by a particle surface that are not at the finest level (a check).
    unsigned int coarse_cut_cells(const parallel::distributed::Triangulation<dim> &triangulation,
                                  const ParticleSet<dim> &particles,
                                  const unsigned int base_level) const;

    /// Refuse, before the mesh is built, a scene whose adapted mesh would be unaffordable
    /// (Domain::max_cells) or whose particles the finest cells cannot resolve
    /// (ParticleSet::min_radius_in_cells): such a run fails at an unpredictable point, on
    /// one rank only, or takes the machine down.
    void check_scene(const Domain<dim> &domain, const ParticleSet<dim> &particles) const;

    /// One warning sentence for each particle smaller than the cells around it
    /// (radius below the smallest cell edge near it): λ cannot see such a ball.
    std::vector<std::string>
    resolution_warnings(const parallel::distributed::Triangulation<dim> &triangulation,
                        const ParticleSet<dim> &                          particles) const;

  private:
    unsigned int n_levels = 0, interval = 1;
    double       band_width = 1;
  };
} // namespace fdparticle

#endif
