#ifndef fdparticle_particles_lubrication_h
#define fdparticle_particles_lubrication_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/base/box.h>
#include <fdparticle/particles/normal_contact.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_interaction.h>
#include <fdparticle/particles/particle_set.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <memory>
#include <optional>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Lubrication correction (subsection Lubrication, doc/method.md §12): the part of the
   * squeeze force of a thin gap that the mesh does not resolve, added between two balls
   * and between a ball and a wall while the gap g is below the resolved gap g_r:
   *
   *   F_i = −(C(g) − C(g + s(g))) v_n n,  v_n = (V_i − V_j)·n,  s(g) = s_0 (1 − g/g_r),
   *
   * with the leading term of lubrication theory for the reduced radius
   * a* = a_i a_j/(a_i + a_j) (a* = a_i at a wall): C(g) = 6π μ a*²/g for spheres
   * (Cox & Brenner 1967) and C(g) = 3√2 π μ (a* / g)^{3/2} for cylinders, per unit length.
   * The resolved flow of a gap below about a cell carries the squeeze force of a wider
   * gap g + s (doc/particles.md, 'Lubrication'); the correction adds what that misses, so
   * nothing is counted twice. The shift s_0 depends on the mesh; it tapers to zero at g_r,
   * where the resolved force has converged. Below the minimum gap (surface roughness) C
   * stays at its value there, so the force stays finite. It is implicit like the contact
   * forces (NormalContact). Prescribed and fixed balls feel it in their contact force.
   */
  template <int dim>
  class Lubrication : public ParticleInteraction<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm) override;

    /// Resolve the 'auto' lengths from the finest cell edge and take the viscosity.
    void initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                    const ParticleSet<dim> &particles, const double finest_cell_size) override;

    bool enabled() const override { return on; }
    /// Spheres and disks only.
    void check_scene(const ParticleSet<dim> &particles) const override;

    /// Subtract the correction at X^{n+1}(V), V from the force-balance rows of the free
    /// balls, its derivative from D (if given), and add it to every ball's contact_force.
    void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                              Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const override;

    /// The correction's law at gap g and normal relative velocity v_n, for reduced radius
    /// a*, between two balls (pair) or a ball and a wall.
    NormalLawValue law(const double reduced_radius, const bool pair, const double gap,
                       const double normal_velocity) const;

    /**
     * The 'auto' shift s_0 = shift_fraction a*, fitted to the resolved force on a ball
     * approaching a wall (benchmarks/lubrication_wall.py, doc/particles.md). Below a cell
     * the fitted shift hardly depends on the gap or on the mesh, so one fraction of the
     * radius serves every mesh, in 2D and 3D.
     */
    static constexpr double shift_fraction = 0.033;
    /**
     * The 'auto' shift between two balls, s_0 = pair_shift_cells h (h the finest cell
     * edge), fitted to two equal balls approaching each other (benchmarks/
     * lubrication_pair.py, doc/particles.md): their resolved force below a cell is far
     * lower than at a wall, because one Q2 velocity has to turn from +U to −U across the
     * gap, and the shift is about a cell at every gap below a cell, better fitted in cells
     * than as a fraction of a*. Each value minimises the largest error against Brenner's
     * exact series (3D) or a fine-mesh reference (2D).
     */
    static constexpr double pair_shift_cells = (dim == 3 ? 0.97 : 0.85);
    /// The resolved gap of 'auto', in finest cell edges: from three cells up the resolved
    /// drag has converged (within 1–3 % of Brenner's, with or without the correction).
    static constexpr double resolved_gap_cells = 3.0;
    /// The minimum gap of 'auto', relative to the reduced radius: a roughness of 0.1 %
    /// keeps the force finite where the balls would touch.
    static constexpr double minimum_gap_fraction = 1e-3;

  private:
    bool                  on = false;
    std::optional<double> resolved_entry, minimum_entry, shift_entry;
    double                resolved_gap = 0, viscosity = 0, finest_cell = 0;
    Box<dim>           domain;
    std::unique_ptr<PairSearch<dim>> search;

    /// C(g) and C'(g) for reduced radius a*, g clamped to the minimum gap.
    std::pair<double, double> coefficient(const double reduced_radius, const double gap) const;
    double                    minimum_gap(const double reduced_radius) const;
    /// s_0 for reduced radius a*, between two balls (pair) or at a wall.
    double gap_shift(const double reduced_radius, const bool pair) const;
  };
} // namespace fdparticle

#endif
