/*
  \file vpMorphPixelChain.h
  \brief Internal to the morph module (not installed): the errors of chords over a closed pixel chain, for
  vpMorphPolygonApproximation.
*/
#ifndef VP_MORPH_PIXEL_CHAIN_H
#define VP_MORPH_PIXEL_CHAIN_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <visp3/morph/vpMorphPolygonApproximation.h>

/*
  A closed chain of pixels, indexed by unwrapped indices (i and i + n are the same pixel), and the errors of the
  chord between two of its pixels: the distances of the pixels between them to that segment (error(): their sum, the
  largest and where; l1(): the sum alone, abandoned past a limit; lowerBound(): a bound of the sum in O(1)). The chain
  is referenced, not copied: it must outlive this object.
*/
class vpMorphPixelChain
{
public:
  struct Pt {
    double x, y;
  };

  // Errors of the chain pixels a..b (unwrapped indices, inclusive) against the segment from pixel a to pixel b.
  struct EdgeError {
    double sum = 0.0, max = 0.0, tol = 1.0;
    std::size_t count = 0;
    std::ptrdiff_t argmax = -1; // unwrapped index of the farthest interior pixel
    double mean() const { return count ? sum / static_cast<double>(count) : 0.0; }
  };

  explicit vpMorphPixelChain(const std::vector<Pt> &p) : m_p(p), m_n(static_cast<std::ptrdiff_t>(p.size()))
  {
    // Prefix sums over the unwrapped indices [-n, 2n), the range of the vertices' neighbours. Only for integer
    // coordinates below 2^20 (image pixels): then every sum, and the cross product lowerBound() takes of them, is
    // exact in doubles.
    bool integral = true;
    double big = 1.0;
    for (const Pt &q : p) {
      integral = integral && q.x == std::floor(q.x) && q.y == std::floor(q.y) && std::fabs(q.x) < 1048576.0 &&
                 std::fabs(q.y) < 1048576.0;
      big = std::max(big, std::max(std::fabs(q.x), std::fabs(q.y)));
    }
    if (!integral || m_n > 1048576)
      return;
    // A distance near 0 is computed with an absolute error of a few ulps of the coordinates, not a relative one.
    m_slack = 1e-12 * static_cast<double>(m_n) * big;
    m_sx.assign(static_cast<std::size_t>(3 * m_n + 1), 0.0);
    m_sy.assign(m_sx.size(), 0.0);
    for (std::ptrdiff_t i = -m_n; i < 2 * m_n; ++i) {
      const std::size_t k = static_cast<std::size_t>(i + m_n);
      m_sx[k + 1] = m_sx[k] + at(i).x;
      m_sy[k + 1] = m_sy[k] + at(i).y;
    }
  }

  // The unwrapped indices are mostly within one turn of [0, n): a comparison then, not a division.
  std::ptrdiff_t wrap(std::ptrdiff_t i) const
  {
    if (i >= 0 && i < m_n)
      return i;
    if (i < 0 && i >= -m_n)
      return i + m_n;
    if (i >= m_n && i < 2 * m_n)
      return i - m_n;
    return ((i % m_n) + m_n) % m_n;
  }
  const Pt &at(std::ptrdiff_t i) const { return m_p[static_cast<std::size_t>(wrap(i))]; }
  std::ptrdiff_t size() const { return m_n; }

  // Pixel coordinates are small integers: sqrt of the squared norm is as exact as std::hypot (which guards against
  // overflow at a cost: it was half of the extraction's time) for them.
  static double segDist(const Pt &a, const Pt &b, const Pt &q)
  {
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    if (l2 <= 0.0)
      return norm(q.x - a.x, q.y - a.y);
    double t = ((q.x - a.x) * dx + (q.y - a.y) * dy) / l2;
    t = std::min(1.0, std::max(0.0, t));
    return norm(q.x - (a.x + t * dx), q.y - (a.y + t * dy));
  }
  static double norm(double x, double y) { return std::sqrt(x * x + y * y); }

