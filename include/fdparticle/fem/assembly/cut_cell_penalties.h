#ifndef fdparticle_fem_assembly_cut_cell_penalties_h
#define fdparticle_fem_assembly_cut_cell_penalties_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/assembly_term.h>
#include <fdparticle/particles/particle_set.h>

#include <utility>

namespace fdparticle
{
  /**
   * The two penalties on the fluid part of cut cells, added to the rigidity rows (F3)
   * (doc/method.md §3, §4):
   *   fluid penalty   s κ²/(α + μ/R²) ∫ λ·η           (the seed's weak λ = 0 in the fluid)
   *   strain penalty  s_e μ ∫ 2 ε(λ):ε(η)              (only in cells owning particle points)
   * both scaled by θ/θ_0 below the penalty ramp θ_0 of the cell's particle fraction θ.
   * Parameters Multiplier/Fluid penalty, Strain penalty, Penalty ramp.
   */
  template <int dim>
  class CutCellPenalties : public AssemblyTerm<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    CutCellPenalties(const Fluid<dim> &fluid, const ParticleSet<dim> &particles)
      : fluid(fluid)
      , particles(particles)
    {}
    void assemble_point(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;
    void assemble_cell_matrix(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;

  private:
    /// The fluid and strain weights of a fluid point of weight JxW whose nearest surface is
    /// that of particle nearest_surface.
    std::pair<double, double> weights(const AssemblyScratch<dim> &s,
                                      const unsigned int nearest_surface, const double JxW) const;

    const Fluid<dim> &      fluid;
    const ParticleSet<dim> &particles;
    double                  fluid_penalty = 0.01;
    double                  strain_penalty = 0.15;
    double                  penalty_ramp = 0.2;
  };
} // namespace fdparticle

#endif
