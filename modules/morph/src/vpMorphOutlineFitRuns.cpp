// vpMorphOutlineFit's model statistics: the runs of outliers along the input that are parts of the view the goal does
// not have (vpMorphOutlineFit::getOutsideShare(), getInsideShare()).
#include <visp3/morph/vpMorphOutlineFit.h>

#include "vpMorphNearestEdge.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace
{
/*
  The fine parts of a closed outline: those its two sides hold by a neck narrower than \e width. A part of the object
  on such a neck (a filament, a knob) or a gap in it behind one (a slit) keeps or loses its pixels as the pixel grid
  moves under the neck, and the outline goes round it or not. Two points of the outline are the neck's sides when
  closer than the width and more than pi width apart along the outline (beyond the local edge, and round a blunt end
  that wide). \e edges: the outline's own edges.
*/
class FineParts
{
public:
  FineParts(const vpMorphContour &c, const vpMorphNearestEdge &edges, double width)
    : m_c(c), m_edges(edges), m_w(width), m_arc(c.size() + 1, 0.0)
  {
    for (std::size_t j = 0; j < c.size(); ++j)
      m_arc[j + 1] = m_arc[j] + c.edgeLength((j + 1) % c.size()); // as resampled() measures it
  }
  double perimeter() const { return m_arc.back(); }
  // Whether the stretch [s0, s1] of the outline is cut off by a neck: a point of the outline within \e reach before
  // it and one within \e reach after it, closer than the width.
  bool pinched(double s0, double s1, double reach) const
  {
    for (std::size_t i = 0; i < m_c.size(); ++i)
      if (positive(s0 - m_arc[i]) <= reach &&
          otherSide(m_c.x(i), m_c.y(i), m_arc[i], [&](double a) { return positive(a - s1) <= reach; }))
        return true;
    return false;
  }

private:
  double positive(double d) const { return d < 0.0 ? d + perimeter() : d; }
  // An edge point within the width of (px, py), the other side of the point at arc length s, at an arc length \e at
  // takes.
  template <typename F> bool otherSide(double px, double py, double s, F at) const
  {
    return m_edges.within(px, py, m_w, [&](std::size_t k, double t) {
      const double a = m_arc[k] + t * (m_arc[k + 1] - m_arc[k]);
      return std::fabs(std::remainder(a - s, perimeter())) > M_PI * m_w && at(a);
    });
  }

  const vpMorphContour &m_c;
  const vpMorphNearestEdge &m_edges;
  double m_w;
  std::vector<double> m_arc; // arc length at each vertex, and the perimeter last
};
} // namespace

void vpMorphOutlineFit::structuredOutliers(const std::vector<double> &w, const vpMorphContour &outline,
                                           const vpMorphNearestEdge *edges)
{
  // Runs of consecutive outliers along the input (cyclic). Outliers of the noise come alone: at the rate p of the
  // isolated ones, a run of m happens by chance with probability about n p^m, so only runs longer than the m that makes
  // it 1e-3 are parts of the view the goal does not have.
  const std::size_t n = m_residuals.size();
  m_outsideShare = m_insideShare = 0.0;
  std::vector<std::pair<std::size_t, std::size_t>> runs; // (start, length)
  std::size_t first = n;
  for (std::size_t k = 0; k < n; ++k)
    if (w[k] > 0.0) {
      first = k;
      break;
    }
  if (first == n) { // no inlier: one run, the whole outline
    double out = 0.0;
    for (double r : m_residuals)
      out += r > 0.0 ? 1.0 : 0.0;
    (out > 0.5 * double(n) ? m_outsideShare : m_insideShare) = 1.0;
    return;
  }
  for (std::size_t i = 1; i <= n; ++i) {
    const std::size_t k = (first + i) % n;
    if (w[k] > 0.0)
      continue;
    if (!runs.empty() && (runs.back().first + runs.back().second) % n == k)
      ++runs.back().second;
    else
      runs.emplace_back(k, 1);
  }
  std::size_t singles = 0;
  for (const auto &run : runs)
    singles += run.second == 1 ? 1 : 0;
  const double p = std::max(double(singles), 0.5) / double(n);
  const double m = std::max(2.0, std::ceil(std::log(1e-3 / double(n)) / std::log(p)));
  // A run on a fine part of the input (FineParts), cut off by a neck narrower than getFineWidth(), is the grid's
  // phase, not a part the goal lacks. The input's samples lie every perimeter / n from its outline's vertex 0 when it
  // is dense (fit()).
  std::unique_ptr<vpMorphNearestEdge> ownEdges; // when the fit has none of the input's
  std::unique_ptr<FineParts> fine;
  for (const auto &run : runs) {
    if (double(run.second) < m)
      continue;
    if (!fine && m_fineWidth > 0.0 && outline.size() > n) {
      if (!edges)
        ownEdges.reset(new vpMorphNearestEdge(outline));
      fine.reset(new FineParts(outline, edges ? *edges : *ownEdges, m_fineWidth));
    }
    const double step = fine ? fine->perimeter() / double(n) : 0.0;
    const auto arcOf = [&](std::size_t j) { return step * double((run.first + j) % n); };
    if (fine && fine->pinched(arcOf(0), arcOf(run.second - 1), step * double(run.second)))
      continue;
    std::size_t out = 0;
    for (std::size_t j = 0; j < run.second; ++j)
      out += m_residuals[(run.first + j) % n] > 0.0 ? 1 : 0;
    (2 * out > run.second ? m_outsideShare : m_insideShare) += double(run.second) / double(n);
  }
}
