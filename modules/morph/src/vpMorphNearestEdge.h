/*
  \file vpMorphNearestEdge.h
  \brief Internal to the morph module (not installed): the nearest point of a closed polygon, through a grid.
*/
#ifndef VP_MORPH_NEAREST_EDGE_H
#define VP_MORPH_NEAREST_EDGE_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <visp3/morph/vpMorphContour.h>

#include "vpMorphBuckets.h"
#include "vpMorphGridCell.h"

/*
  Signed distance from p to the nearest point of the closed polygon c, and the unit direction m along which it is
  measured (the edge normal when the nearest point is inside an edge, towards p when it is a vertex). The edges are
  bucketed in a uniform grid of cells about four mean edges wide, searched in rings around p's cell (the nearest cell
  when p is outside the grid) until an edge is found, then in the cells within that edge's distance (within a short
  reach, the cells of the box p +- reach alone): a dense outline (a point per boundary pixel) is queried in constant
  time instead of scanning its hundreds of edges. The cell size only sets the cost, not the result: four edges were
  7 % faster than two on the outline fits (their query points lie up to pixels off the outline, where small cells need
  more rings). The result is the exhaustive scan's (equal distances: the lowest edge index). A non-finite query point
  gives NaN (and m = 0).
*/
class vpMorphNearestEdge
{
public:
  explicit vpMorphNearestEdge(const vpMorphContour &c) : vpMorphNearestEdge(c, std::vector<char>()) {}

