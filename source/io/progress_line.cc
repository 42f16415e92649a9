#include <fdparticle/io/progress_line.h>

#include <iomanip>
#include <sstream>

namespace fdparticle
{
  ProgressLine::ProgressLine(const double end_time, const bool show_linear_iterations)
    : end_time(end_time)
    , show_linear_iterations(show_linear_iterations)
  {}

  std::string ProgressLine::format_duration(const double seconds)
  {
    std::ostringstream s;
    s << std::fixed;
    if (seconds < 120)
      s << std::setprecision(0) << seconds << " s";
    else if (seconds < 2 * 3600)
      s << std::setprecision(0) << seconds / 60 << " min";
    else
      s << std::setprecision(1) << seconds / 3600 << " h";
    return s.str();
  }

  void ProgressLine::print(const ConditionalOStream &out, const StatisticsTable &stats, const bool finished)
  {
    const double now = stats.get("time"), seconds = stats.get("wall_seconds");
    recent.emplace_back(stats.get("dt"), seconds);
    if (recent.size() > window)
      recent.pop_front();
    // Counts are stored as doubles; printed as integers.
    const auto count = [&](const std::string &name) {
      return static_cast<unsigned long long>(stats.get(name));
    };
    double simulated = 0, wall = 0;
    for (const auto &[dt, seconds] : recent)
      {
        simulated += dt;
        wall += seconds;
      }
    const double end = end_time;
    const double left = (simulated > 0 ? (end - now) * wall / simulated : 0.0);
    out << "step " << std::setw(5) << count("step") << "  t = " << std::setw(10)
        << std::setprecision(6) << now << " / " << end << " (" << std::fixed
        << std::setprecision(0) << std::setw(3) << 100 * now / end << " %)"
        << std::defaultfloat << "  Newton " << count("nonlinear_iterations");
    if (show_linear_iterations)
      out << "  linear " << count("linear_iterations");
    out << "  residual " << std::scientific << std::setprecision(3) << stats.get("residual")
        << std::defaultfloat << "  DoFs " << count("dofs") << "  " << std::setprecision(3)
        << seconds << " s";
    if (!finished)
      out << "  left ~" << format_duration(left);
    out << std::endl;
  }
} // namespace fdparticle
