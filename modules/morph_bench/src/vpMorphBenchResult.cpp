#include <visp3/morph_bench/vpMorphBenchResult.h>

#include <limits>

double vpMorphBenchResult::pathRatio() const
{
  return straightLine >= 1e-3 ? pathLength / straightLine : std::numeric_limits<double>::quiet_NaN();
}
