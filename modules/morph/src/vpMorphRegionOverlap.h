/*
  \file vpMorphRegionOverlap.h
  \brief Internal to the morph module (not installed): the area shared by two polygons' regions, and its gradient
  under a rigid motion of one of them.
*/
#ifndef VP_MORPH_REGION_OVERLAP_H
#define VP_MORPH_REGION_OVERLAP_H

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphContour.h>

#include "vpMorphBuckets.h"
#include "vpMorphGridCell.h"

//! A contour's vertices as points.
inline std::vector<Eigen::Vector2d> vpMorphPoints(const vpMorphContour &c)
{
  std::vector<Eigen::Vector2d> p(c.size());
  for (std::size_t k = 0; k < c.size(); ++k)
    p[k] = Eigen::Vector2d(c.x(k), c.y(k));
  return p;
}

/*
  A closed polygon (counter-clockwise) with its edges bucketed in a uniform grid of cells about two mean edges wide:
  a dense outline (a point per boundary pixel) meets another one's edges, and answers "inside?", in about constant
  time per edge instead of scanning all of them.
*/
class vpMorphOverlapPolygon
{
public:
  vpMorphOverlapPolygon() = default;
  explicit vpMorphOverlapPolygon(const std::vector<Eigen::Vector2d> &p) { assign(p); }

  //! Rebuilds for the points \e p (not empty), in the storage already held: an optimisation moves a polygon and
  //! rebuilds it at every step.
  void assign(const std::vector<Eigen::Vector2d> &p)
  {
    m_p.assign(p.begin(), p.end());
    double a = 0.0;
    for (std::size_t k = 0; k < m_p.size(); ++k)
      a += cross(m_p[k], m_p[(k + 1) % m_p.size()]);
    if (a < 0.0)
      std::reverse(m_p.begin(), m_p.end());
    m_area = std::fabs(a) / 2.0;
    Eigen::Vector2d lo = m_p[0], hi = m_p[0];
    double perimeter = 0.0;
    for (std::size_t k = 0; k < m_p.size(); ++k) {
      lo = lo.cwiseMin(m_p[k]);
      hi = hi.cwiseMax(m_p[k]);
      perimeter += (m_p[(k + 1) % m_p.size()] - m_p[k]).norm();
    }
    m_lo = lo;
    const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y());
    m_h = std::max(2.0 * perimeter / double(m_p.size()), 1e-9 * span);
    m_nx = std::min(512, int((hi.x() - lo.x()) / m_h) + 1);
    m_ny = std::min(512, int((hi.y() - lo.y()) / m_h) + 1);
    m_h = std::max((hi.x() - lo.x()) / m_nx, (hi.y() - lo.y()) / m_ny) * (1.0 + 1e-12) + 1e-300;
    // Each edge's cells (the columns and rows of its bounding box), computed once for the grid and for the queries'
    // "each edge once" tests (a floor and a division per candidate edge were most of the queries' time).
    m_box.resize(m_p.size());
    for (std::size_t k = 0; k < m_p.size(); ++k) {
      const Eigen::Vector2d &a = m_p[k], &b = m_p[(k + 1) % m_p.size()];
      m_box[k] = {cellX(std::min(a.x(), b.x())), cellX(std::max(a.x(), b.x())), cellY(std::min(a.y(), b.y())),
                  cellY(std::max(a.y(), b.y()))};
    }
    // Cells in one array (counted, then filled).
    vpMorphFillBuckets(
        std::size_t(m_nx) * std::size_t(m_ny), [this](auto &&f) { forEachCell(f); }, m_start, m_edges, m_fill);
  }

  const std::vector<Eigen::Vector2d> &points() const { return m_p; }
  double area() const { return m_area; }

  //! Whether q is inside (crossing number along +x, through the cells of q's grid row only).
  bool inside(const Eigen::Vector2d &q) const
  {
    if (!(q.y() >= m_lo.y() && q.y() < m_lo.y() + m_ny * m_h && q.x() < m_lo.x() + m_nx * m_h))
      return false;
    const int j = cellY(q.y()), i0 = cellX(q.x());
    bool in = false;
    for (int i = i0; i < m_nx; ++i)
      for (std::size_t e = m_start[index(i, j)]; e < m_start[index(i, j) + 1]; ++e) {
        const std::size_t k = m_edges[e];
        const Eigen::Vector2d &a = m_p[k], &b = m_p[(k + 1) % m_p.size()];
        if ((a.y() > q.y()) == (b.y() > q.y()) || i != std::max(i0, m_box[k][0]))
          continue; // not across the ray's line, or met before in this row
        const double x = a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (x > q.x())
          in = !in;
      }
    return in;
  }

  /*
    Calls f(t, k, s) for each crossing of segment [p, q] with this polygon's edge k, at p + t (q - p) and
    m_p[k] + s (m_p[k+1] - m_p[k]), t and s in [0, 1) (half-open: a crossing at a shared vertex counts once).
  */
  template <class F> void crossings(const Eigen::Vector2d &p, const Eigen::Vector2d &q, F f) const
  {
    const Eigen::Vector2d e = q - p;
    const int i0 = std::max(0, cellX(std::min(p.x(), q.x()))), i1 = std::min(m_nx - 1, cellX(std::max(p.x(), q.x())));
    const int j0 = std::max(0, cellY(std::min(p.y(), q.y()))), j1 = std::min(m_ny - 1, cellY(std::max(p.y(), q.y())));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (std::size_t c = m_start[index(i, j)]; c < m_start[index(i, j) + 1]; ++c) {
          const std::size_t k = m_edges[c];
          // Each edge once: in the first cell of the scan (row by row) that holds it.
          if (j != std::max(j0, m_box[k][2]) || i != std::max(i0, m_box[k][0]))
            continue;
          const Eigen::Vector2d &a = m_p[k], &b = m_p[(k + 1) % m_p.size()], d = b - a;
          const double den = cross(e, d);
          if (den == 0.0)
            continue; // parallel: no crossing that changes the side
          const Eigen::Vector2d w = a - p;
          const double t = cross(w, d) / den, s = cross(w, e) / den;
          if (t >= 0.0 && t < 1.0 && s >= 0.0 && s < 1.0)
            f(t, k, s);
        }
  }

  static double cross(const Eigen::Vector2d &a, const Eigen::Vector2d &b) { return a.x() * b.y() - a.y() * b.x(); }