  /*!
    Over the edges \e keep marks only (edge k from vertex k to k + 1; empty: every edge): an outline's stretches
    that are the object's own edge, say. Without any edge kept, no point is within reach (+inf).
  */
  vpMorphNearestEdge(const vpMorphContour &c, const std::vector<char> &keep)
  {
    const std::size_t n = c.size();
    auto kept = [&keep](std::size_t k) { return keep.empty() || keep[k] != 0; };
    // Each edge's start and direction, laid out flat: a query visits dozens of edges.
    m_edges.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t l = (k + 1) % n;
      Edge &e = m_edges[k];
      e.ax = c.x(k);
      e.ay = c.y(k);
      e.dx = c.x(l) - e.ax;
      e.dy = c.y(l) - e.ay;
      const double l2 = e.dx * e.dx + e.dy * e.dy;
      e.il2 = l2 > 0 ? 1.0 / l2 : 0.0;
      const double len = std::hypot(e.dx, e.dy);
      e.nx = len > 0 ? -e.dy / len : 0.0;
      e.ny = len > 0 ? e.dx / len : 1.0;
    }
    for (std::size_t k = 0; k < n; ++k)
      if (kept(k))
        m_kept.push_back(k);
    if (n < 32 || m_kept.empty())
      return; // a polygon: scanning is as fast
    m_x0 = *std::min_element(c.xs().begin(), c.xs().end());
    m_y0 = *std::min_element(c.ys().begin(), c.ys().end());
    const double x1 = *std::max_element(c.xs().begin(), c.xs().end());
    const double y1 = *std::max_element(c.ys().begin(), c.ys().end());
    m_h = std::max(4.0 * c.perimeter() / double(n), 1e-9 * std::max(x1 - m_x0, y1 - m_y0));
    m_nx = std::min(1024, int((x1 - m_x0) / m_h) + 1);
    m_ny = std::min(1024, int((y1 - m_y0) / m_h) + 1);
    m_h = std::max((x1 - m_x0) / m_nx, (y1 - m_y0) / m_ny) * (1.0 + 1e-12) + 1e-300;
    m_invH = 1.0 / m_h;
    // The cells' edge lists laid out one after the other (m_first[cell] to m_first[cell + 1] in m_cellEdges), each in
    // increasing edge order: counted, then filled.
    std::vector<std::size_t> cursor;
    vpMorphFillBuckets(
        std::size_t(m_nx) * std::size_t(m_ny),
        [&](auto &&f) {
          for (std::size_t k : m_kept) {
            const std::size_t l = (k + 1) % n;
            const int i0 = cellX(std::min(c.x(k), c.x(l))), i1 = cellX(std::max(c.x(k), c.x(l)));
            const int j0 = cellY(std::min(c.y(k), c.y(l))), j1 = cellY(std::max(c.y(k), c.y(l)));
            for (int j = j0; j <= j1; ++j)
              for (int i = i0; i <= i1; ++i)
                f(std::size_t(j) * std::size_t(m_nx) + std::size_t(i), k);
          }
        },
        m_first, m_cellEdges, cursor);
  }

  double operator()(double px, double py, double &mx, double &my) const { return query(px, py, mx, my, nullptr); }

  /*
    As operator(), and \e along = m . n, n the nearest edge's own normal (-dy, dx) / |d|: 1 when the nearest point is
    inside the edge, under 1 in magnitude at its ends. Moving that edge by e along n moves the distance by -along e:
    what a fit needs to offset the edges (an outline measured grown or shrunk by a biased edge level).
  */
  double operator()(double px, double py, double &mx, double &my, double &along) const
  {
    return query(px, py, mx, my, &along);
  }

  /*
    As operator(), when the nearest edge lies within \e reach (> 0) of p; +inf (m = 0, along = 0) otherwise. The search
    ends where no edge within reach can remain: a fit that weighs out whatever lies beyond a cut-off needs no farther
    edge, and a point far off a dense outline would spread the rings over the whole grid. Within reach, the result is
    operator()'s.
  */
  double within(double px, double py, double reach, double &mx, double &my, double *along = nullptr) const
  {
    return query(px, py, mx, my, along, reach);
  }

  /*
    operator()'s distance at each point (xs[i], y) of a row, in \e out (resized): a raster, most of whose points lie
    far from a polygon of long edges, where the rings spread over the grid's few crowded cells. Each point visits the
    point before's nearest edge, then the edges in order of their distance in y, skipping those whose box lies beyond
    the best found and stopping at the first whose distance in y does: every edge left is farther, so the result is
    the scan's.
  */
  void alongRow(double y, const std::vector<double> &xs, std::vector<double> &out) const
  {
    // Per edge: its squared distance in y and its extent in x (as visit() reaches its end: a + t d at t = 1).
    struct Near
    {
      double y2, x0, x1;
      std::size_t k;
      bool operator<(const Near &o) const { return y2 < o.y2; }
    };
    std::vector<Near> byY;
    byY.reserve(m_kept.size());
    for (std::size_t k : m_kept) {
      const Edge &e = m_edges[k];
      const double x1 = e.ax + e.dx, y1 = e.ay + e.dy;
      const double dy = std::max(0.0, std::max(std::min(e.ay, y1) - y, y - std::max(e.ay, y1)));
      byY.push_back(Near{dy * dy, std::min(e.ax, x1), std::max(e.ax, x1), k});
    }
    std::sort(byY.begin(), byY.end());
    out.resize(xs.size());
    std::size_t previous = m_edges.size();
    double mx, my;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double px = xs[i];
      Best b;
      if (!std::isfinite(px) || !std::isfinite(y)) {
        out[i] = finish(b, px, y, mx, my, nullptr);
        continue;
      }
      if (previous < m_edges.size())
        visit(previous, px, y, b);
      // An edge's squared distance is at least the sum of its squared distances in x and y, rounding included (a + t d
      // lies between the edge's ends and each operation is monotone): the edges left once that in y exceeds the best
      // are farther still.
      for (const Near &e : byY) {
        if (e.y2 > b.d2)
          break;
        const double dx = std::max(0.0, std::max(e.x0 - px, px - e.x1));
        if (dx * dx + e.y2 <= b.d2)
          visit(e.k, px, y, b);
      }
      out[i] = b.k < m_edges.size() ? finish(b, px, y, mx, my, nullptr) : beyond(mx, my, nullptr);
      previous = b.k;
    }
  }

  /*
    Whether an edge lies within \e tol (> 0) of p: the nearest point's distance compared with tol, but only the cells
    that the box p +- tol meets are searched, and only until one edge is within (a stretch of an outline that lies on
    the target is searched for over the whole outline at every hypothesis, where its distance is not needed).
  */
  bool within(double px, double py, double tol) const
  {
    return within(px, py, tol, [](std::size_t, double) { return true; });
  }
  /*
    The same over the edges \e accept takes: accept(k, t), the nearest point of edge k at k + t (t in [0, 1]), for an
    edge within tol of p.
  */
  template <typename Accept> bool within(double px, double py, double tol, Accept accept) const
  {
    if (!std::isfinite(px) || !std::isfinite(py))
      return false;
    const double tol2 = tol * tol;
    // Edge k within tol of p, as the nearest-point search measures it, and accepted.
    auto near = [&](std::size_t k) {
      Best b;
      visit(k, px, py, b);
      if (!(b.d2 < tol2))
        return false;
      const Edge &e = m_edges[k];
      return accept(k, std::min(1.0, std::max(0.0, ((px - e.ax) * e.dx + (py - e.ay) * e.dy) * e.il2)));
    };
    if (m_first.empty()) {
      for (std::size_t k : m_kept)
        if (near(k))
          return true;
      return false;
    }
    const int i0 = cellX(px - tol), i1 = cellX(px + tol), j0 = cellY(py - tol), j1 = cellY(py + tol);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t cell = std::size_t(j) * std::size_t(m_nx) + std::size_t(i);
        for (std::size_t e = m_first[cell]; e < m_first[cell + 1]; ++e)
          if (near(m_cellEdges[e]))
            return true;
      }
    return false;
  }

