#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_file.h>
#include <fdparticle/particles/random_packing.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/ellipsoid.h>
#include <fdparticle/particles/sphere.h>

#include <algorithm>
#include <sstream>
#include <iomanip>
#include <istream>
#include <ostream>

namespace fdparticle
{
  template <int dim>
  void ParticleSet<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Particles");
    {
      prm.declare_entry("Particles", "", Patterns::Anything(),
                        "';'-separated entries 'x, y, z : shape : density [: motion]' (2D: 'x, y "
                        ": ...'). shape = a radius (sphere, disk), 'ellipsoid a, b, c [, ax, ay, "
                        "az, angle]' (3D: semi-axes along the body axes, the body turned by angle "
                        "degrees about the axis) or 'ellipse a, b [, angle]' (2D: the a axis at "
                        "angle degrees from x). motion = free (default), fixed, or 'prescribed : "
                        "vx, vy, vz [: wx, wy, wz]' (constant velocity and angular velocity; 2D: "
                        "'vx, vy [: wz]'). Empty: no particles besides Particle file and Random "
                        "particles.");
      prm.declare_entry("Particle file", "", Patterns::Anything(),
                        "CSV file of more particles, one per line: 'x, y[, z], radius, "
                        "density[, motion[, vx, vy[, vz][, angular velocity]]]' (motion as "
                        "in Particles; the radius may be a shape as in Particles with spaces "
                        "between its numbers, 'ellipse 0.2 0.1 30'); '#' comments and a "
                        "header line are skipped. A relative path starts in the directory "
                        "fdparticle runs in.");
      RandomPacking<dim>::declare_parameters(prm);
      prm.declare_entry("Angular velocity closure", "torque balance",
                        Patterns::Selection("torque balance|kinematic"),
                        "torque balance: (rho_k - rho_f) J dw/dt + <lambda, theta x r> = 0; "
                        "kinematic: the seed's |P| w = 1/2 int_P curl u.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void read_shape(const std::string &field, const std::string &name, Particle<dim> &p)
  {
    using namespace ParameterTools;
    const std::string text = trim(field);
    const std::string word = text.substr(0, text.find_first_of(" \t"));
    if (word != "ellipse" && word != "ellipsoid")
      {
        const double radius = to_double(text, name + " radius");
        AssertThrow(radius > 0, ExcMessage("Parameter '" + name +
                                           "': the radius must be positive, got " +
                                           field + "."));
        p.shape = std::make_shared<const Sphere<dim>>(radius);
        return;
      }
    const std::string form = dim == 2 ? "'ellipse a, b [, angle in degrees]'" :
                                        "'ellipsoid a, b, c [, axis x, y, z, angle in degrees]'";
    AssertThrow(word == (dim == 2 ? "ellipse" : "ellipsoid"),
                ExcMessage("Parameter '" + name + "': " + (dim == 2 ? "a 2D" : "a 3D") +
                           " scene has no " + word + "; the shape is a radius or " + form +
                           "."));
    std::vector<double> values;
    std::string         numbers = text.substr(word.size());
    std::replace(numbers.begin(), numbers.end(), ',', ' ');
    std::istringstream in(numbers);
    for (std::string v; in >> v;)
      values.push_back(to_double(v, name + " " + word));
    const unsigned int n_angle = (dim == 2 ? 1 : 4);
    AssertThrow(values.size() == dim || values.size() == dim + n_angle,
                ExcMessage("Parameter '" + name + "': '" + text + "' is not of the form " +
                           form + "."));
    Tensor<1, dim> axes;
    for (unsigned int d = 0; d < dim; ++d)
      axes[d] = values[d];
    p.shape = std::make_shared<const Ellipsoid<dim>>(axes, name);
    if (values.size() == dim)
      return;
    Eigen::Vector3d axis(0, 0, 1);
    if (dim == 3)
      axis = Eigen::Vector3d(values[3], values[4], values[5]);
    AssertThrow(axis.norm() > 0,
                ExcMessage("Parameter '" + name + "': the axis of the rotation is zero."));
    p.orientation = Eigen::Quaterniond(
      Eigen::AngleAxisd(values.back() * numbers::PI / 180, axis.normalized()));
    p.orientation_old = p.orientation;
  }

  namespace
  {
    /// A particle from the fields of one entry (a Particles/Particles entry or a line of
    /// the particle file): centre, radius, density[, motion[, velocity[, angular
    /// velocity]]]; 'name' says where the entry came from in error messages.
    template <int dim>
    Particle<dim> make_particle(const std::vector<std::string> &fields, const std::string &name,
                                const std::string &form)
    {
      using namespace ParameterTools;
      Particle<dim> p;
      p.position = Point<dim>(to_tensor<dim>(fields[0], name + " centre"));
      read_shape(fields[1], name, p);
      p.density = to_double(fields[2], name + " density");
      AssertThrow(p.density > 0, ExcMessage("Parameter '" + name +
                                            "': the density must be positive, got " +
                                            fields[2] + "."));
      if (fields.size() >= 4)
        {
          const std::string &motion = fields[3];
          AssertThrow(motion == "free" || motion == "fixed" || motion == "prescribed",
                      ExcMessage("Parameter '" + name + "': motion '" + motion +
                                 "' is not 'free', 'fixed' or 'prescribed'."));
          AssertThrow((motion == "prescribed") == (fields.size() >= 5),
                      ExcMessage("Parameter '" + name + "': " +
                                 (motion == "prescribed" ?
                                    "'prescribed' needs a velocity after it" :
                                    "only 'prescribed' takes a velocity") +
                                 "; the form is " + form + "."));
          p.motion = (motion == "fixed"      ? ParticleMotion::fixed :
                      motion == "prescribed" ? ParticleMotion::prescribed :
                                               ParticleMotion::free);
        }
      if (p.motion == ParticleMotion::prescribed)
        {
          // Given (V, ω) are held in the velocity histories, so the BDF formula of
          // finish_step() moves the ball with V exactly (constant V) and the assembler
          // sees them as it sees a solved-for velocity.
          p.velocity = to_tensor<dim>(fields[4], name + " velocity");
          if (fields.size() == 6)
            {
              const Tensor<1, RigidBody<dim>::n_rotations> w =
                to_tensor<RigidBody<dim>::n_rotations>(fields[5], name + " angular velocity");
              for (unsigned int j = 0; j < RigidBody<dim>::n_rotations; ++j)
                p.omega[RigidBody<dim>::rotation_component(j)] = w[j];
            }
          p.velocity_old = p.velocity_old2 = p.velocity;
          p.omega_old = p.omega_old2 = p.omega;
        }
      p.position_old = p.position;
      p.place(p.position, p.orientation);
      return p;
    }
  } // namespace

  template <int dim>
  std::vector<Point<dim>> Particle<dim>::centres_near(const BoundingBox<dim> &box,
                                                    const double reach) const
  {
    // Per direction, the shifts k with lo − reach < X + k L < hi + reach; then the
    // combinations within reach in all directions together.
    std::array<std::vector<double>, dim> coordinates;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double lo = box.lower_bound(d) - reach, hi = box.upper_bound(d) + reach;
        const double c = geometry_center[d];
        if (period[d] > 0)
          for (double k = std::floor((lo - c) / period[d]) + 1; c + k * period[d] < hi; ++k)
            coordinates[d].push_back(c + k * period[d]);
        else if (c > lo && c < hi)
          coordinates[d].push_back(c);
        if (coordinates[d].empty())
          return {};
      }
    std::vector<Point<dim>>       result;
    std::array<std::size_t, dim> choice{};
    for (;;)
      {
        Point<dim> X;
        for (unsigned int d = 0; d < dim; ++d)
          X[d] = coordinates[d][choice[d]];
        if (distance(box, X) < reach)
          result.push_back(X);
        unsigned int d = 0;
        while (d < dim && ++choice[d] == coordinates[d].size())
          choice[d++] = 0;
        if (d == dim)
          break;
      }
    return result;
  }

  template <int dim>
  void ParticleSet<dim>::parse_parameters(ParameterHandler &prm, const Box<dim> &domain,
                                          const MPI_Comm comm)
  {
    using namespace ParameterTools;
    particles.clear();
    std::string       file;
    RandomPacking<dim> random;
    prm.enter_subsection("Particles");
    {
      angular_closure = (prm.get("Angular velocity closure") == "kinematic" ?
                           AngularVelocityClosure::kinematic :
                           AngularVelocityClosure::torque_balance);
      const std::string list = prm.get("Particles");
      if (!trim(list).empty())
        for (const std::string &entry : split(list, ';'))
          {
            const std::string name =
              "Particles/Particles (entry " + std::to_string(particles.size() + 1) + ")";
            AssertThrow(!entry.empty(),
                        ExcMessage("Parameter '" + name +
                                   "' is empty; entries are 'x, y[, z] : shape : density'."));
            const std::vector<std::string> fields = split(entry, ':');
            const std::string form = "'centre : shape : density [: free | fixed | "
                                     "prescribed : velocity [: angular velocity]]'";
            AssertThrow(fields.size() >= 3 && fields.size() <= 6,
                        ExcMessage("Parameter '" + name + "': '" + entry +
                                   "' is not of the form " + form + "."));
            particles.push_back(make_particle<dim>(fields, name, form));
          }
      file = trim(prm.get("Particle file"));
      random.parse_parameters(prm, domain);
    }
    prm.leave_subsection();

    if (!file.empty())
      for (const auto &entry : ParticleFile<dim>::read(file, comm))
        particles.push_back(make_particle<dim>(entry.fields, entry.name,
                                               "'" + ParticleFile<dim>::line_form() + "'"));
    // Random particles avoid the listed ones; they are checked with them below.
    for (const Particle<dim> &p : random.place(particles))
      particles.push_back(p);
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        particles[k].id     = k;
        particles[k].period = domain.period();
      }

    check_positions(domain, 0.0);
    this->domain = domain;
    // A centre on the upper face of a periodic direction is the same ball as on the lower.
    for (Particle<dim> &p : particles)
      {
        wrap(p);
        p.place(p.position, p.orientation);
      }
    update_index();

    n_block_unknowns = 0;
    for (Particle<dim> &p : particles)
      if (p.motion == ParticleMotion::free)
        {
          p.first_unknown = n_block_unknowns;
          n_block_unknowns += RigidBody<dim>::n_unknowns;
        }
  }