private:
  int cellX(double x) const { return vpMorphGridCell((x - m_lo.x()) / m_h, m_nx); }
  int cellY(double y) const { return vpMorphGridCell((y - m_lo.y()) / m_h, m_ny); }
  std::size_t index(int i, int j) const { return std::size_t(j) * std::size_t(m_nx) + std::size_t(i); }
  // f(cell, edge) for every cell of every edge's bounding box.
  template <class F> void forEachCell(F f) const
  {
    for (std::size_t k = 0; k < m_p.size(); ++k)
      for (int j = m_box[k][2]; j <= m_box[k][3]; ++j)
        for (int i = m_box[k][0]; i <= m_box[k][1]; ++i)
          f(index(i, j), k);
  }

  std::vector<Eigen::Vector2d> m_p;
  double m_area = 0.0;
  Eigen::Vector2d m_lo;
  double m_h = 1.0;
  int m_nx = 1, m_ny = 1;
  std::vector<std::size_t> m_start, m_edges; // edges of cell c: m_edges[m_start[c] .. m_start[c + 1])
  std::vector<std::array<int, 4>> m_box;     // each edge's first and last column, first and last row
  std::vector<std::size_t> m_fill;           // the fill's cursor per cell, kept for its storage
};

/*
  Area of A's region inside B's (Green's theorem over the pieces of each boundary that lie inside the other) and,
  when grad is given, its derivative under a rigid motion of A: (d/dtheta about c, d/dtx, d/dty). Moving A only
  moves the pieces of its boundary inside B, each by its normal velocity (the crossings' own motion adds nothing
  at first order).
  Boundaries that coincide (a contour against itself, collinear edges) have no crossings and points on the other's
  boundary: A is read a billionth of B's size away along a fixed generic direction, so that every such case is a
  proper crossing or a clear side (the area changes by that much).
*/
inline double vpMorphOverlapArea(const vpMorphOverlapPolygon &A, const vpMorphOverlapPolygon &B,
                                 const Eigen::Vector2d &c = Eigen::Vector2d::Zero(), Eigen::Vector3d *grad = nullptr)
{
  double twice = 0.0;
  if (grad)
    grad->setZero();
  std::vector<double> ts;
  double span = 0.0;
  for (const Eigen::Vector2d &q : B.points())
    span = std::max(span, (q - B.points()[0]).cwiseAbs().maxCoeff());
  const Eigen::Vector2d shift = 1e-9 * span * Eigen::Vector2d(0.6180339887, 0.7548776662);
  // Pieces of P's edges inside Q, P moved by offset; forA: P is A (the moving one), for the gradient.
  auto pieces = [&](const vpMorphOverlapPolygon &P, const vpMorphOverlapPolygon &Q, const Eigen::Vector2d &offset,
                    bool forA) {
    const std::vector<Eigen::Vector2d> &p = P.points();
    // The side of Q is carried along P from crossing to crossing, and read afresh every 32 edges (a ray test
    // costs a row of cells), so that a crossing lost to rounding cannot flip the rest of the boundary.
    bool in = false;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const Eigen::Vector2d a = p[k] + offset, b = p[(k + 1) % p.size()] + offset, e = b - a;
      ts.clear();
      Q.crossings(a, b, [&](double t, std::size_t, double) { ts.push_back(t); });
      std::sort(ts.begin(), ts.end());
      if (k % 32 == 0)
        in = Q.inside(a);
      double t0 = 0.0;
      auto piece = [&](double t1) {
        const Eigen::Vector2d u = a + t0 * e, v = a + t1 * e;
        twice += vpMorphOverlapPolygon::cross(u, v);
        if (forA && grad) {
          const Eigen::Vector2d d = v - u, m = 0.5 * (u + v) - c;
          (*grad)[0] -= d.dot(m);
          (*grad)[1] += d.y();
          (*grad)[2] -= d.x();
        }
      };
      for (double t : ts) {
        if (in)
          piece(t);
        in = !in;
        t0 = t;
      }
      if (in)
        piece(1.0);
    }
  };
  pieces(A, B, shift, true);
  pieces(B, A, -shift, false);
  return twice / 2.0;
}

#endif