  /*! Distances of the chain pixels from index \e w on (up to kBlock of them, contiguous: not past the chain's end, nor
    past unwrapped index \e b) to the segment [pa, pb], into \e d; returns how many. Two at a time where SSE2 is
    there: its square roots and divisions round as the scalar ones do, so each distance is segDist()'s to the bit,
    whichever path computes it (as long as the compiler fuses no multiply-add: x86-64 without -mfma, this project's
    flags). */
  static constexpr std::ptrdiff_t kBlock = 16;
  std::ptrdiff_t blockDistances(const Pt &pa, const Pt &pb, std::ptrdiff_t i, std::ptrdiff_t w, std::ptrdiff_t b,
                                double *d) const
  {
    const std::ptrdiff_t len = blockLength(i, w, b);
    const Pt *q = &m_p[static_cast<std::size_t>(w)];
    std::ptrdiff_t k = 0;
#ifdef __SSE2__
    const double dx = pb.x - pa.x, dy = pb.y - pa.y, l2 = dx * dx + dy * dy;
    if (l2 > 0.0) {
      const __m128d vax = _mm_set1_pd(pa.x), vay = _mm_set1_pd(pa.y), vdx = _mm_set1_pd(dx), vdy = _mm_set1_pd(dy),
                    vl2 = _mm_set1_pd(l2), zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0);
      for (; k + 1 < len; k += 2) {
        const __m128d p0 = _mm_loadu_pd(&q[k].x), p1 = _mm_loadu_pd(&q[k + 1].x);
        const __m128d x = _mm_unpacklo_pd(p0, p1), y = _mm_unpackhi_pd(p0, p1);
        // segDist(): t = min(1, max(0, t)) is (t < 1 ? t : 1) of (0 < t ? t : 0), as minpd / maxpd with t first.
        __m128d t =
            _mm_div_pd(_mm_add_pd(_mm_mul_pd(_mm_sub_pd(x, vax), vdx), _mm_mul_pd(_mm_sub_pd(y, vay), vdy)), vl2);
        t = _mm_min_pd(_mm_max_pd(t, zero), one);
        const __m128d rx = _mm_sub_pd(x, _mm_add_pd(vax, _mm_mul_pd(t, vdx)));
        const __m128d ry = _mm_sub_pd(y, _mm_add_pd(vay, _mm_mul_pd(t, vdy)));
        _mm_storeu_pd(&d[k], _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(rx, rx), _mm_mul_pd(ry, ry))));
      }
    }
