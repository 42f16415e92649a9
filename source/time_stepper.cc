#include <fdparticle/parameter_tools.h>
#include <fdparticle/time_stepper.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  void TimeStepper::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    {
      prm.declare_entry("End time", "1", Patterns::Anything(), "Final time of the run (>= 0).");
      prm.declare_entry("Time step", "0.1", Patterns::Anything(), "Time step Delta t > 0.");
      prm.declare_entry("Scheme", "BDF2", Patterns::Anything(),
                        "BDF1 (implicit Euler) or BDF2 (second order; its first step is BDF1).");
    }
    prm.leave_subsection();
  }

  void TimeStepper::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Time");
    {
      t_end = to_double(prm.get("End time"), "Time/End time");
      dt_requested = to_double(prm.get("Time step"), "Time/Time step");
      AssertThrow(dt_requested > 0,
                  ExcMessage("Parameter 'Time/Time step' must be positive, got " +
                             prm.get("Time step") + "."));
      AssertThrow(t_end >= 0, ExcMessage("Parameter 'Time/End time' must not be negative."));
      const std::string scheme = trim(prm.get("Scheme"));
      AssertThrow(scheme == "BDF1" || scheme == "BDF2",
                  ExcMessage("Parameter 'Time/Scheme': unknown scheme '" + scheme +
                             "' (use BDF1 or BDF2)."));
      max_order = (scheme == "BDF2" ? 2 : 1);
    }
    prm.leave_subsection();
  }

  unsigned int TimeStepper::order() const
  {
    return (step == 0 ? 1 : max_order);
  }

  double TimeStepper::next_step() const
  {
    return std::min(dt_requested, t_end - t);
  }

  bool TimeStepper::finished() const
  {
    // A remainder below 1e-9 of a step is round-off in the accumulated time, not a step.
    return t_end - t <= 1e-9 * dt_requested;
  }

  std::array<double, 3> TimeStepper::coefficients() const
  {
    const double dt = next_step();
    if (order() == 1)
      return {{1.0 / dt, -1.0 / dt, 0.0}};
    const double w = dt / dt_previous;
    return {{(1 + 2 * w) / (1 + w) / dt, -(1 + w) / dt, w * w / (1 + w) / dt}};
  }

  void TimeStepper::advance()
  {
    const double dt = next_step();
    t = (t_end - t - dt <= 1e-9 * dt_requested) ? t_end : t + dt;
    dt_previous = dt;
    ++step;
  }
} // namespace fdparticle
