#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/base/time_stepper.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <istream>
#include <ostream>
#include <sstream>

namespace fdparticle
{
  void TimeStepper::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    {
      prm.declare_entry("End time", "1", Patterns::Anything(), "Final time of the run (>= 0; 0: set up and write the initial state "
                        "only).");
      prm.declare_entry("Time step", "0.1", Patterns::Anything(),
                        "Time step Delta t > 0. If End time is not a multiple of it, the last "
                        "two steps share the remainder (the run says so at its start).");
      prm.declare_entry("Scheme", "BDF2", Patterns::Anything(),
                        "BDF1 (implicit Euler) or BDF2 (second order; its first step is BDF1).");
      prm.declare_entry("Max time step reductions", "6", Patterns::Anything(),
                        "When Newton fails (no convergence, growing or non-finite residual) the "
                        "step is retried with half the time step, down to 'Time step' / 2^N; "
                        "the step then doubles back to 'Time step' after each accepted step. "
                        "0: no retries, a failure ends the run.");
    }
    prm.leave_subsection();
  }

  void TimeStepper::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Time");
    {
      t_end = get_non_negative(prm, "End time", "Time/End time");
      dt_requested = to_double(prm.get("Time step"), "Time/Time step");
      AssertThrow(dt_requested > 0,
                  ExcMessage("Parameter 'Time/Time step' must be positive, got " +
                             prm.get("Time step") + "."));
      dt_current = dt_requested;
      // Before the run starts: a run of 10^12 steps hangs instead of failing.
      const double n_steps = t_end / dt_requested;
      AssertThrow(n_steps <= max_steps,
                  ExcMessage("Parameters 'Time/End time' = " + prm.get("End time") +
                             " and 'Time/Time step' = " + prm.get("Time step") + " ask for " +
                             format_short(n_steps) + " time steps; fdparticle refuses more than " +
                             format_short(max_steps) +
                             ". Use a larger Time step or a shorter End time."));
      const std::string scheme = trim(prm.get("Scheme"));
      AssertThrow(scheme == "BDF1" || scheme == "BDF2",
                  ExcMessage("Parameter 'Time/Scheme': unknown scheme '" + scheme +
                             "' (use BDF1 or BDF2)."));
      max_order = (scheme == "BDF2" ? 2 : 1);
      const double reductions =
        to_double(prm.get("Max time step reductions"), "Time/Max time step reductions");
      AssertThrow(reductions >= 0 && reductions <= 50 && reductions == std::floor(reductions),
                  ExcMessage("Parameter 'Time/Max time step reductions' must be a whole number "
                             "from 0 to 50, got " + prm.get("Max time step reductions") + "."));
      max_reductions = static_cast<unsigned int>(reductions);
    }
    prm.leave_subsection();
  }

  unsigned int TimeStepper::order() const
  {
    return (step == 0 ? 1 : max_order);
  }

  double TimeStepper::next_step() const
  {
    // Land on the end time without a sliver step: a step of 1/32 after steps of 1 is a
    // legal variable-step BDF2 step, but a needless jolt. Split the last two instead.
    const double remaining = t_end - t;
    if (remaining <= dt_current * (1 + 1e-9))
      return remaining;
    if (remaining < 2 * dt_current * (1 - 1e-9))
      return 0.5 * remaining;
    return dt_current;
  }

  std::string TimeStepper::describe() const
  {
    const double steps = std::floor(t_end / dt_requested * (1 + 1e-12));
    const double rest  = t_end - steps * dt_requested;
    if (rest <= 1e-9 * dt_requested || t_end == 0)
      return "";
    std::ostringstream out;
    out << "Time: End time " << t_end << " is not a multiple of the time step " << dt_requested
        << ": ";
    if (steps == 0)
      out << "the run is one step of " << rest << ".";
    else
      out << "the last two steps are " << 0.5 * (dt_requested + rest) << " each.";
    return out.str();
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
    dt_current = std::min(dt_requested, 2 * dt_current);
    n_reductions = 0;
  }

  bool TimeStepper::reduce_step()
  {
    // The floor is absolute, not per step: a run whose every step fails and whose step
    // regrows in between must not creep down to Δt = 1e-30.
    const double smallest = dt_requested / std::pow(2.0, max_reductions);
    if (0.5 * next_step() < smallest * (1 - 1e-12))
      return false;
    ++n_reductions;
    dt_current = 0.5 * next_step();
    return true;
  }

  void TimeStepper::save(std::ostream &out) const
  {
    // 17 significant digits reproduce a double exactly, so a restart is bitwise faithful.
    out << std::setprecision(17) << t << ' ' << step << ' ' << dt_previous << ' ' << dt_current
        << '\n';
  }

  void TimeStepper::load(std::istream &in)
  {
    in >> t >> step >> dt_previous >> dt_current;
    // A restart may ask for a smaller step than the run had.
    dt_current = std::min(dt_current, dt_requested);
    n_reductions = 0;
  }
} // namespace fdparticle
