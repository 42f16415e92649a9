#ifndef fdparticle_fem_domain_h
#define fdparticle_fem_domain_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/affine_constraints.h>

#include <array>
#include <cmath>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The box Ω: its corners and base mesh (subsection Geometry) and what happens on its
   * faces (subsection Boundary conditions): each direction is periodic or bounded by two
   * no-slip walls, which may slide with a given velocity. Faces carry boundary ids
   * 0..2dim-1 in the order x-, x+, y-, y+, z-, z+.
   */
  template <int dim>
  class Domain
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /**
     * The most cells a mesh may have; a scene asking for more is refused before the mesh
     * is built. 1e7 is 100 times the largest mesh run with the code: the Q2/Q2/P1
     * unknowns alone take about 10 kB per cell in 2D and 90 kB in 3D, so 1e7 cells need
     * 0.1–1 TB. A larger request is a mistake (one refinement level too many), not a scene.
     */
    static constexpr double max_cells = 1e7;

    /**
     * The largest coordinate, and the inverse of the narrowest box, accepted. Lengths enter
     * squared and cubed (cell volumes, |x - X|^2) and are multiplied by densities,
     * viscosities and 1/dt: beyond 1e+-30 a scene leaves the range of double (1e+-308)
     * and the run ends in overflow or a stack overflow of the cut-cell quadrature. A light
     * year is 1e16 m, a nanometre 1e-9 m: any scene in any unit lies inside.
     */
    static constexpr double max_length = 1e30;

    /// Build the (refined) base mesh and register periodic face pairs with p4est.
    void create_mesh(parallel::distributed::Triangulation<dim> &triangulation) const;
    /// The same without the global refinements: what a checkpoint's mesh is loaded onto.
    void create_coarse_mesh(parallel::distributed::Triangulation<dim> &triangulation) const;

    /// Periodicity constraints on all components given in mask.
    void make_periodicity_constraints(const DoFHandler<dim> &    dof_handler,
                                      AffineConstraints<double> &constraints) const;

    /**
     * Wall conditions: the components in velocity_mask take each wall's velocity
     * (homogeneous = true: zero, for Newton updates). Walls at rest are applied first, so
     * at an edge shared by a resting and a sliding wall the fluid is at rest ("watertight"
     * lid). The multiplier is not constrained on walls: a particle near a wall needs the
     * rigid modes of λ in the cut cells that touch it (doc/method.md §4).
     */
    void make_wall_constraints(const DoFHandler<dim> &    dof_handler,
                               const ComponentMask &      velocity_mask,
                               const bool                 homogeneous,
                               AffineConstraints<double> &constraints) const;

    /// A wall near a ball: the gap between them, the wall's inward normal and its
    /// (tangential) velocity.
    struct WallGap
    {
      double         gap;
      Tensor<1, dim> normal, velocity;
    };
    /// The walls whose gap to the ball of centre x and radius r is below reach.
    std::vector<WallGap> walls_near(const Point<dim> &x, const double r, const double reach) const;

    bool                 is_periodic(const unsigned int direction) const;
    /// The box's length in each periodic direction, 0 in the wall-bounded ones.
    Tensor<1, dim>       period() const;
    /// r shifted by whole periods (period as given by period()) to its shortest image:
    /// the nearest-image rule of every distance in a periodic box (doc/method.md §12).
    static Tensor<1, dim> nearest_image(Tensor<1, dim> r, const Tensor<1, dim> &period)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (period[d] > 0)
          r[d] -= period[d] * std::round(r[d] / period[d]);
      return r;
    }
    bool                 is_wall(const types::boundary_id face) const;
    Tensor<1, dim>       wall_velocity(const types::boundary_id face) const;
    const Point<dim> &   lower_corner() const { return lower; }
    const Point<dim> &   upper_corner() const { return upper; }
    double               volume() const;
    unsigned int         n_global_refinements() const { return global_refinements; }
    /// Cells of the mesh create_mesh() builds (before any particle refinement).
    double               n_cells() const;
    /// The smallest base-mesh cell edge after the global refinements.
    double               base_cell_size() const;
    static std::string   face_name(const types::boundary_id face);

  private:
    Point<dim>                             lower, upper;
    std::vector<unsigned int>              subdivisions;
    unsigned int                           global_refinements = 0;
    std::array<bool, dim>                  periodic{};
    std::array<Tensor<1, dim>, 2 * dim>    wall_velocities{};
  };
} // namespace fdparticle

#endif