  template <int dim>
  void ParticleSet<dim>::check_positions(const Box<dim> &domain, const double time) const
  {
    const std::string when = (time == 0.0 ? "" : " at t = " + std::to_string(time));
    // The centre must lie in the box (on a periodic face it may). In a wall-bounded
    // direction the ball may not touch the wall; in a periodic direction it crosses the
    // faces freely (its images, doc/method.md §12) but must be narrower than the period,
    // or it would overlap its own image.
    // The particles as they are now (the step's geometry may have been a prediction).
    std::vector<Particle<dim>> now(particles);
    for (Particle<dim> &p : now)
      p.place(p.position, p.orientation);
    for (const Particle<dim> &p : now)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double      lower = domain.lower_corner()[d], upper = domain.upper_corner()[d];
          const std::string what = "Particle " + std::to_string(p.id) + " (centre " +
                                   std::string(1, "xyz"[d]) + " = " +
                                   std::to_string(p.position[d]) +
                                   ", radius " + std::to_string(p.bounding_radius()) + ")";
          if (domain.is_periodic(d))
            {
              AssertThrow(time > 0.0 || (p.position[d] >= lower && p.position[d] <= upper),
                          ExcMessage(what + " lies outside the box."));
              AssertThrow(2 * p.bounding_radius() < upper - lower,
                          ExcMessage(what + " is wider than the periodic box in " +
                                     std::string(1, "xyz"[d]) +
                                     " and would overlap its own periodic image."));
              continue;
            }
          AssertThrow(time > 0.0 || (p.position[d] > lower && p.position[d] < upper),
                      ExcMessage(what + " lies outside the box."));
          Tensor<1, dim> e;
          e[d] = 1;
          AssertThrow(p.position[d] - p.extent(-e) > lower && p.position[d] + p.extent(e) < upper,
                      ExcMessage(what + " overlaps a wall of the box" + when +
                                 (time == 0.0 ? "." : " (see subsection Wall repulsion).")));
        }
    std::vector<Point<dim>> x;
    std::vector<double>     r;
    for (const Particle<dim> &p : particles)
      {
        x.push_back(p.position);
        r.push_back(p.bounding_radius());
      }
    // Bounding balls that overlap, then the shapes themselves.
    for (const auto &pair : PairSearch<dim>(domain).pairs(x, r, 0.0))
      AssertThrow(ContactGeometry<dim>::pair(now[pair.i], now[pair.j], pair.offset).gap >= 0,
                  ExcMessage("Particles " + std::to_string(pair.i) + " and " +
                             std::to_string(pair.j) + " overlap" + when +
                             (time == 0.0 ? "." : " (see subsection Collisions).")));
  }

  template <int dim>
  Tensor<1, 3> ParticleSet<dim>::mean_free_velocity() const
  {
    Tensor<1, 3> sum;
    unsigned int n_free = 0;
    for (const Particle<dim> &p : particles)
      if (p.motion == ParticleMotion::free)
        {
          for (unsigned int d = 0; d < dim; ++d)
            sum[d] += p.velocity[d];
          ++n_free;
        }
    return n_free > 0 ? sum / n_free : sum;
  }

  template <int dim>
  int ParticleSet<dim>::locate(const Point<dim> &x) const
  {
    Assert(index_is_current(), ExcMessage("The particle index is out of date."));
    int owner = -1;
    // A ball containing x has its centre within R_max of x: in x's bin or an adjacent one.
    index->for_each_near(x, [&](const unsigned int k) {
      if ((owner < 0 || int(k) < owner) && particles[k].contains(x))
        owner = k;
    });
    return owner;
  }

  template <int dim>
  std::vector<unsigned int> ParticleSet<dim>::meeting(const BoundingBox<dim> &box) const
  {
    Assert(index_is_current(), ExcMessage("The particle index is out of date."));
    // A ball meeting the box has its centre within R_max of it; past a periodic face the
    // index wraps around, where the images of the balls on the other side are.
    Point<dim> lower = box.get_boundary_points().first, upper = box.get_boundary_points().second;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lower[d] -= largest_radius;
        upper[d] += largest_radius;
      }
    std::vector<unsigned int> result;
    index->for_each_in_box(lower, upper, [&](const unsigned int k) {
      if (particles[k].meets(box))
        result.push_back(k);
    });
    std::sort(result.begin(), result.end());
    return result;
  }

  template <int dim>
  void ParticleSet<dim>::update_index()
  {
    static std::uint64_t last_revision = 0;
    revision = ++last_revision;
    largest_radius = 0;
    for (const Particle<dim> &p : particles)
      largest_radius = std::max(largest_radius, p.bounding_radius());
    // Without balls any width does: one bin across the box.
    index.emplace(domain, largest_radius > 0 ?
                            2 * largest_radius :
                            (domain.upper_corner() - domain.lower_corner()).norm());
    indexed_centres.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        index->insert(k, particles[k].geometry_center);
        indexed_centres[k] = particles[k].geometry_center;
      }
  }

  template <int dim>
  bool ParticleSet<dim>::index_is_current() const
  {
    if (!index || indexed_centres.size() != particles.size())
      return false;
    for (unsigned int k = 0; k < particles.size(); ++k)
      if (indexed_centres[k] != particles[k].geometry_center)
        return false;
    return true;
  }

  template <int dim>
  void ParticleSet<dim>::prepare_step(const TimeStepper &time)
  {
    // The orientation as the centre: q^n (BDF1), or q^n turned on by the last step's
    // rotation scaled to the coming step (the extrapolation of TimeStepper::extrapolate).
    const double w = time.order() == 1 ? 0.0 : time.next_step() / time.previous_step();
    for (Particle<dim> &p : particles)
      p.place(time.extrapolate(p.position, p.position_old),
              w == 0.0 ? p.orientation :
                         RigidBody<dim>::rotate(p.orientation, p.last_rotation(), w));
    update_index();
  }

  template <int dim>
  void ParticleSet<dim>::extrapolate_velocities(const TimeStepper &time)
  {
    for (Particle<dim> &p : particles)
      if (p.first_unknown != numbers::invalid_unsigned_int)
        {
          p.velocity = time.extrapolate(p.velocity_old, p.velocity_old2);
          p.omega    = time.extrapolate(p.omega_old, p.omega_old2);
        }
  }

  template <int dim>
  void ParticleSet<dim>::set_unknowns(const Eigen::VectorXd &y)
  {
    AssertDimension(y.size(), n_block_unknowns);
    for (Particle<dim> &p : particles)
      if (p.first_unknown != numbers::invalid_unsigned_int)
        {
          for (unsigned int d = 0; d < dim; ++d)
            p.velocity[d] = y[p.first_unknown + d];
          for (unsigned int j = 0; j < RigidBody<dim>::n_rotations; ++j)
            p.omega[RigidBody<dim>::rotation_component(j)] = y[p.first_unknown + dim + j];
        }
  }

  template <int dim>
  Eigen::VectorXd ParticleSet<dim>::get_unknowns() const
  {
    Eigen::VectorXd y(n_block_unknowns);
    for (const Particle<dim> &p : particles)
      if (p.first_unknown != numbers::invalid_unsigned_int)
        {
          for (unsigned int d = 0; d < dim; ++d)
            y[p.first_unknown + d] = p.velocity[d];
          for (unsigned int j = 0; j < RigidBody<dim>::n_rotations; ++j)
            y[p.first_unknown + dim + j] = p.omega[RigidBody<dim>::rotation_component(j)];
        }
    return y;
  }

  template <int dim>
  void ParticleSet<dim>::finish_step(const TimeStepper &time)
  {
    const auto c = time.coefficients();
    for (Particle<dim> &p : particles)
      {
        // BDF formula for dX/dt = V (Euler for BDF1, as the seed's eq. 3.19).
        // A prescribed particle moves with its constant V; the history then holds V too.
        const Point<dim> x_new = p.position_after_step(c);
        p.position_old = p.position;
        p.position = x_new;
        wrap(p);
        // The BDF formula for dθ/dt = ω on the rotation vector of the step, δ^{n+1} =
        // (ω^{n+1} + c2 δ^n)/c0 (c0 + c1 + c2 = 0): δ = Δt ω for BDF1, the analogue of
        // X^{n+1} for BDF2.
        const Tensor<1, 3> turn = (p.omega + c[2] * p.last_rotation()) / c[0];
        p.orientation_old = p.orientation;
        p.orientation = RigidBody<dim>::rotate(p.orientation, turn, 1.0);
        p.velocity_old2 = p.velocity_old;
        p.velocity_old = p.velocity;
        p.omega_old2 = p.omega_old;
        p.omega_old = p.omega;
      }
  }

  template <int dim>
  void ParticleSet<dim>::wrap(Particle<dim> &p) const
  {
    // X^n and X^{n−1} move together, so the BDF formula and the extrapolation of the next
    // step see the same motion. The geometry centre of the step just taken stays: every
    // geometric question is asked of all images.
    for (unsigned int d = 0; d < dim; ++d)
      if (p.period[d] > 0)
        {
          const double shift =
            p.period[d] * std::floor((p.position[d] - domain.lower_corner()[d]) / p.period[d]);
          p.position[d] -= shift;
          p.position_old[d] -= shift;
        }
  }

  template <int dim>
  void ParticleSet<dim>::save(std::ostream &out) const
  {
    out << std::setprecision(17);
    for (const Particle<dim> &p : particles)
      {
        for (const auto *t : {&p.position, &p.position_old})
          for (unsigned int d = 0; d < dim; ++d)
            out << (*t)[d] << ' ';
        for (const auto *t : {&p.velocity, &p.velocity_old, &p.velocity_old2, &p.force,
                              &p.contact_force})
          for (unsigned int d = 0; d < dim; ++d)
            out << (*t)[d] << ' ';
        for (const auto *t : {&p.omega, &p.omega_old, &p.omega_old2, &p.torque})
          for (unsigned int d = 0; d < 3; ++d)
            out << (*t)[d] << ' ';
        for (const auto *o : {&p.orientation, &p.orientation_old})
          {
            const auto &q = o->coeffs();
            out << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << ' ';
          }
        out << '\n';
      }
  }

  template <int dim>
  void ParticleSet<dim>::load(std::istream &in)
  {
    for (Particle<dim> &p : particles)
      {
        for (auto *t : {&p.position, &p.position_old})
          for (unsigned int d = 0; d < dim; ++d)
            in >> (*t)[d];
        for (auto *t : {&p.velocity, &p.velocity_old, &p.velocity_old2, &p.force,
                        &p.contact_force})
          for (unsigned int d = 0; d < dim; ++d)
            in >> (*t)[d];
        for (auto *t : {&p.omega, &p.omega_old, &p.omega_old2, &p.torque})
          for (unsigned int d = 0; d < 3; ++d)
            in >> (*t)[d];
        for (auto *o : {&p.orientation, &p.orientation_old})
          {
            auto &q = o->coeffs();
            in >> q[0] >> q[1] >> q[2] >> q[3];
          }
        p.place(p.position, p.orientation);
      }
    update_index();
  }

  template struct Particle<2>;
  template struct Particle<3>;
  template void read_shape<2>(const std::string &, const std::string &, Particle<2> &);
  template void read_shape<3>(const std::string &, const std::string &, Particle<3> &);

  template <int dim>
  void ParticleSet<dim>::declare_columns(StatisticsTable &statistics) const
  {
    statistics.declare_vector("mean_particle_v");
  }

  template <int dim>
  void ParticleSet<dim>::statistics(StatisticsTable &statistics) const
  {
    statistics.set_vector("mean_particle_v", mean_free_velocity());
  }

  template class ParticleSet<2>;
  template class ParticleSet<3>;
} // namespace fdparticle
