#include "vpMorphSimilarityFit.h"

#include <cmath>
#include <utility>
#include <vector>

#include "vpMorphRigidShapeData.h"

namespace vpMorphSimilarityFit
{
namespace
{
constexpr int kGrid = vpMorphRigidShapeData::kGrid;
static_assert(vpMorphRigidShapeData::kLanes == 4, "a batch is one vector of four floats");

// Four points at once, in GCC's and Clang's vector types (SIMD registers where the target has them, scalar code
// otherwise). Float: its 1e-7 of a size is far below a grid cell.
typedef float F4 __attribute__((vector_size(16)));
typedef int I4 __attribute__((vector_size(16)));

inline F4 load(const std::vector<float> &v, std::size_t i) { return F4{v[i], v[i + 1], v[i + 2], v[i + 3]}; }
inline F4 masked(F4 v, I4 mask) { return reinterpret_cast<F4>(reinterpret_cast<I4>(v) & mask); }
inline F4 absolute(F4 v) { return reinterpret_cast<F4>(reinterpret_cast<I4>(v) & (I4{} + 0x7fffffff)); }
inline double sum(F4 v) { return (static_cast<double>(v[0]) + v[1]) + (static_cast<double>(v[2]) + v[3]); }
// Lanes i, ..., i + 3 that are below n (the arrays are padded beyond).
inline I4 below(std::size_t i, std::size_t n) { return (I4{0, 1, 2, 3} + static_cast<int>(i)) < static_cast<int>(n); }

// Bilinear signed distance of t's grid and its gradient at the normalised points (X, Y); the lanes on the grid (-1,
// the others 0, which read its first cell).
inline I4 gridAt(const vpMorphRigidShapeData &t, F4 X, F4 Y, F4 &d, F4 &gx, F4 &gy)
{
  const float lo = static_cast<float>(t.lo), inv = static_cast<float>(t.invStep);
  constexpr float lim = static_cast<float>(kGrid - 1);
  F4 fx = (X - lo) * inv, fy = (Y - lo) * inv;
  const I4 on = (fx >= 0.0f) & (fy >= 0.0f) & (fx < lim) & (fy < lim); // false for NaN
  fx = masked(fx, on);
  fy = masked(fy, on);
  const I4 i = __builtin_convertvector(fx, I4), j = __builtin_convertvector(fy, I4);
  const F4 u = fx - __builtin_convertvector(i, F4), v = fy - __builtin_convertvector(j, F4);
  const I4 c = j * kGrid + i;
  const float *g = t.grid.data();
  const F4 p{g[c[0]], g[c[1]], g[c[2]], g[c[3]]}, q{g[c[0] + 1], g[c[1] + 1], g[c[2] + 1], g[c[3] + 1]};
  const F4 r{g[c[0] + kGrid], g[c[1] + kGrid], g[c[2] + kGrid], g[c[3] + kGrid]},
      s{g[c[0] + kGrid + 1], g[c[1] + kGrid + 1], g[c[2] + kGrid + 1], g[c[3] + kGrid + 1]};
  const F4 u1 = 1.0f - u, v1 = 1.0f - v;
  d = (p * u1 + q * u) * v1 + (r * u1 + s * u) * v;
  gx = ((q - p) * v1 + (s - r) * v) * inv;
  gy = ((r - p) * u1 + (s - q) * u) * inv;
  return on;
}

// Mean of min(|d| k, tau) / tau over the n points (xs, ys) mapped by \e m onto t's grid, tau off it.
double truncatedMean(const vpMorphRigidShapeData &t, const std::vector<float> &xs, const std::vector<float> &ys,
                     std::size_t n, const Sim &m, double k, double tau)
{
  const float a = static_cast<float>(m.a), b = static_cast<float>(m.b), tx = static_cast<float>(m.tx),
              ty = static_cast<float>(m.ty), kf = static_cast<float>(k);
  const F4 T = F4{} + static_cast<float>(tau);
  F4 acc{};
  for (std::size_t i = 0; i < n; i += 4) {
    const F4 x = load(xs, i), y = load(ys, i);
    F4 d, gx, gy;
    const I4 on = gridAt(t, a * x - b * y + tx, b * x + a * y + ty, d, gx, gy);
    const F4 e = absolute(d) * kf, truncated = e < T ? e : T;
    acc += masked(on ? truncated : T, below(i, n));
  }
  return sum(acc) / (tau * static_cast<double>(n));
}

// Solves the 4x4 symmetric system A x = b in place (Gaussian elimination with partial pivoting); false if singular.
bool solve4(double A[4][4], double b[4])
{
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c]))
        p = r;
    if (!(std::fabs(A[p][c]) > 1e-300))
      return false;
    if (p != c) {
      std::swap(A[p], A[c]);
      std::swap(b[p], b[c]);
    }
    for (int r = c + 1; r < 4; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int k = c; k < 4; ++k)
        A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int c = 3; c >= 0; --c) {
    for (int k = c + 1; k < 4; ++k)
      b[c] -= A[c][k] * b[k];
    b[c] /= A[c][c];
  }
  return true;
}
} // namespace

