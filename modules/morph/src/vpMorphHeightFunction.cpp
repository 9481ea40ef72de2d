#include <visp3/morph/vpMorphHeightFunction.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

vpMorphHeightFunction::vpMorphHeightFunction() : m_points(0), m_segments(0), m_skip(0.3), m_mirrors(true), m_starts(4)
{
  setPoints(100, 20);
}

void vpMorphHeightFunction::setPoints(std::size_t points, std::size_t segments)
{
  if (points < 8 || segments < 2 || segments > points || points % segments != 0) {
    std::ostringstream os;
    os << "vpMorphHeightFunction: " << points << " points in " << segments
       << " segments (at least 8 points, at least 2 segments dividing them)";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  m_points = points;
  m_segments = segments;
  // Segment m is centred on the point m * k further along (k = points / segments); its weight falls as the inverse
  // of that distance in segments, one added so that the point's own segment (its curvature) weighs most, not without
  // bound. Normalised to sum 1: a point's cost is in [0, 2].
  m_weights.assign(segments, 0.0f);
  double sum = 0.0;
  for (std::size_t m = 0; m < segments; ++m) {
    const double d = static_cast<double>(std::min(m, segments - m));
    m_weights[m] = static_cast<float>(1.0 / (1.0 + d));
    sum += m_weights[m];
  }
  for (float &w : m_weights)
    w = static_cast<float>(w / sum);
}

void vpMorphHeightFunction::setSkipCost(double c)
{
  if (!std::isfinite(c) || c <= 0.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphHeightFunction: the skip cost must be finite and positive");
  m_skip = c;
}

std::vector<float> vpMorphHeightFunction::heights(const vpMorphContour &c) const
{
  if (c.size() < 3 || !(c.area() > 0.0))
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphHeightFunction: the outline needs at least 3 vertices and a positive area");
  const std::size_t N = m_points, M = m_segments, k = N / M;
  const vpMorphContour r = c.counterClockwise().resampled(N);
  std::vector<float> F(N * M, 0.0f);
  const std::size_t half = k / 2; // segment m holds the points m * k - half .. m * k - half + k - 1 further along
  for (std::size_t i = 0; i < N; ++i) {
    const std::size_t prev = (i + N - 1) % N, next = (i + 1) % N;
    double tx = r.x(next) - r.x(prev), ty = r.y(next) - r.y(prev);
    const double tn = std::hypot(tx, ty);
    if (tn > 0.0) {
      tx /= tn;
      ty /= tn;
    }
    // Left normal of a counter-clockwise traversal: towards the inside.
    const double nx = -ty, ny = tx;
    for (std::size_t m = 0; m < M; ++m) {
      double s = 0.0;
      for (std::size_t q = 0; q < k; ++q) {
        const std::size_t j = (i + m * k + N - half + q) % N;
        s += (r.x(j) - r.x(i)) * nx + (r.y(j) - r.y(i)) * ny;
      }
      F[i * M + m] = static_cast<float>(s / static_cast<double>(k));
    }
  }
  for (std::size_t m = 0; m < M; ++m) {
    float mx = 0.0f;
    for (std::size_t i = 0; i < N; ++i)
      mx = std::max(mx, std::fabs(F[i * M + m]));
    if (mx > 0.0f)
      for (std::size_t i = 0; i < N; ++i)
        F[i * M + m] /= mx;
  }
  return F;
}

vpMorphHeightFunction::Descriptor vpMorphHeightFunction::describe(const vpMorphContour &c) const
{
  Descriptor d;
  d.direct = heights(c);
  if (m_mirrors)
    d.mirrored = heights(c.mirrored());
  return d;
}

namespace
{
// Least cost of an order-preserving correspondence of the N points of a with those of b from b's point s on (C[i *
// N + j]: cost of matching a_i with b_j; a point left out costs skip).
float closedCost(const std::vector<float> &C, std::size_t N, std::size_t s, float skip, std::vector<float> &prev,
                 std::vector<float> &cur)
{
  for (std::size_t j = 0; j <= N; ++j)
    prev[j] = skip * static_cast<float>(j);
  for (std::size_t i = 1; i <= N; ++i) {
    const float *Ci = &C[(i - 1) * N];
    cur[0] = skip * static_cast<float>(i);
    for (std::size_t j = 1; j <= N; ++j) {
      std::size_t jb = j - 1 + s;
      if (jb >= N)
        jb -= N;
      cur[j] = std::min(prev[j - 1] + Ci[jb], std::min(prev[j], cur[j - 1]) + skip);
    }
    std::swap(prev, cur);
  }
  return prev[N];
}
} // namespace

double vpMorphHeightFunction::oriented(const std::vector<float> &a, const std::vector<float> &b) const
{
  const std::size_t N = m_points, M = m_segments;
  // Cost matrix: C[i * N + j] matches point i of a with point j of b.
  std::vector<float> C(N * N);
  for (std::size_t i = 0; i < N; ++i) {
    const float *ai = &a[i * M];
    for (std::size_t j = 0; j < N; ++j) {
      const float *bj = &b[j * M];
      float s = 0.0f;
      for (std::size_t m = 0; m < M; ++m)
        s += m_weights[m] * std::fabs(ai[m] - bj[m]);
      C[i * N + j] = s;
    }
  }
  const float skip = static_cast<float>(m_skip);
  std::vector<float> prev(N + 1), cur(N + 1);
  float best = std::numeric_limits<float>::infinity();
  if (m_starts == 0) {
    for (std::size_t s = 0; s < N; ++s)
      best = std::min(best, closedCost(C, N, s, skip, prev, cur));
    return static_cast<double>(best) / static_cast<double>(N);
  }
  // Candidates: the local minima of the cost of the correspondence that skips nothing (a start next to a better one
  // is the same basin: the skips reach it), the cheapest first.
  std::vector<double> diag(N, 0.0);
  for (std::size_t s = 0; s < N; ++s)
    for (std::size_t i = 0; i < N; ++i)
      diag[s] += C[i * N + (i + s) % N];
  std::vector<std::pair<double, std::size_t>> starts;
  for (std::size_t s = 0; s < N; ++s)
    if (diag[s] <= diag[(s + N - 1) % N] && diag[s] <= diag[(s + 1) % N])
      starts.emplace_back(diag[s], s);
  const std::size_t tried = std::min(m_starts, starts.size());
  std::partial_sort(starts.begin(), starts.begin() + static_cast<long>(tried), starts.end());
  for (std::size_t t = 0; t < tried; ++t)
    best = std::min(best, closedCost(C, N, starts[t].second, skip, prev, cur));
  return static_cast<double>(best) / static_cast<double>(N);
}

double vpMorphHeightFunction::distance(const Descriptor &a, const Descriptor &b, bool *mirrored) const
{
  const std::size_t n = m_points * m_segments;
  if (a.direct.size() != n || b.direct.size() != n || (m_mirrors && b.mirrored.size() != n))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphHeightFunction: descriptors made with other settings");
  const double d = oriented(a.direct, b.direct);
  const double dm = m_mirrors ? oriented(a.direct, b.mirrored) : d;
  if (mirrored)
    *mirrored = dm < d;
  return std::min(d, dm);
}
