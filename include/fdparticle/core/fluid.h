#ifndef fdparticle_core_fluid_h
#define fdparticle_core_fluid_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Properties of the Newtonian fluid (subsection Fluid) and the gravity vector (top level,
   * because particles feel it too).
   */
  template <int dim>
  struct Fluid
  {
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    double         density = 1;
    double         viscosity = 1;
    bool           convection = true;
    /// Uniform force per unit volume on the whole box (e.g. a mean pressure gradient).
    Tensor<1, dim> body_force;
    Tensor<1, dim> gravity;

    /// ρ_f g + f: the gradient of the hydrostatic pressure.
    Tensor<1, dim> hydrostatic_gradient() const { return density * gravity + body_force; }
    /// The hydrostatic pressure at x, zero at x_ref: (ρ_f g + f)·(x − x_ref).
    double hydrostatic_pressure(const Point<dim> &x, const Point<dim> &x_ref) const
    {
      return hydrostatic_gradient() * (x - x_ref);
    }
  };
} // namespace fdparticle

#endif