Sim compose(const Sim &s, const Sim &t)
{
  return Sim{s.a * t.a - s.b * t.b, s.b * t.a + s.a * t.b, s.a * t.tx - s.b * t.ty + s.tx,
             s.b * t.tx + s.a * t.ty + s.ty};
}

Sim toSim(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const vpMorphRigidTransform &T)
{
  // T: x' = s R (x - c) + c + t in pixels; normalised: X = (s in.size / t.size) R x + (T(in.c) - t.c) / t.size.
  double ox, oy;
  T.apply(in.cx, in.cy, ox, oy);
  const double k = T.scale() * in.size / t.size;
  return Sim{k * std::cos(T.theta()), k * std::sin(T.theta()), (ox - t.cx) / t.size, (oy - t.cy) / t.size};
}

vpMorphRigidTransform toPixels(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s)
{
  const double k = std::hypot(s.a, s.b);
  return vpMorphRigidTransform(std::atan2(s.b, s.a), t.cx - in.cx + s.tx * t.size, t.cy - in.cy + s.ty * t.size,
                               k * t.size / in.size, in.cx, in.cy);
}

double inputCost(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s, double tau)
{
  return truncatedMean(t, in.inputX, in.inputY, in.inputs.size(), s, 1.0, tau);
}

double targetCost(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s, double tau)
{
  const double s2 = s.a * s.a + s.b * s.b;
  if (!(s2 > 0.0) || !std::isfinite(s2))
    return 1.0;
  // The inverse similarity lays the target's samples on the input; their distances, in input sizes, times the scale
  // are in the target's.
  const double a = s.a / s2, b = -s.b / s2;
  const Sim inverse{a, b, -(a * s.tx - b * s.ty), -(b * s.tx + a * s.ty)};
  return truncatedMean(in, t.evenX, t.evenY, (t.x.size() + 1) / 2, inverse, std::sqrt(s2), tau);
}

Sim refine(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, Sim s, double tau, int iterations)
{
  const std::size_t n = in.inputs.size();
  const float T = static_cast<float>(tau);
  for (int it = 0; it < iterations; ++it) {
    const float a = static_cast<float>(s.a), b = static_cast<float>(s.b), tx = static_cast<float>(s.tx),
                ty = static_cast<float>(s.ty);
    // Per lane: the normal equations' 10 distinct entries, the right-hand side's 4, the samples used.
    F4 AtA[10] = {}, Atr[4] = {}, used{};
    for (std::size_t i = 0; i < n; i += 4) {
      const F4 x = load(in.inputX, i), y = load(in.inputY, i);
      F4 r, gx, gy;
      const I4 on = gridAt(t, a * x - b * y + tx, b * x + a * y + ty, r, gx, gy);
      const I4 w = on & (absolute(r) <= T) & below(i, n);
      gx = masked(gx, w);
      gy = masked(gy, w);
      r = masked(r, w);
      const F4 J[4] = {gx * x + gy * y, gy * x - gx * y, gx, gy};
      int e = 0;
      for (int p = 0; p < 4; ++p) {
        Atr[p] -= J[p] * r;
        for (int q = p; q < 4; ++q, ++e)
          AtA[e] += J[p] * J[q];
      }
      used += masked(F4{} + 1.0f, w);
    }
    if (sum(used) < 4.0)
      break;
    double A[4][4], B[4];
    int e = 0;
    for (int p = 0; p < 4; ++p) {
      B[p] = sum(Atr[p]);
      for (int q = p; q < 4; ++q, ++e)
        A[p][q] = A[q][p] = sum(AtA[e]);
    }
    for (int p = 0; p < 4; ++p)
      A[p][p] *= 1.0 + 1e-6; // Levenberg's damping: a flat direction (a straight edge) stays put
    if (!solve4(A, B))
      break;
    s.a += B[0];
    s.b += B[1];
    s.tx += B[2];
    s.ty += B[3];
    if (std::fabs(B[0]) + std::fabs(B[1]) + std::fabs(B[2]) + std::fabs(B[3]) < 1e-4)
      break; // converged: a ten-thousandth of a size
  }
  return s;
}
} // namespace vpMorphSimilarityFit
