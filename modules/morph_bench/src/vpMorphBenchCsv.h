/*!
  \file vpMorphBenchCsv.h
  \brief Internal: the bench's CSV fields (numbers written with a fixed precision and read back), orders of names.
*/
#ifndef VP_MORPH_BENCH_CSV_H
#define VP_MORPH_BENCH_CSV_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace vpMorphBenchCsv
{
//! A number as a CSV field: \e precision significant digits, empty when not finite.
inline std::string num(double x, int precision = 4)
{
  if (!std::isfinite(x))
    return "";
  std::ostringstream os;
  os << std::setprecision(precision) << x;
  return os.str();
}

//! A CSV field as a number: NaN when empty or not a number.
inline double number(const std::string &field)
{
  if (field.empty())
    return std::numeric_limits<double>::quiet_NaN();
  char *end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  return end == field.c_str() + field.size() ? v : std::numeric_limits<double>::quiet_NaN();
}

//! The fields of a CSV row (no quoted separators: the bench writes none).
inline std::vector<std::string> split(const std::string &row)
{
  std::vector<std::string> f;
  std::string::size_type start = 0;
  for (;;) {
    const std::string::size_type comma = row.find(',', start);
    f.push_back(row.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos)
      return f;
    start = comma + 1;
  }
}

//! The place of \e n in \e names, or after them all.
inline int orderOf(const std::vector<std::string> &names, const std::string &n)
{
  const auto it = std::find(names.begin(), names.end(), n);
  return static_cast<int>(it - names.begin());
}
} // namespace vpMorphBenchCsv

#endif
