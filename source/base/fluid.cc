#include <fdparticle/base/fluid.h>
#include <fdparticle/base/parameter_tools.h>

namespace fdparticle
{
  template <int dim>
  void Fluid<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Gravity", "0, -10, 0", Patterns::Anything(),
                      "Gravitational acceleration g, Dimension comma-separated numbers.");
    prm.enter_subsection("Fluid");
    {
      prm.declare_entry("Density", "1", Patterns::Anything(), "Fluid density rho_f > 0.");
      prm.declare_entry("Viscosity", "1", Patterns::Anything(), "Dynamic viscosity mu > 0.");
      prm.declare_entry("Convection", "true", Patterns::Bool(),
                        "true: Navier-Stokes (Newton); false: Stokes (one linear solve a step).");
      prm.declare_entry("Body force", "", Patterns::Anything(),
                        "Uniform force per unit volume on the whole box, e.g. a mean pressure "
                        "gradient driving a periodic box (Dimension numbers; empty: none).");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Fluid<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    gravity = get_tensor<dim>(prm, "Gravity", "Gravity");
    prm.enter_subsection("Fluid");
    {
      density = to_double(prm.get("Density"), "Fluid/Density");
      viscosity = to_double(prm.get("Viscosity"), "Fluid/Viscosity");
      AssertThrow(density > 0,
                  ExcMessage("Parameter 'Fluid/Density' must be positive, got " +
                             prm.get("Density") + "."));
      AssertThrow(viscosity > 0,
                  ExcMessage("Parameter 'Fluid/Viscosity' must be positive, got " +
                             prm.get("Viscosity") + "."));
      convection = prm.get_bool("Convection");
      body_force = trim(prm.get("Body force")).empty() ?
                     Tensor<1, dim>() :
                     get_tensor<dim>(prm, "Body force", "Fluid/Body force");
    }
    prm.leave_subsection();
  }

  template struct Fluid<2>;
  template struct Fluid<3>;
} // namespace fdparticle
