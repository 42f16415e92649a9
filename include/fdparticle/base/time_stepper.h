#ifndef fdparticle_base_time_stepper_h
#define fdparticle_base_time_stepper_h

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <iosfwd>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Time levels, step-size control and the variable-step BDF1/BDF2 formulas (doc/method.md §2).
   * With ω = Δt_n/Δt_{n-1}, BDF2 reads
   *   dy/dt ≈ [(1+2ω)/(1+ω) y^{n+1} − (1+ω) y^n + ω²/(1+ω) y^{n−1}] / Δt_n,
   * which is 3/2, −2, 1/2 for a constant step. The first step is always BDF1.
   *
   * Recovery: a failed step is retried with half the step, down to the requested
   * step / 2^'Max time step reductions'; after each accepted step the step doubles back
   * toward the requested one. Ratios ω of 1/2 and 2 keep variable-step BDF2 zero-stable
   * (ω < 1 + √2).
   */
  class TimeStepper
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /// The most steps a run may ask for (End time / Time step). 1e8 is 10^4 times the
    /// longest run made with the code (10^4 steps); more is a typo (a step in the wrong
    /// unit), would never finish, and would outgrow the unsigned step counter (2^32) and
    /// the round-off of the accumulated time (Δt / End time stays above 1e-8).
    static constexpr double max_steps = 1e8;

    double       time() const { return t; }
    unsigned int step_number() const { return step; }
    double       end_time() const { return t_end; }
    double       requested_step() const { return dt_requested; }
    /// 1 or 2: the order the next step will use.
    unsigned int order() const;
    /// The size of the next step: the current one, shortened to land on the end time
    /// (the last two steps share the remainder when it is less than two steps).
    double       next_step() const;
    /// Δt_{n−1}, the size of the last completed step.
    double       previous_step() const { return dt_previous; }
    /// Whether the end time is reached.
    bool         finished() const;
    /// A line for the start of a run when End time is not a multiple of Time step (the
    /// size of the last two steps), else "".
    std::string  describe() const;

    /// c0, c1, c2 with dy/dt ≈ c0 y^{n+1} + c1 y^n + c2 y^{n−1}, for the next step.
    std::array<double, 3> coefficients() const;

    /// w in the extrapolation y^{n+1} ≈ y^n + w (y^n − y^{n−1}) of the next step's order:
    /// Δt_n/Δt_{n−1}, 0 for BDF1 (y^n).
    double extrapolation_weight() const
    {
      return order() == 1 ? 0.0 : next_step() / dt_previous;
    }

    /// Extrapolated y^{n+1} of the scheme's order (y^n for BDF1), for frozen geometry.
    template <typename T>
    T extrapolate(const T &y_n, const T &y_nm1) const
    {
      const double w = extrapolation_weight();
      if (w == 0.0)
        return y_n;
      return y_n + w * (y_n - y_nm1);
    }

    /// Record a completed step of the size next_step() returned; grow the step back.
    void advance();

    /// Halve the step for a retry; false if it would fall below Time step / 2^max.
    bool reduce_step();
    /// Halvings used on the step being attempted.
    unsigned int reductions() const { return n_reductions; }

    /// The state a restart needs (time, step count, step sizes), as exact text.
    void save(std::ostream &out) const;
    void load(std::istream &in);

    std::string scheme_name() const { return max_order == 2 ? "BDF2" : "BDF1"; }

  private:
    double       t = 0, t_end = 1, dt_requested = 0.1, dt_previous = 0, dt_current = 0.1;
    unsigned int step = 0, max_order = 2, max_reductions = 6, n_reductions = 0;
  };
} // namespace fdparticle

#endif
