#ifndef fdparticle_particles_shape_h
#define fdparticle_particles_shape_h

#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The geometry of a rigid particle about its centre, in the particle's frame: what the
   * cut-cell rules, the refinement band, the cell list, the particle equations and the
   * contact models ask of a particle's shape. Offsets r = x − X are given to the nearest
   * periodic image already (Particle::offset). A new shape (an ellipsoid, say) derives
   * from this class and is created where particles are read (ParticleSet, ParticleFile,
   * RandomPacking); the rest of the code asks these questions only.
   *
   * Contacts and lubrication see every particle as its bounding ball (exact for a sphere).
   */
  template <int dim>
  class Shape
  {
  public:
    virtual ~Shape() = default;

    /// Points closer to the surface than this fraction of the size count as on it. A
    /// mesh vertex that lies on the surface in exact arithmetic (a centre on a vertex and
    /// a radius of whole cells, as scenes are often set up) falls on either side by
    /// round-off, and differently from its mirror image: cells would become cut or not
    /// (penalties, multiplier DoFs) at random, and a sphere on the axis of a symmetric
    /// box would drift sideways (tests/symmetry_vertex_3d.prm). Far above round-off
    /// (10⁻¹⁶), far below anything a mesh resolves.
    static constexpr double surface_tolerance = 1e-10;

    /// The shape's name as the parameter files and messages spell it.
    virtual std::string name() const = 0;

    /// Radius of the smallest ball about the centre that holds the shape: how far from
    /// the centre a cell, a bin or a wall must be to be sure to miss it.
    virtual double bounding_radius() const = 0;
    /// Radius of the largest ball about the centre that the shape holds: a box within it
    /// lies inside the shape.
    virtual double inscribed_radius() const = 0;

    /// |P|: area (2D) or volume (3D).
    virtual double volume() const = 0;
    /// J/ρ: the moment of inertia per unit density about any axis through the centre
    /// (doc/method.md §0 (F5)).
    virtual double inertia() const = 0;

    /// Whether the point at offset r lies in the shape, its surface included within
    /// surface_tolerance.
    virtual bool contains(const Tensor<1, dim> &r) const = 0;
    /// Signed distance from the point at offset r to the surface, negative inside.
    virtual double surface_distance(const Tensor<1, dim> &r) const = 0;

    /// A smooth level set of the shape centred at X, negative inside and zero on the
    /// surface, with gradient and Hessian (the level-set cut-cell rules, doc/method.md §7).
    virtual std::unique_ptr<Function<dim>> level_set(const Point<dim> &X) const = 0;
  };
} // namespace fdparticle

#endif
