/*
  \file vpMorphLevelSpread.h
  \brief Internal to the morph module (not installed): the spread of a surface's grey levels, robust to another surface
  beside it (vpMorphRegionMeasure, vpMorphOwnEdges).
*/
#ifndef VP_MORPH_LEVEL_SPREAD_H
#define VP_MORPH_LEVEL_SPREAD_H

#include <algorithm>
#include <array>
#include <vector>

namespace vpMorphLevelSpread
{
// The half-width of a surface's levels about their centre: 4 sigma of a normal noise (sigma = 1.4826 MAD), at least
// half a grey level (the quantization's).
inline double fourSigma(double mad) { return std::max(0.5, 4.0 * 1.4826 * mad); }

// The median of a histogram of levels: its lowest bin with half the counts at or under it, 0 when empty (the spread
// about it is quantizedDeviationMedian()'s).
inline double medianOf(const std::array<long, 256> &dev)
{
  long total = 0, acc = 0;
  for (long c : dev)
    total += c;
  for (int d = 0; d < 256; ++d) {
    acc += dev[d];
    if (total > 0 && 2 * acc >= total)
      return d;
  }
  return 0.0;
}

/*
  The median deviation, on one side of a level, of grey levels that are rounded continuous values: \e dev[d] counts the
  pixels d grey levels from the level on that side, dev[0] those at the level itself, of which half lie on each side.
  Each bin's pixels spread evenly over the deviations that round to it ([d - 1/2, d + 1/2], [0, 1/2] for dev[0]): the
  grouped-data median. Why not medianOf(): a surface whose levels span a few grey levels (a dark surface under a light
  that falls off) has most of a side at its median level, whose median deviation of 0 would narrow the window about
  it to that one level. 0 when empty.
*/
inline double quantizedDeviationMedian(const std::array<long, 256> &dev)
{
  double total = 0.5 * double(dev[0]);
  for (int d = 1; d < 256; ++d)
    total += double(dev[d]);
  if (!(total > 0.0))
    return 0.0;
  const double half = 0.5 * total;
  double below = 0.0; // the pixels of the bins under the current one
  for (int d = 0; d < 256; ++d) {
    const double count = d == 0 ? 0.5 * double(dev[0]) : double(dev[d]);
    const double lo = d == 0 ? 0.0 : d - 0.5, hi = d + 0.5;
    if (count > 0.0 && below + count >= half)
      return lo + (hi - lo) * (half - below) / count;
    below += count;
  }
  return 255.5;
}

// The median of \e v (reordered; 0 when empty).
inline double median(std::vector<double> &v)
{
  if (v.empty())
    return 0.0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/*
  The median absolute deviation of a surface's levels, from the side of their centre that deviates less: \e below and
  \e above the median deviations on each side. Why: a normal noise deviates alike on both sides, while another surface
  in the mask lies on one side of the main one and inflates that side's only. A side that reaches the sensor's limit
  (\e belowClipped, \e aboveClipped: pixels at 0 or 255 in the mask) is clipped and deviates less for that: it counts
  only when both do.
*/
inline double oneSidedMad(double below, bool belowClipped, double above, bool aboveClipped)
{
  if (belowClipped != aboveClipped)
    return belowClipped ? above : below;
  return std::min(above, below);
}
} // namespace vpMorphLevelSpread

#endif
