#ifndef fdparticle_base_statistics_table_h
#define fdparticle_base_statistics_table_h

#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The columns of statistics.csv and the row of the current step. Each part of the code
   * that reports a number declares its columns once, at set-up (declare_columns()
   * members), and sets their values each step: a new column is added where its number is
   * computed (and described in doc/output.md). The file's columns are the declared
   * names in the order of declaration; a column not set in a step holds 0.
   */
  class StatisticsTable
  {
  public:
    /// Declare a column at the end of the table. A name may be declared once only.
    void declare(const std::string &name);
    /// Declare namex, namey, namez: a vector as three columns (z is 0 in 2D).
    void declare_vector(const std::string &name);

    /// Start the row of a new step: every value 0.
    void new_row();
    /// Set a declared column of the current row.
    void set(const std::string &name, const double value);
    /// Set namex, namey, namez from the dim components of v (z = 0 in 2D).
    template <int dim>
    void set_vector(const std::string &name, const Tensor<1, dim> &v)
    {
      for (unsigned int d = 0; d < 3; ++d)
        set(name + "xyz"[d], d < dim ? v[d] : 0.0);
    }
    double get(const std::string &name) const;

    const std::vector<std::string> &names() const { return column_names; }
    const std::vector<double> &     values() const { return row; }

  private:
    std::vector<std::string> column_names;
    std::vector<double>      row;
    unsigned int             index(const std::string &name) const;
  };
} // namespace fdparticle

#endif
