#include <deal.II/base/mpi.h>

#include <iomanip>
#include <limits>
#include <sstream>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/fem/particle_refinement.h>
#include <fdparticle/particles/sphere.h>

namespace fdparticle
{
  namespace
  {
    /**
     * Slack of the band's edges, in units of the cell's size. For a centre on a vertex and
     * a radius of whole cells the edges R ± b h lie on mesh planes, and mirror-image cells
     * must decide alike after the centre has drifted off its plane of symmetry by
     * round-off (about 1e-12 a step on prm/dkt3d.prm); otherwise one side of a pair's band
     * loses a row of refined cells and the pair leaves its plane. A millionth of a cell
     * covers tens of thousands of such steps and moves no band edge that matters.
     */
    constexpr double band_tolerance = 1e-6;
  } // namespace

  template <int dim>
  void ParticleRefinement<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Refinement");
    {
      prm.declare_entry("Particle refinement levels", "0", Patterns::Integer(0, 8),
                        "Extra refinement levels around particle surfaces, 0 to 8, re-adapted "
                        "as the particles move (0: the base mesh as it is).");
      prm.declare_entry("Band width", "1", Patterns::Double(0),
                        "Half-width of the refined band around each surface, in units of the "
                        "local cell size.");
      prm.declare_entry("Refinement interval", "1", Patterns::Integer(1),
                        "Adapt the mesh to the particles every N steps.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void ParticleRefinement<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Refinement");
    n_levels = prm.get_integer("Particle refinement levels");
    band_width = prm.get_double("Band width");
    interval = prm.get_integer("Refinement interval");
    prm.leave_subsection();
  }

  template <int dim>
  double ParticleRefinement<dim>::estimated_cells(const Domain<dim> &      domain,
                                                  const ParticleSet<dim> &particles) const
  {
    // Each pass refines the cells in_band() finds: a shell around each surface reaching
    // band_width h + the cell diagonal sqrt(dim) h to either side; each refined cell
    // adds 2^dim - 1. Counted in units of h (no overflow for tiny or huge boxes) and at
    // most every cell of the level. The mesh smoothing adds a few cells more: this is an
    // estimate to refuse absurd requests, not a prediction.
    const double base = domain.n_cells();
    double       cells = base;
    double       h = domain.base_cell_size();
    const double half_width = band_width + std::sqrt(double(dim));
    for (unsigned int level = 0; level < n_levels; ++level, h /= 2)
      {
        double in_bands = 0;
        for (unsigned int k = 0; k < particles.size(); ++k)
          {
            const double r = particles[k].bounding_radius() / h;
            in_bands += Sphere<dim>(r + half_width).volume() -
                        Sphere<dim>(std::max(0.0, r - half_width)).volume();
          }
        const double all = base * std::pow(2.0, dim * level);
        cells += (std::pow(2.0, dim) - 1) * (in_bands < all ? in_bands : all);
      }
    return cells;
  }

  template <int dim>
  bool ParticleRefinement<dim>::in_band(const typename Triangulation<dim>::cell_iterator &cell,
                                        const ParticleSet<dim> &particles) const
  {
    // Distance from the particle's surface to the cell's box, against band × diameter.
    // Only the balls within the margin of a box can pass: the index finds them, in the box
    // grown by one cell more than the margin, so that the strict test of meeting() cannot
    // drop a ball exactly at the margin. In a periodic direction each image of a centre
    // counts, so a ball next to a periodic face has the same mesh around it as in the
    // middle of the box (and no hanging nodes across that face).
    const BoundingBox<dim> box = cell->bounding_box();
    const double h = cell->diameter() / std::sqrt(double(dim));
    const double margin = band_width * h;
    BoundingBox<dim> reach = box;
    reach.extend(margin + h);
    // With a slack, so that mirror-image cells decide alike (band_tolerance).
    const double tolerance = band_tolerance * h;
    for (const unsigned int k : particles.meeting(reach))
      {
        const Particle<dim> &p = particles[k];
        for (const Point<dim> &X : p.centres_near(box, p.bounding_radius() + margin + tolerance))
          {
            // The box's farthest point from the centre: the far corner in every direction.
            double far2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              far2 += std::pow(std::max(std::abs(X[d] - box.lower_bound(d)),
                                        std::abs(X[d] - box.upper_bound(d))),
                               2);
            if (p.shape->is_isotropic())
              {
                if (std::sqrt(far2) >= p.shape->inscribed_radius() - margin - tolerance)
                  return true;
                continue;
              }
            // Another (convex) shape: the box grown by the margin meets it, and not every
            // corner lies in the shape shrunk about its centre by the factor
            // s = 1 − margin/inscribed radius, whose points are at least the margin inside
            // (its support function is s h(n) ≤ h(n) − margin). For a ball both are the
            // test above.
            BoundingBox<dim> grown = box;
            grown.extend(margin + tolerance);
            if (!p.shape->meets(grown, X, p.geometry_rotation))
              continue;
            const double s = 1 - (margin + tolerance) / p.shape->inscribed_radius();
            if (s <= 0)
              return true;
            for (unsigned int v = 0; v < (1u << dim); ++v)
              {
                Tensor<1, dim> r;
                for (unsigned int d = 0; d < dim; ++d)
                  r[d] = ((v >> d) & 1 ? box.upper_bound(d) : box.lower_bound(d)) - X[d];
                if (!p.shape->contains(transpose(p.geometry_rotation) * r / s))
                  return true;
              }
          }
      }
    return false;
  }

