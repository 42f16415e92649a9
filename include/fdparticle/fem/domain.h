#ifndef fdparticle_fem_domain_h
#define fdparticle_fem_domain_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/affine_constraints.h>

#include <fdparticle/base/box.h>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The box Ω with its mesh: the Box (corners, periodic directions, walls) and the base
   * mesh on it (subsection Geometry), the periodic face pairs p4est needs, and the wall
   * and periodicity constraints on a DoFHandler. Faces carry the boundary ids of
   * Box::face_name.
   */
  template <int dim>
  class Domain : public Box<dim>
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

    /// Build the (refined) base mesh and register periodic face pairs with p4est.
    void create_mesh(parallel::distributed::Triangulation<dim> &triangulation) const;
    /// The same without the global refinements: what a checkpoint's mesh is loaded onto.
    void create_coarse_mesh(parallel::distributed::Triangulation<dim> &triangulation) const;

    /**
     * coarse = fine with every cell replaced by its parent (cells of the base mesh stay),
     * periodic faces registered as in create_coarse_mesh(): one level of a geometric
     * multigrid's mesh hierarchy. coarse must be empty.
     */
    void create_coarsened_copy(const parallel::distributed::Triangulation<dim> &fine,
                               parallel::distributed::Triangulation<dim> &      coarse) const;

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

    unsigned int         n_global_refinements() const { return global_refinements; }
    /// Cells of the mesh create_mesh() builds (before any particle refinement).
    double               n_cells() const;
    /// The smallest base-mesh cell edge after the global refinements.
    double               base_cell_size() const;

  private:
    std::vector<unsigned int> subdivisions;
    unsigned int              global_refinements = 0;
  };
} // namespace fdparticle

#endif
