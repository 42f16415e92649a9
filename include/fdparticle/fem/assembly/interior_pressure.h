#ifndef fdparticle_fem_assembly_interior_pressure_h
#define fdparticle_fem_assembly_interior_pressure_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/fem/assembly/assembly_term.h>

namespace fdparticle
{
  /**
   * −(δ/μ) ∫ (p − p_hydrostatic) q in the cells lying inside a particle (doc/method.md §3,
   * §4): inside a rigid body p and λ are determined only together, and this picks the
   * hydrostatic pressure there. Parameter Multiplier/Interior pressure penalty (δ).
   */
  template <int dim>
  class InteriorPressure : public AssemblyTerm<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    explicit InteriorPressure(const Fluid<dim> &fluid)
      : fluid(fluid)
    {}
    void assemble_point(const AssemblyScratch<dim> &s, AssemblyCopy<dim> &copy) const override;

    /// Whether the term acts at all (δ > 0): then it fixes the pressure level wherever a
    /// cell lies inside a particle.
    bool enabled() const { return penalty > 0; }
    /// The point where the hydrostatic pressure is zero (the pressure level's cell centre).
    void set_reference_point(const Point<dim> &x) { reference_point = x; }

  private:
    const Fluid<dim> &fluid;
    double            penalty = 1e-3;
    Point<dim>        reference_point;
  };
} // namespace fdparticle

#endif