  template <int dim>
  bool ParticleRefinement<dim>::mark(parallel::distributed::Triangulation<dim> &triangulation,
                                     const ParticleSet<dim> &particles,
                                     const unsigned int      base_level) const
  {
    bool changed = false;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          // Coarsen only where the parent would not be refined again: a child can leave
          // the band (its own margin is smaller) while its parent is still in it, and the
          // mesh would flip between the two every step.
          if (in_band(cell, particles))
            {
              if (cell->level() < int(base_level + n_levels))
                {
                  cell->set_refine_flag();
                  changed = true;
                }
            }
          else if (cell->level() > int(base_level) && !in_band(cell->parent(), particles))
            {
              cell->set_coarsen_flag();
              changed = true;
            }
        }
    if (!Utilities::MPI::logical_or(changed, triangulation.get_communicator()))
      return false;
    // A coarsening flag stays only where all siblings have one: what is left after the
    // smoothing decides whether the mesh changes at all (an unchanged mesh keeps its DoFs
    // and whatever the solvers built on them).
    triangulation.prepare_coarsening_and_refinement();
    bool flagged = false;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && (cell->refine_flag_set() || cell->coarsen_flag_set()))
        {
          flagged = true;
          break;
        }
    return Utilities::MPI::logical_or(flagged, triangulation.get_communicator());
  }

  template <int dim>
  unsigned int ParticleRefinement<dim>::coarse_cut_cells(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const ParticleSet<dim> &particles, const unsigned int base_level) const
  {
    unsigned int n = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->level() < int(base_level + n_levels))
        for (const unsigned int k : particles.meeting(cell->bounding_box()))
          {
            bool inside = false, outside = false;
            for (const unsigned int v : cell->vertex_indices())
              (particles[k].contains(cell->vertex(v)) ? inside : outside) = true;
            n += (inside && outside);
          }
    return Utilities::MPI::sum(n, triangulation.get_communicator());
  }

  template <int dim>
  std::vector<std::string> ParticleRefinement<dim>::resolution_warnings(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const ParticleSet<dim> &                          particles) const
  {
    // The ball must span cells for λ to see it; below one cell per radius it is a blur.
    std::vector<std::string> warnings;
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        double               h = std::numeric_limits<double>::max();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              cell->center().distance(P.position) < P.bounding_radius() + cell->diameter())
            h = std::min(h, cell->minimum_vertex_distance());
        h = Utilities::MPI::min(h, triangulation.get_communicator());
        const double R = P.shape->inscribed_radius();
        if (R < h)
          {
            std::ostringstream w;
            w << "Warning: particle " << k << " (radius " << R
              << ") is smaller than the cells around it (h = " << h << ", d/h = "
              << std::setprecision(3) << 2 * R / h
              << "): it is under-resolved; refine with Geometry/Global refinements or "
                 "Refinement/Particle refinement levels.";
            warnings.push_back(w.str());
          }
      }
    return warnings;
  }

  template <int dim>
  void ParticleRefinement<dim>::check_scene(const Domain<dim> &     domain,
                                            const ParticleSet<dim> &particles) const
  {
    const double cells = estimated_cells(domain, particles);
    AssertThrow(cells <= Domain<dim>::max_cells,
                ExcMessage("The mesh would have about " + ParameterTools::format_short(cells) +
                           " cells (" + ParameterTools::format_short(domain.n_cells()) +
                           " base cells, Refinement/Particle refinement levels = " +
                           std::to_string(n_levels) +
                           " around the particles); fdparticle refuses meshes of more than " +
                           ParameterTools::format_short(Domain<dim>::max_cells) +
                           " cells (0.1-1 TB of memory). Use fewer particle refinement "
                           "levels, a narrower Refinement/Band width or a coarser base mesh."));
    const double h = domain.base_cell_size() / std::pow(2.0, n_levels);
    for (unsigned int k = 0; k < particles.size(); ++k)
      AssertThrow(particles[k].shape->inscribed_radius() >=
                    ParticleSet<dim>::min_radius_in_cells * h,
                  ExcMessage("Particle " + std::to_string(k) + " (radius " +
                             ParameterTools::format_short(particles[k].shape->inscribed_radius()) +
                             ") is smaller than " +
                             ParameterTools::format_short(ParticleSet<dim>::min_radius_in_cells) +
                             " times the finest cell edge (h = " +
                             ParameterTools::format_short(h) +
                             "): the mesh cannot resolve it. Refine with Geometry/Global "
                             "refinements or Refinement/Particle refinement levels."));
  }

  template <int dim>
  void ParticleRefinement<dim>::declare_columns(StatisticsTable &statistics) const
  {
    statistics.declare("coarse_cut_cells");
  }

  template <int dim>
  void ParticleRefinement<dim>::statistics(
    const parallel::distributed::Triangulation<dim> &triangulation,
    const ParticleSet<dim> &particles, const unsigned int base_level,
    StatisticsTable &statistics) const
  {
    if (enabled())
      statistics.set("coarse_cut_cells", coarse_cut_cells(triangulation, particles, base_level));
  }

  template class ParticleRefinement<2>;
  template class ParticleRefinement<3>;
} // namespace fdparticle
