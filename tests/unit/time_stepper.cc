// Unit test of fdparticle::TimeStepper (include/fdparticle/base/time_stepper.h), set up through
// a ParameterHandler exactly as the program does (subsection Time).
//
// Independent references: BDF1 = (1, -1, 0)/dt, constant-step BDF2 = (3/2, -2, 1/2)/dt,
// and the defining property of the variable-step BDF2 formula: it differentiates every
// quadratic exactly on the actual (non-uniform) time levels. Extrapolation must reproduce
// linear functions. The number of steps to the end time is counted by hand.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/base/time_stepper.h>

#include "unit_check.h"

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{

  /// A TimeStepper read from the given 'Time' entries.
  TimeStepper make_stepper(const std::string &scheme, const std::string &dt,
                           const std::string &end)
  {
    ParameterHandler prm;
    TimeStepper::declare_parameters(prm);
    prm.parse_input_from_string("subsection Time\n"
                                "  set Scheme = " + scheme + "\n"
                                "  set Time step = " + dt + "\n"
                                "  set End time = " + end + "\n"
                                "end\n");
    TimeStepper time;
    time.parse_parameters(prm);
    return time;
  }

  /// The message of the exception make_stepper throws, or "" if it does not throw.
  std::string error_of(const std::string &scheme, const std::string &dt, const std::string &end)
  {
    try
      {
        make_stepper(scheme, dt, end);
      }
    catch (const std::exception &exc)
      {
        const std::string m = ParameterTools::one_line_message(exc);
        return m.empty() ? "(empty message)" : m;
      }
    return "";
  }

  void check_error(const std::string &scheme, const std::string &dt, const std::string &end,
                   const std::string &phrase)
  {
    const std::string m = error_of(scheme, dt, end);
    check(!m.empty() && m.find(phrase) != std::string::npos,
          "Scheme = " + scheme + ", Time step = " + dt + ", End time = " + end +
            " throws '..." + phrase + "...'",
          m.empty() ? "no exception" : "message: " + m);
  }

  void test_constant_step()
  {
    std::cout << "BDF2, dt = 0.25, end = 1: coefficients and step count" << std::endl;
    TimeStepper time = make_stepper("BDF2", "0.25", "1");
    const double dt = 0.25;
    check(time.scheme_name() == "BDF2", "scheme_name() == BDF2");
    check_close(time.requested_step(), dt, 0, "requested_step() == 0.25");
    check_close(time.end_time(), 1.0, 0, "end_time() == 1");
    check(time.step_number() == 0 && time.time() == 0.0, "starts at step 0, t = 0");

    check(time.order() == 1, "first step has order 1");
    auto c = time.coefficients();
    check_close(c[0], 1 / dt, 1e-14, "first step c0 == 1/dt");
    check_close(c[1], -1 / dt, 1e-14, "first step c1 == -1/dt");
    check_close(c[2], 0.0, 0.0, "first step c2 == 0");
    time.advance();

    unsigned int n = 1;
    while (!time.finished())
      {
        check(time.order() == 2, "step " + std::to_string(n) + " has order 2");
        c = time.coefficients();
        check_close(c[0], 1.5 / dt, 1e-13, "step " + std::to_string(n) + " c0 == 3/(2 dt)");
        check_close(c[1], -2.0 / dt, 1e-13, "step " + std::to_string(n) + " c1 == -2/dt");
        check_close(c[2], 0.5 / dt, 1e-13, "step " + std::to_string(n) + " c2 == 1/(2 dt)");
        time.advance();
        ++n;
        if (n > 100)
          break;
      }
    check(n == 4 && time.step_number() == 4, "finished after 4 steps",
          "took " + std::to_string(n));
    check(time.time() == 1.0, "time() == end time at the end");
  }

  /// Runs a scheme to the end and checks, on the actual time levels, that the coefficients
  /// differentiate quadratics (BDF2) or linear functions (BDF1) exactly, and that
  /// extrapolate() reproduces linear functions.
  void test_variable_step(const std::string &scheme, const double dt, const double end,
                          const std::vector<double> &expected_steps)
  {
    std::cout << scheme << ", dt = " << dt << ", end = " << end
              << ": exactness on the actual time levels" << std::endl;
    std::ostringstream dts, ends;
    dts.precision(17);
    ends.precision(17);
    dts << dt;
    ends << end;
    TimeStepper time = make_stepper(scheme, dts.str(), ends.str());
    const unsigned int max_order = (scheme == "BDF2" ? 2 : 1);

    // y(t) = a + b t + c t², shifted so that no term vanishes at t = 0; linear g(t) = d + e t.
    const auto y = [](const double t) { return 0.7 - 1.3 * t + 2.9 * (t - 0.37) * (t - 0.37); };
    const auto dy = [](const double t) { return -1.3 + 5.8 * (t - 0.37); };
    const auto g = [](const double t) { return -0.4 + 1.7 * t; };
    const auto dg = [](const double) { return 1.7; };
    const auto gv = [](const double t) { return Tensor<1, 2>({1.0 - 2.0 * t, 0.5 + 3.0 * t}); };

    std::vector<double> levels = {0.0}; // t^0, t^1, ... as reached
    std::vector<double> steps;
    while (!time.finished() && steps.size() < 100)
      {
        const unsigned int n = time.step_number();
        const double       t_n = levels.back();
        check_close(time.time(), t_n, 1e-12, "step " + std::to_string(n) + ": time() == t_n");
        const double t_np1 = t_n + time.next_step();
        const auto   c = time.coefficients();
        const std::string at = "step " + std::to_string(n) + " (dt_n = " +
                               std::to_string(time.next_step()) + ")";
        check(time.order() == (n == 0 ? 1u : max_order),
              at + ": order " + std::to_string(n == 0 ? 1u : max_order));
        if (time.order() == 1)
          {
            // BDF1 differentiates linear functions exactly; c2 plays no role.
            check_close(c[0] * g(t_np1) + c[1] * g(t_n) + c[2] * 12345.0, dg(t_np1), 1e-12,
                        at + ": BDF1 coefficients exact for a linear function");
            check_close(c[0], 1.0 / (t_np1 - t_n), 1e-12, at + ": c0 == 1/dt_n");
            check_close(c[2], 0.0, 0.0, at + ": c2 == 0");
            // The BDF1 extrapolation is the last value (no history yet / first order).
            check_close(time.extrapolate(g(t_n), 999.0), g(t_n), 0.0,
                        at + ": order-1 extrapolate returns y^n");
          }
        else
          {
            const double t_nm1 = levels[levels.size() - 2];
            // Sum of c_i t_i² == 2 t_{n+1}, and exactness for a general quadratic.
            check_close(c[0] * t_np1 * t_np1 + c[1] * t_n * t_n + c[2] * t_nm1 * t_nm1,
                        2 * t_np1, 1e-12, at + ": sum c_i t_i^2 == 2 t_{n+1}");
            check_close(c[0] * y(t_np1) + c[1] * y(t_n) + c[2] * y(t_nm1), dy(t_np1), 1e-11,
                        at + ": BDF2 exact for a quadratic");
            check_close(c[0] + c[1] + c[2], 0.0, 1e-12, at + ": sum c_i == 0 (constants)");
            check_close(time.extrapolate(g(t_n), g(t_nm1)), g(t_np1), 1e-13,
                        at + ": extrapolate() exact for a linear function");
            const Tensor<1, 2> e = time.extrapolate(gv(t_n), gv(t_nm1)) - gv(t_np1);
            check(e.norm() < 1e-13, at + ": extrapolate() exact for a linear Tensor<1,2>");
          }
        steps.push_back(time.next_step());
        time.advance();
        levels.push_back(t_np1);
      }

    check(steps.size() == expected_steps.size(),
          "finished() after " + std::to_string(expected_steps.size()) + " steps",
          "took " + std::to_string(steps.size()));
    for (unsigned int i = 0; i < std::min(steps.size(), expected_steps.size()); ++i)
      check_close(steps[i], expected_steps[i], 1e-12,
                  "step " + std::to_string(i) + " has size " + std::to_string(expected_steps[i]));
    check(time.time() == end, "time() == end time exactly at the end");
    check(time.finished(), "finished() at the end");
  }
} // namespace

