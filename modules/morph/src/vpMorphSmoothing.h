/*
  \file vpMorphSmoothing.h
  \brief Internal to the morph module (not installed): an outline smoothed along its arc length.
*/
#ifndef VP_MORPH_SMOOTHING_H
#define VP_MORPH_SMOOTHING_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>

/*
  Dense resampling by arc length, circular Gaussian smoothing (sigma as a fraction of the perimeter), then
  resampling to n points: the outline at one scale (sigma <= 0: resampled only). The ownEdge() marks are carried
  along.
*/
inline vpMorphContour vpMorphSmoothed(const vpMorphContour &c, double sigma, std::size_t n)
{
  if (sigma <= 0.0)
    return c.resampled(n);
  const std::size_t dense = std::max<std::size_t>(4 * n, 256);
  const vpMorphContour d = c.resampled(dense);
  const double s = sigma * dense;
  const int half = static_cast<int>(std::ceil(3.0 * s));
  std::vector<double> w(2 * half + 1);
  double sum = 0.0;
  for (int k = -half; k <= half; ++k)
    sum += (w[k + half] = std::exp(-0.5 * k * k / (s * s)));
  // The dense outline with \e half points of wrap-around either side, so that the window needs no modulo.
  const int N = static_cast<int>(dense);
  std::vector<double> px(dense + 2 * static_cast<std::size_t>(half)), py(px.size());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const int j = ((static_cast<int>(i) - half) % N + N) % N;
    px[i] = d.x(static_cast<std::size_t>(j));
    py[i] = d.y(static_cast<std::size_t>(j));
  }
  std::vector<double> x(dense), y(dense);
  for (int i = 0; i < N; ++i) {
    double ax = 0.0, ay = 0.0;
    const double *qx = &px[static_cast<std::size_t>(i)], *qy = &py[static_cast<std::size_t>(i)];
    for (int k = 0; k <= 2 * half; ++k) {
      ax += w[k] * qx[k];
      ay += w[k] * qy[k];
    }
    x[i] = ax / sum;
    y[i] = ay / sum;
  }
  vpMorphContour out(x, y, c.units());
  if (d.hasOwnEdges()) { // each smoothed edge keeps the mark of the edge it was smoothed from
    std::vector<bool> marks(dense);
    for (std::size_t i = 0; i < dense; ++i)
      marks[i] = d.ownEdge(i);
    out.setOwnEdges(marks);
  }
  return out.resampled(n);
}

#endif
