#ifndef fdparticle_time_stepper_h
#define fdparticle_time_stepper_h

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Time levels and the variable-step BDF1/BDF2 formulas (formulation.md, "Equations at
   * t^{n+1}"). With ω = Δt_n/Δt_{n-1}, BDF2 reads
   *   dy/dt ≈ [(1+2ω)/(1+ω) y^{n+1} − (1+ω) y^n + ω²/(1+ω) y^{n−1}] / Δt_n,
   * which is 3/2, −2, 1/2 for a constant step. The first step is always BDF1.
   */
  class TimeStepper
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    double       time() const { return t; }
    unsigned int step_number() const { return step; }
    double       end_time() const { return t_end; }
    double       requested_step() const { return dt_requested; }
    /// 1 or 2: the order the next step will use.
    unsigned int order() const;
    /// The size of the next step: the requested one, shortened to land on the end time.
    double       next_step() const;
    bool         finished() const;

    /// c0, c1, c2 with dy/dt ≈ c0 y^{n+1} + c1 y^n + c2 y^{n−1}, for the next step.
    std::array<double, 3> coefficients() const;

    /// Extrapolated y^{n+1} of the scheme's order (y^n for BDF1), for frozen geometry.
    template <typename T>
    T extrapolate(const T &y_n, const T &y_nm1) const
    {
      if (order() == 1)
        return y_n;
      const double w = next_step() / dt_previous;
      return y_n + w * (y_n - y_nm1);
    }

    /// Record a completed step of the size next_step() returned.
    void advance();

    std::string scheme_name() const { return max_order == 2 ? "BDF2" : "BDF1"; }

  private:
    double       t = 0, t_end = 1, dt_requested = 0.1, dt_previous = 0;
    unsigned int step = 0, max_order = 2;
  };
} // namespace fdparticle

#endif
