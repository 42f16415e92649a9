#ifndef fdparticle_fem_assembly_assembly_data_h
#define fdparticle_fem_assembly_assembly_data_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <fdparticle/fem/assembly/cell_shapes.h>
#include <fdparticle/fem/assembly/particle_integrals.h>
#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/fem/introspection.h>

#include <array>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * What every assembly term reads (doc/method.md §3): the step's constants, the cell's
   * kind, the current iterate and the shape functions at one quadrature point and, for the
   * Jacobian's cell products, at all points of the cell. NavierStokesAssembler fills it
   * cell by cell and point by point; the terms only read it.
   */
  template <int dim>
  struct AssemblyScratch
  {
    AssemblyScratch(const FESystem<dim> &fe, const std::array<double, 3> &c, const double alpha,
                    const double viscous_pairing, const bool with_matrix);

    /// κ = α + c μ/R² of the pairing <λ, v> over a ball of radius R (doc/method.md §0, §4).
    double pairing_weight(const double radius) const
    {
      return alpha + viscous_pairing / (radius * radius);
    }

    /// The cell: read the shape functions at all its points from the FEValues of the
    /// scalar element of u and λ (one FE_Q serves both) and of the pressure's, and
    /// evaluate the iterate there from the cell's coefficients of the solution and of the
    /// history. A FEValues of the scalar elements costs a fraction of the FESystem's, which
    /// matters where a level-set rule is made for one cut cell (doc/method.md §7).
    void reinit(const FEValues<dim> &scalar, const FEValues<dim> &pressure,
                const Vector<double> &solution, const Vector<double> &history);
    /// The point q of the cell: its shape functions into N and dN.
    void reinit_point(const unsigned int q);

    // The step.
    std::array<double, 3> c;           ///< BDF weights: ∂_t u ≈ c0 u + c1 u^n + c2 u^{n−1}
    double                alpha;       ///< α = ρ_f c0 of the step (doc/method.md §0)
    double                viscous_pairing; ///< c μ of the pairing weight κ = α + c μ/R²
    bool                  with_matrix; ///< assemble the Jacobian as well as the residual

    // The local DoFs by field, the vector component (0..dim−1) of each, and the index of
    // its function in the field's scalar element.
    std::vector<unsigned int> component, scalar_function;
    std::vector<unsigned int> velocity_dofs, multiplier_dofs, pressure_dofs;

    // The cell.
    CellKind                kind = CellKind::fluid;
    int                     cut_particle = -1; ///< the ball whose surface is nearest to the point (cut cells)
    double                  particle_fraction = 0; ///< of a cut cell: its weights inside
    bool                    has_particle = false;  ///< some point of the cell is in a particle
    // The iterate at the cell's points.
    std::vector<Tensor<1, dim>> u, u_history, lambda;
    std::vector<Tensor<2, dim>> grad_u, grad_lambda;
    std::vector<double>         p;
    // Every point of the cell: its weight JxW, its owner (−1: fluid) and, for a fluid point
    // of a cut cell, the ball whose surface is nearest.
    std::vector<double> weights;
    std::vector<int>    owners, nearest_surfaces;
    // The shape functions at every point of the cell: u and λ as CellShapes, the
    // pressure's as row-major n_points × pressure_dofs matrices.
    CellShapes<dim>             velocity_shapes, multiplier_shapes;
    std::vector<double>         pressure_values;
    std::vector<Tensor<1, dim>> pressure_gradients;

    // The point.
    unsigned int                q = 0;
    double                      JxW = 0;
    Point<dim>                  x;
    int                         particle = -1; ///< owner of the point, −1: fluid
    std::vector<double>         N;             ///< shape values at the point
    std::vector<Tensor<1, dim>> dN;            ///< shape gradients at the point
  };

  /**
   * What the terms add to: the cell's residual and Jacobian, the particle coupling of the
   * free particles the cell meets (the cell's part of the border columns B and rows C of
   * the Newton system, doc/method.md §3) and the particle integrals of this rank.
   */
  template <int dim>
  struct AssemblyCopy
  {
    AssemblyCopy(const unsigned int dofs_per_cell, const unsigned int n_particles)
      : matrix(dofs_per_cell, dofs_per_cell)
      , rhs(dofs_per_cell)
      , border_B(n_particles)
      , border_C(n_particles)
      , integrals(n_particles)
    {}

    FullMatrix<double> matrix;
    Vector<double>     rhs;
    /// [particle] → (local DoF, particle unknown) block of B and of Cᵀ; sized only for the
    /// free particles in touching.
    std::vector<FullMatrix<double>> border_B, border_C;
    /// The particles owning points of the cell, each once.
    std::vector<int> touching;
    /// Summed over all cells of this rank (not reset per cell).
    std::vector<ParticleIntegrals<dim>> integrals;
    /// Workspace of the cell products (weighted shape matrices and their products), kept
    /// from cell to cell to spare the allocations.
    std::vector<double> weighted, product;
  };
} // namespace fdparticle

#endif