private:
  double query(double px, double py, double &mx, double &my, double *along,
               double reach = std::numeric_limits<double>::infinity()) const
  {
    Best b;
    if (!std::isfinite(px) || !std::isfinite(py))
      return finish(b, px, py, mx, my, along); // no edge compared: NaN
    if (m_kept.empty())
      return beyond(mx, my, along);
    // No grid: the scan.
    if (m_first.empty()) {
      for (std::size_t k : m_kept)
        visit(k, px, py, b);
      return b.d2 > reach * reach ? beyond(mx, my, along) : finish(b, px, py, mx, my, along);
    }
    // Every edge lies in the grid's box: beyond reach of it, none is within.
    const double gx = std::max(0.0, std::max(m_x0 - px, px - (m_x0 + m_nx * m_h)));
    const double gy = std::max(0.0, std::max(m_y0 - py, py - (m_y0 + m_ny * m_h)));
    if (gx * gx + gy * gy > reach * reach)
      return beyond(mx, my, along);
    // A reach whose box p +- reach meets at most 2 x 2 cells (any reach of half a cell or less, as the fits' final
    // cut-offs are): those cells hold every edge within reach (its nearest point to p lies in the box, in a cell the
    // edge is bucketed in), searched alone. The rings would search 9 cells as soon as ring 0 holds no edge.
    if (reach > 0.0 && reach < std::numeric_limits<double>::infinity()) {
      const int i0 = cellX(px - reach), i1 = cellX(px + reach), j0 = cellY(py - reach), j1 = cellY(py + reach);
      if ((i1 - i0 + 1) * (j1 - j0 + 1) <= 4) {
        // p's own cell first: its edges are mostly the nearest, and the other cells then mostly lie farther (skipped
        // unread). The order does not change the result (equal distances: the lowest index).
        const int ci = cellX(px), cj = cellY(py);
        visitCell(ci, cj, px, py, b);
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i)
            if (i != ci || j != cj)
              visitCell(i, j, px, py, b);
        return b.d2 > reach * reach ? beyond(mx, my, along) : finish(b, px, py, mx, my, along);
      }
    }
    // Rings around p's cell, or around the nearest cell when p is outside the grid (a bent limb mapped beyond the
    // template's box: 4 % of the queries of a deformed view's fits, which scanned every edge).
    const int ci = cellX(px), cj = cellY(py);
    const int maxRing = std::max(m_nx, m_ny);
    for (int r = 0; r <= maxRing; ++r) {
      for (int j = cj - r; j <= cj + r; ++j) {
        if (j < 0 || j >= m_ny)
          continue;
        const bool edgeRow = j == cj - r || j == cj + r;
        for (int i = ci - r; i <= ci + r; i += (edgeRow || r == 0) ? 1 : 2 * r) {
          if (i >= 0 && i < m_nx)
            visitCell(i, j, px, py, b);
        }
      }
      // Every cell not searched yet lies beyond a side of the (2r + 1)^2 block that has not reached the grid's edge,
      // so it is at least as far from p as that side's line (p is inside the block on those sides: the block starts
      // at p's cell, or at the grid's edge cell nearest to p).
      double border = std::numeric_limits<double>::infinity();
      if (ci - r > 0)
        border = std::min(border, px - (m_x0 + (ci - r) * m_h));
      if (ci + r + 1 < m_nx)
        border = std::min(border, m_x0 + (ci + r + 1) * m_h - px);
      if (cj - r > 0)
        border = std::min(border, py - (m_y0 + (cj - r) * m_h));
      if (cj + r + 1 < m_ny)
        border = std::min(border, m_y0 + (cj + r + 1) * m_h - py);
      if (b.k >= m_edges.size()) {
        if (border > reach)
          return beyond(mx, my, along); // no edge within reach, and none is left there
        continue;                       // nothing yet: the next ring
      }
      if (border >= 0.0 && b.d2 <= border * border)
        break;
      // A nearer edge's nearest point lies within the best distance d of p: in a cell of the box p +- d (the cells
      // hold every edge whose box they meet, and the cell of a coordinate grows with it). Those cells not in the
      // block are searched, and that is all: a cell or two where the rings went on with a whole ring (a query a pixel
      // off a dense outline: 95 -> 82 ns). Beyond reach, only the box p +- reach matters.
      const double d = std::min(std::sqrt(b.d2), reach);
      const int i0 = cellX(px - d), i1 = cellX(px + d), j0 = cellY(py - d), j1 = cellY(py + d);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          if (std::abs(i - ci) > r || std::abs(j - cj) > r)
            visitCell(i, j, px, py, b);
      break;
    }
    return b.d2 > reach * reach ? beyond(mx, my, along) : finish(b, px, py, mx, my, along);
  }

  static double beyond(double &mx, double &my, double *along)
  {
    mx = my = 0.0;
    if (along)
      *along = 0.0;
    return std::numeric_limits<double>::infinity();
  }

  struct Best
  {
    double d2 = std::numeric_limits<double>::max(), fx = 0, fy = 0;
    bool interior = true;
    std::size_t k = std::numeric_limits<std::size_t>::max();
  };
  /*
    Whether cell (i, j) lies farther from p than the best edge found (with a relative margin for rounding): an edge's
    nearest point to p lies in a cell the edge is bucketed in, so such a cell cannot hold a nearer one. Skipping it
    leaves the result as is; of a ring's cells, most are skipped once ring 0 has found the outline a pixel away.
  */
  bool fartherThanBest(int i, int j, double px, double py, const Best &b) const
  {
    const double xa = m_x0 + i * m_h, ya = m_y0 + j * m_h;
    const double dx = std::max(0.0, std::max(xa - px, px - (xa + m_h)));
    const double dy = std::max(0.0, std::max(ya - py, py - (ya + m_h)));
    return dx * dx + dy * dy > b.d2 * (1.0 + 1e-9);
  }
  // The edges of cell (i, j) of the grid, unless it lies farther than the best.
  void visitCell(int i, int j, double px, double py, Best &b) const
  {
    if (fartherThanBest(i, j, px, py, b))
      return;
    const std::size_t cell = std::size_t(j) * std::size_t(m_nx) + std::size_t(i);
    for (std::size_t e = m_first[cell]; e < m_first[cell + 1]; ++e)
      visit(m_cellEdges[e], px, py, b);
  }
  int cellX(double x) const { return vpMorphGridCell((x - m_x0) * m_invH, m_nx); }
  int cellY(double y) const { return vpMorphGridCell((y - m_y0) * m_invH, m_ny); }
  void visit(std::size_t k, double px, double py, Best &b) const
  {
    const Edge &e = m_edges[k];
    const double ax = e.ax, ay = e.ay, dx = e.dx, dy = e.dy;
    double t = ((px - ax) * dx + (py - ay) * dy) * e.il2;
    bool in = true;
    if (t <= 0.0) {
      t = 0.0;
      in = false;
    } else if (t >= 1.0) {
      t = 1.0;
      in = false;
    }
    const double qx = ax + t * dx, qy = ay + t * dy;
    const double d2 = (px - qx) * (px - qx) + (py - qy) * (py - qy);
    if (d2 < b.d2 || (d2 == b.d2 && k < b.k)) {
      b.d2 = d2;
      b.k = k;
      b.fx = qx;
      b.fy = qy;
      b.interior = in;
    }
  }
  double finish(const Best &b, double px, double py, double &mx, double &my, double *along) const
  {
    if (b.k >= m_edges.size()) { // no edge compared: a non-finite query point (a map that overflowed)
      mx = my = 0.0;
      if (along)
        *along = 0.0;
      return std::numeric_limits<double>::quiet_NaN();
    }
    const double nx = m_edges[b.k].nx, ny = m_edges[b.k].ny;
    const double ex = px - b.fx, ey = py - b.fy, e = b.interior ? 0.0 : std::hypot(ex, ey);
    if (b.interior || e <= 0.0) {
      mx = nx;
      my = ny;
      if (along)
        *along = 1.0;
      return nx * ex + ny * ey;
    }
    mx = ex / e;
    my = ey / e;
    if (along)
      *along = mx * nx + my * ny;
    return e;
  }

  struct Edge
  {
    double ax, ay, dx, dy;
    double il2;    // 1 / (dx^2 + dy^2), 0 for a null edge: a product where a division was a visit's longest step
    double nx, ny; // the unit normal (0, 1 for a null edge), computed once: a query used to take two hypot()s
  };
  std::vector<Edge> m_edges;
  std::vector<std::size_t> m_kept;                // the edges searched, increasing
  double m_x0 = 0, m_y0 = 0, m_h = 1, m_invH = 1; // m_invH: a product instead of two divisions per query
  int m_nx = 0, m_ny = 0;
  std::vector<std::size_t> m_first, m_cellEdges; // empty without a grid
};

#endif
