#ifndef fdparticle_base_fluid_h
#define fdparticle_base_fluid_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

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

    /// The directions in which the box is periodic (copied from Domain): the pressure is
    /// periodic there, so ρ_f g + f along them drives the flow and no pressure balances it.
    std::array<bool, dim> periodic{};

    /// ρ_f g + f: the force per volume on the fluid at rest.
    Tensor<1, dim> hydrostatic_gradient() const { return density * gravity + body_force; }
    /// The hydrostatic pressure at x, zero at x_ref: (ρ_f g + f)·(x − x_ref) over the
    /// wall-bounded directions. A periodic pressure has no part along a periodic direction,
    /// and must not: inside a ball across a periodic face the interior-pressure penalty
    /// (doc/method.md §4) would aim at values a whole period's drop apart.
    double hydrostatic_pressure(const Point<dim> &x, const Point<dim> &x_ref) const
    {
      const Tensor<1, dim> G = hydrostatic_gradient();
      double               p = 0;
      for (unsigned int d = 0; d < dim; ++d)
        if (!periodic[d])
          p += G[d] * (x[d] - x_ref[d]);
      return p;
    }
  };
} // namespace fdparticle

#endif
