/*
  \file vpMorphInsideTest.h
  \brief Internal to the morph module (not installed): whether a point is inside a closed curve, through bands.
*/
#ifndef VP_MORPH_INSIDE_TEST_H
#define VP_MORPH_INSIDE_TEST_H

#include <algorithm>
#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>

#include "vpMorphBuckets.h"
#include "vpMorphGridCell.h"

/*
  The even-odd rule on a closed curve, with its edges bucketed in horizontal bands about four mean edges high: a
  point's ray crosses only edges that span its ordinate, and those lie in its band, so a dense outline (a point per
  boundary pixel) answers from a few tens of edges instead of all of them. Each edge is tested exactly as the plain
  scan tests it, and a parity does not depend on the order: the answer is the scan's, bit for bit.
*/
class vpMorphInsideTest
{
public:
  explicit vpMorphInsideTest(const vpMorphContour &c) : m_x(c.xs()), m_y(c.ys())
  {
    const std::size_t n = c.size();
    if (n == 0)
      return;
    m_y0 = *std::min_element(c.ys().begin(), c.ys().end());
    const double y1 = *std::max_element(c.ys().begin(), c.ys().end());
    const double span = y1 - m_y0;
    m_h = std::max(4.0 * c.perimeter() / double(n), 1e-9 * span);
    m_nb = std::min(4096, int(span / m_h) + 1); // m_h > 0: a contour has 3 distinct vertices at least
    m_h = span / m_nb * (1.0 + 1e-12) + 1e-300;
    // Edge (k - 1, k), named k, in every band from its lower end's to its upper end's: a band's index grows with the
    // ordinate, so any ordinate the edge spans falls in one of them.
    std::vector<std::size_t> cursor;
    vpMorphFillBuckets(
        std::size_t(m_nb),
        [&](auto &&f) {
          for (std::size_t k = 0; k < n; ++k) {
            const std::size_t l = (k + n - 1) % n;
            for (int b = band(std::min(c.y(k), c.y(l))), b1 = band(std::max(c.y(k), c.y(l))); b <= b1; ++b)
              f(std::size_t(b), k);
          }
        },
        m_first, m_edges, cursor);
  }

  //! Whether (x, y) is inside the curve: an odd number of its edges cross the ray from (x, y) along +x.
  bool operator()(double x, double y) const
  {
    const std::size_t n = m_x.size();
    if (n == 0)
      return false;
    const std::size_t b = std::size_t(band(y));
    bool in = false;
    for (std::size_t e = m_first[b]; e < m_first[b + 1]; ++e) {
      const std::size_t k = m_edges[e], l = (k + n - 1) % n;
      if ((m_y[k] > y) != (m_y[l] > y) && x < m_x[k] + (y - m_y[k]) / (m_y[l] - m_y[k]) * (m_x[l] - m_x[k]))
        in = !in;
    }
    return in;
  }

private:
  int band(double y) const { return vpMorphGridCell((y - m_y0) / m_h, m_nb); }

  std::vector<double> m_x, m_y; // the curve's vertices
  double m_y0 = 0.0, m_h = 1.0;
  int m_nb = 1;
  std::vector<std::size_t> m_first;
  std::vector<unsigned int> m_edges;
};

#endif