#endif
    for (; k < len; ++k)
      d[k] = segDist(pa, pb, q[k]);
    return len;
  }
  std::ptrdiff_t next(std::ptrdiff_t w, std::ptrdiff_t len) const { return w + len == m_n ? 0 : w + len; }
  // The pixels of a block from unwrapped index i (stored at w) up to b: at most kBlock, contiguous in storage.
  std::ptrdiff_t blockLength(std::ptrdiff_t i, std::ptrdiff_t w, std::ptrdiff_t b) const
  {
    return std::min(kBlock, std::min(b - i, m_n - w));
  }

  EdgeError error(std::ptrdiff_t a, std::ptrdiff_t b) const
  {
    EdgeError e;
    const Pt &pa = at(a), &pb = at(b);
    e.tol = vpMorphPolygonApproximation::tolerance(pa.x, pa.y, pb.x, pb.y);
    double d[kBlock];
    for (std::ptrdiff_t i = a + 1, w = wrap(i); i < b;) {
      const std::ptrdiff_t len = blockDistances(pa, pb, i, w, b, d);
      for (std::ptrdiff_t k = 0; k < len; ++k) {
        e.sum += d[k];
        if (d[k] > e.max) {
          e.max = d[k];
          e.argmax = i + k;
        }
      }
      i += len;
      w = next(w, len);
    }
    e.count = static_cast<std::size_t>(std::max<std::ptrdiff_t>(b - a + 1, 1));
    return e;
  }

  // L1 error only (the quantity refinement minimises). The sum stops once base + sum reaches \e limit (then the value
  // returned is no longer the error, but base + it is still >= limit): the terms are >= 0 and rounding is monotone,
  // so base + the whole sum could not have come under the limit either. The limit is checked once per block of
  // distances (an abandoned sum comes out larger, still >= limit).
  // On a chain of integer pixels, a pixel that projects inside the chord is |cross| / |chord| from it, and the
  // crosses are integers: their sum is exact in any order (under 2^53, as an image's are), and divided once (no square
  // root or division per pixel); the pixels beyond an end (near a corner) add their distances to the end. Elsewhere
  // the distances are added one by one in the chain's order.
  double l1(std::ptrdiff_t a, std::ptrdiff_t b, double base = 0.0,
            double limit = std::numeric_limits<double>::infinity()) const
  {
    const Pt &pa = at(a), &pb = at(b);
    const double dx = pb.x - pa.x, dy = pb.y - pa.y, l2 = dx * dx + dy * dy;
    if (!m_sx.empty() && l2 > 0.0) {
      const double len = std::sqrt(l2);
      double inside = 0.0, beyond = 0.0; // the sum of |cross| inside, of the distances beyond the ends
#ifdef __SSE2__
      const __m128d vax = _mm_set1_pd(pa.x), vay = _mm_set1_pd(pa.y), vdx = _mm_set1_pd(dx), vdy = _mm_set1_pd(dy),
                    vl2 = _mm_set1_pd(l2), zero = _mm_setzero_pd(), sign = _mm_set1_pd(-0.0);
#endif
      for (std::ptrdiff_t i = a + 1, w = wrap(i); i < b && base + inside / len + beyond < limit;) {
        const std::ptrdiff_t count = blockLength(i, w, b);
        const Pt *q = &m_p[static_cast<std::size_t>(w)];
        std::ptrdiff_t k = 0;
#ifdef __SSE2__
        // Two pixels at a time while both project inside (integers: the order of the sum does not change it).
        __m128d acc = _mm_setzero_pd();
        for (; k + 1 < count; k += 2) {
          const __m128d p0 = _mm_loadu_pd(&q[k].x), p1 = _mm_loadu_pd(&q[k + 1].x);
          const __m128d ex = _mm_sub_pd(_mm_unpacklo_pd(p0, p1), vax), ey = _mm_sub_pd(_mm_unpackhi_pd(p0, p1), vay);
          const __m128d dot = _mm_add_pd(_mm_mul_pd(ex, vdx), _mm_mul_pd(ey, vdy));
          if (_mm_movemask_pd(_mm_or_pd(_mm_cmplt_pd(dot, zero), _mm_cmpgt_pd(dot, vl2))) != 0)
            break; // a pixel beyond an end: the rest of the block one by one
          acc = _mm_add_pd(acc, _mm_andnot_pd(sign, _mm_sub_pd(_mm_mul_pd(ex, vdy), _mm_mul_pd(ey, vdx))));
        }
        double lanes[2];
        _mm_storeu_pd(lanes, acc);
        inside += lanes[0] + lanes[1];
#endif
        for (; k < count; ++k) {
          const double ex = q[k].x - pa.x, ey = q[k].y - pa.y, dot = ex * dx + ey * dy;
          if (dot < 0.0)
            beyond += norm(ex, ey);
          else if (dot > l2)
            beyond += norm(q[k].x - pb.x, q[k].y - pb.y);
          else
            inside += std::fabs(ex * dy - ey * dx);
        }
        i += count;
        w = next(w, count);
      }
      return inside / len + beyond;
    }
    double s = 0.0, d[kBlock];
    for (std::ptrdiff_t i = a + 1, w = wrap(i); i < b && base + s < limit;) {
      const std::ptrdiff_t len = blockDistances(pa, pb, i, w, b, d);
      for (std::ptrdiff_t k = 0; k < len; ++k)
        s += d[k];
      i += len;
      w = next(w, len);
    }
    return s;
  }

  // A lower bound of l1(a, b), in O(1): each pixel's distance to the segment is at least its distance to the
  // segment's line, and the sum of those is at least the absolute value of the sum of the signed ones, which the
  // prefix sums give exactly. 0 when no prefix sums were built, or for a < -n or b > 2n.
  double lowerBound(std::ptrdiff_t a, std::ptrdiff_t b) const
  {
    if (m_sx.empty() || b - a < 2 || a < -m_n || b > 2 * m_n)
      return 0.0;
    const Pt &pa = at(a), &pb = at(b);
    const double dx = pb.x - pa.x, dy = pb.y - pa.y, l2 = dx * dx + dy * dy;
    if (l2 <= 0.0)
      return 0.0;
    const std::size_t i0 = static_cast<std::size_t>(a + 1 + m_n), i1 = static_cast<std::size_t>(b + m_n);
    const double m = static_cast<double>(b - a - 1);
    const double cross = (m_sx[i1] - m_sx[i0] - m * pa.x) * dy - (m_sy[i1] - m_sy[i0] - m * pa.y) * dx;
    return std::fabs(cross) / std::sqrt(l2);
  }

  /*! Whether every l1(a, b, base, limit) whose exact value is at least \e bound comes out >= limit: the bound
    lowered by more than the rounding of the sums (under 1e-11 relative for chains of up to 2^20 pixels, plus the
    absolute error of distances near 0) and of the bound's division and square root. */
  bool atLeast(double bound, double limit) const { return bound * (1.0 - 1e-10) - m_slack >= limit; }

private:
  const std::vector<Pt> &m_p;
  std::ptrdiff_t m_n;
  std::vector<double> m_sx, m_sy; // prefix sums of the coordinates from index -n, when exact
  double m_slack = 0.0;
};

#endif
