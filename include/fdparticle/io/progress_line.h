#ifndef fdparticle_io_progress_line_h
#define fdparticle_io_progress_line_h

#include <deal.II/base/conditional_ostream.h>

#include <fdparticle/base/statistics_table.h>

#include <deque>
#include <string>
#include <utility>

namespace fdparticle
{
  /**
   * The screen line of each step: progress, Newton and linear iterations, residual, size,
   * wall time, and the time left, estimated from the simulated time per wall second of the
   * recent steps.
   */
  class ProgressLine
  {
  public:
    /// show_linear_iterations: the linear solver iterates, so its count is worth a column.
    ProgressLine(const double end_time, const bool show_linear_iterations);

    /// Record the step and print its line.
    void print(const ConditionalOStream &out, const StatisticsTable &stats, const bool finished);

    /// Seconds as "42 s", "12 min" or "3.5 h".
    static std::string format_duration(const double seconds);

  private:
    /// Steps the estimate of the time left averages over: enough to smooth the noise of
    /// single steps, few enough to follow a change of the time step or of the mesh.
    static constexpr std::size_t window = 10;

    double end_time;
    bool   show_linear_iterations;
    /// (Δt, wall seconds) of the recent steps.
    std::deque<std::pair<double, double>> recent;
  };
} // namespace fdparticle

#endif