int main()
{
  try
    {
      test_constant_step();
      // dt = 0.3, end = 1: the remainder 0.4 < 2 dt is shared by the last two steps
      // (levels 0, 0.3, 0.6, 0.8, 1.0; ω = 2/3, then 1), not 0.3 + a sliver of 0.1.
      test_variable_step("BDF2", 0.3, 1.0, {0.3, 0.3, 0.2, 0.2});
      test_variable_step("BDF1", 0.3, 1.0, {0.3, 0.3, 0.2, 0.2});
      // End time just above a whole number of steps: the last two share, no sliver.
      test_variable_step("BDF2", 0.25, 1.01, {0.25, 0.25, 0.25, 0.13, 0.13});
      // 0.1 does not add up to 1.0 in floating point: still exactly 10 steps, no sliver step.
      test_variable_step("BDF2", 0.1, 1.0, std::vector<double>(10, 0.1));
      // Step larger than the whole interval: one shortened BDF1 step.
      test_variable_step("BDF2", 0.5, 0.2, {0.2});

      // The line a run prints when the end time is not a multiple of the step: the sizes
      // the steps above take.
      unit_check::check(make_stepper("BDF2", "0.3", "1").describe().find("are 0.2 each") !=
                          std::string::npos,
                        "describe(): dt = 0.3 to 1, the last two steps are 0.2 each");
      unit_check::check(make_stepper("BDF2", "0.1", "1").describe().empty(),
                        "describe(): nothing to say when 0.1 fits 10 times into 1");
      unit_check::check(make_stepper("BDF2", "0.5", "0.2").describe().find("one step of 0.2") !=
                          std::string::npos,
                        "describe(): a step longer than the run is one step of 0.2");

      std::cout << "Recovery: halving down to dt / 2^N, doubling back" << std::endl;
      {
        ParameterHandler prm;
        TimeStepper::declare_parameters(prm);
        prm.parse_input_from_string("subsection Time\n  set Time step = 0.4\n  set End time = 10\n"
                                    "  set Max time step reductions = 2\nend\n");
        TimeStepper time;
        time.parse_parameters(prm);
        check(time.reduce_step(), "first halving allowed");
        check_close(time.next_step(), 0.2, 1e-15, "dt = 0.2 after one halving");
        check(time.reduce_step(), "second halving allowed");
        check_close(time.next_step(), 0.1, 1e-15, "dt = 0.1 after two halvings");
        check(!time.reduce_step(), "a third halving is refused (0.4 / 2^2 is the floor)");
        check(time.reductions() == 2, "two reductions counted");
        time.advance();
        check(time.reductions() == 0, "the count restarts with the next step");
        check_close(time.next_step(), 0.2, 1e-15, "dt doubles back after an accepted step");
        // Variable-step BDF2 with ω = 2: c = ((1+2ω)/(1+ω), −(1+ω), ω²/(1+ω)) / dt.
        const auto c = time.coefficients();
        check_close(c[0], 5.0 / 3.0 / 0.2, 1e-12, "c0 for ω = 2");
        check_close(c[1], -3.0 / 0.2, 1e-12, "c1 for ω = 2");
        check_close(c[2], 4.0 / 3.0 / 0.2, 1e-12, "c2 for ω = 2");
        check(!time.reduce_step() || time.next_step() >= 0.1 - 1e-15,
              "the floor is absolute: after regrowth, halving never goes below 0.1");
      }

      std::cout << "End time 0: finished before any step" << std::endl;
      {
        const TimeStepper time = make_stepper("BDF2", "0.1", "0");
        check(time.finished(), "End time = 0 is finished at once");
      }

      std::cout << "Bad input" << std::endl;
      check_error("BDF3", "0.1", "1", "unknown scheme 'BDF3'");
      check_error("bdf2", "0.1", "1", "unknown scheme");
      check_error("BDF2", "-1", "1", "'Time/Time step' must be positive");
      check_error("BDF2", "0", "1", "'Time/Time step' must be positive");
      check_error("BDF2", "0.1x", "1", "not a finite number");
      check_error("BDF2", "nan", "1", "not a finite number");
      check_error("BDF2", "0.1", "-1", "'Time/End time' must not be negative");
      check(error_of(" BDF1 ", "1e-2", "2").empty(), "' BDF1 ', '1e-2', '2' are accepted");
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << exc.what() << std::endl;
      return 2;
    }
  return unit_check::summary();
}
