#ifndef fdparticle_fem_introspection_h
#define fdparticle_fem_introspection_h

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_dgp.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values_extractors.h>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The one place that knows the layout of the finite element (doc/method.md §1): the
   * fields (u, λ, p), their vector components, their degrees, and the quadrature and output
   * resolution those degrees call for. Everything else asks here instead of writing 0, dim,
   * 2·dim or a degree out.
   */
  template <int dim>
  struct Introspection
  {
    /// The three fields of the (u, λ, p) system.
    enum class Field
    {
      velocity,
      multiplier,
      pressure
    };

    /// u and λ are continuous Q2 (the seed's pair; λ needs the velocity's space for the
    /// pairing), p discontinuous P1: the inf-sup stable Q2/P1disc pair.
    static constexpr unsigned int velocity_degree = 2;
    static constexpr unsigned int pressure_degree = 1;

    /// First vector component of each field; the pressure is the last component.
    static constexpr unsigned int first_velocity_component = 0;
    static constexpr unsigned int first_multiplier_component = dim;
    static constexpr unsigned int pressure_component = 2 * dim;
    static constexpr unsigned int n_components = 2 * dim + 1;

    static Field field(const unsigned int component)
    {
      return component < first_multiplier_component ?
               Field::velocity :
               (component < pressure_component ? Field::multiplier : Field::pressure);
    }

    static FESystem<dim> finite_element()
    {
      return FESystem<dim>(FE_Q<dim>(velocity_degree), dim, FE_Q<dim>(velocity_degree), dim,
                           FE_DGP<dim>(pressure_degree), 1);
    }

    static FEValuesExtractors::Vector velocities()
    {
      return FEValuesExtractors::Vector(first_velocity_component);
    }
    static FEValuesExtractors::Vector multipliers()
    {
      return FEValuesExtractors::Vector(first_multiplier_component);
    }
    static FEValuesExtractors::Scalar pressure()
    {
      return FEValuesExtractors::Scalar(pressure_component);
    }

    /// Gauss rule of a cell away from the particles: degree + 1 points a direction
    /// integrate the mass matrix of Q2 exactly on the (affine) cells of the box.
    static QGauss<dim> cell_quadrature() { return QGauss<dim>(velocity_degree + 1); }

    /// Subdivisions of a cell in the output: one per polynomial degree shows Q2 as it is.
    static constexpr unsigned int output_subdivisions = velocity_degree;
  };
} // namespace fdparticle

#endif
