#include <visp3/morph/vpMorphMatcher.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphOutlineShare.h"

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
// Gap between two solved starts below which Maes' recursion solves the starts in between directly.
constexpr int kDirectGap = 4;
// Widest range of starts whose lower bound is computed before solving it (see solveBetween()).
constexpr int kBoundGap = 8;
// One row of the dynamic programme on columns [l, r]: D[i][j] = min(D[i-1][j-1] + cd[j], D[i-1][j] + ca,
// D[i][j-1] + cB[j]). With P[j] the prefix sum of cB, D[i][j] - P[j] is the running minimum of
// y[j] = min(diagonal, A step) - P[j] along the row: the serial part is a bare minimum, run as two
// independent chains over the two halves of the row (then the first half's minimum is carried into the
// second), and the rest vectorises. prev must be +inf where the previous row has no cell.
__attribute__((always_inline)) inline void dpRow(const double *__restrict prev, const double *__restrict cd, double ca,
                                                 const double *__restrict pB, int l, int r, double *__restrict cur)
{
  if (r - l < 16) {
    // Short rows (the narrow bands deep in Maes' recursion): one pass, no set-up to amortise; the chain from
    // cell to cell is the running minimum alone.
    double run = kInf;
    for (int j = l; j <= r; ++j) {
      const double up = prev[j] + ca, dg = prev[j - 1] + cd[j];
      const double y = (up < dg ? up : dg) - pB[j];
      run = y < run ? y : run;
      cur[j] = run + pB[j];
    }
    return;
  }
  for (int j = l; j <= r; ++j) {
    const double up = prev[j] + ca, dg = prev[j - 1] + cd[j];
    cur[j] = (up < dg ? up : dg) - pB[j];
  }
  const int half = (r - l + 1) / 2, mid = l + half;
  double run0 = cur[l], run1 = cur[mid];
  for (int t = 0; t < half; ++t) {
    const double y0 = cur[l + t], y1 = cur[mid + t];
    run0 = y0 < run0 ? y0 : run0;
    run1 = y1 < run1 ? y1 : run1;
    cur[l + t] = run0;
    cur[mid + t] = run1;
  }
  if (mid + half <= r) { // odd length: the last cell
    const double y = cur[r];
    cur[r] = y < run1 ? y : run1;
  }
  for (int j = mid; j <= r; ++j)
    cur[j] = cur[j] < run0 ? cur[j] : run0;
  for (int j = l; j <= r; ++j)
    cur[j] += pB[j];
}
} // namespace

vpMorphMatcher::vpMorphMatcher(const vpMorphWorkModel &model, bool normalizeScale)
  : m_model(model), m_normalizeScale(normalizeScale)
{
}

void vpMorphMatcher::checkStart(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b)
{
  if (A.empty() || B.empty())
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphMatcher: cannot match an empty contour (default-constructed vpMorphContour)");
  if (A.units() != B.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphMatcher: the two contours are in different units (pixel vs normalised)");
  if (a >= A.size() || b >= B.size()) {
    std::ostringstream os;
    os << "vpMorphMatcher: starting pair (" << a << ", " << b << ") is out of range for polygons of " << A.size()
       << " and " << B.size() << " vertices";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}

__attribute__((target_clones("avx2", "default"))) void
vpMorphMatcher::prepare(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b)
{
  checkStart(A, B, a, b);
  m_m = A.size();
  m_n = B.size();
  m_a0 = a;
  m_b0 = b;
  // Both polygons are traversed with positive signed area, so that D(A, B) does not depend on the direction
  // in which their vertices were listed; indices are mapped back to the caller's numbering at the end.
  m_reversedA = A.signedArea() < 0;
  m_reversedB = B.signedArea() < 0;
  const double sA = m_normalizeScale ? 1.0 / A.perimeter() : 1.0;
  const double sB = m_normalizeScale ? 1.0 / B.perimeter() : 1.0;
  const std::size_t m = m_m, n = m_n;
  // Incoming edge length and turning angle of vertex r of the positive traversal of C.
  auto vertex = [](const vpMorphContour &C, bool reversed, std::size_t r, double &len, double &phi) {
    const std::size_t N = C.size();
    if (!reversed) {
      len = C.edgeLength(r);
      phi = C.turningAngle(r);
    } else {
      // Vertex r of the reversed traversal is vertex (N - r) % N; its incoming edge is that vertex's
      // outgoing one, and its left turns become right turns.
      const std::size_t o = (N - r) % N;
      len = C.edgeLength((o + 1) % N);
      phi = -C.turningAngle(o);
    }
  };
  // Row i of the grid is A's vertex (a + i) mod m.
  m_lenA.resize(m);
  m_phiA.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    vertex(A, m_reversedA, (a + i) % m, m_lenA[i], m_phiA[i]);
    m_lenA[i] *= sA;
  }
  // Column j of the grid is B's vertex (b + j) mod n; columns are doubled (0 .. 2n-1) so that every path of
  // the cyclic problem lies on a plane grid.
  m_lenB.resize(2 * n);
  m_phiB.resize(2 * n);
  for (std::size_t j = 0; j < n; ++j) {
    vertex(B, m_reversedB, (b + j) % n, m_lenB[j], m_phiB[j]);
    m_lenB[j] *= sB;
    m_lenB[j + n] = m_lenB[j];
    m_phiB[j + n] = m_phiB[j];
  }

  // Step costs: A-only and B-only steps depend on one vertex; diagonal steps on the cell (table m x 2n).
  const double kb = m_model.kb();
  m_costA.resize(m);
  for (std::size_t i = 0; i < m; ++i)
    m_costA[i] = m_model.stretching(m_lenA[i], 0.0) + kb * m_phiA[i] * m_phiA[i];
  m_costB.resize(2 * n);
  m_prefB.resize(2 * n);
  for (std::size_t j = 0; j < 2 * n; ++j) {
    m_costB[j] = m_model.stretching(0.0, m_lenB[j]) + kb * m_phiB[j] * m_phiB[j];
    m_prefB[j] = (j ? m_prefB[j - 1] : 0.0) + m_costB[j];
  }
  // Diagonal steps: Eq. 2 + Eq. 3 written out so that the loop vectorises (same values as
  // vpMorphWorkModel::stretching() and bending()).
  m_costDiag.resize(m * 2 * n);
  const double ks = m_model.ks(), cs = m_model.cs();
  const double *__restrict lB = m_lenB.data(), *__restrict pB = m_phiB.data();
  for (std::size_t i = 0; i < m; ++i) {
    double *__restrict row = &m_costDiag[i * 2 * n];
    const double lA = m_lenA[i], pA = m_phiA[i];
    for (std::size_t j = 0; j < n; ++j) {
      const double lmin = lA < lB[j] ? lA : lB[j], lmax = lA < lB[j] ? lB[j] : lA;
      const double dl = lB[j] - lA, dp = pB[j] - pA;
      row[j] = ks * dl * dl / ((1.0 - cs) * lmin + cs * lmax) + kb * dp * dp;
    }
    std::copy(row, row + n, row + n);
  }
}

// Minimal work of a path from (0, b) to (m, b + n) whose row i stays within the columns spanned by the path
// \e lo (leftmost) and the path \e hi (rightmost) in that row; null bounds: unconstrained. On request, traces
// the path back: its extent per row (\e extent) and its cells from (0, b) to (m, b + n) (\e cells).
// Built twice, for AVX2 and for any x86-64, and chosen at load time: the row passes vectorise 4 wide where the
// processor allows it, and the library still runs everywhere.
__attribute__((target_clones("avx2", "default"))) double
vpMorphMatcher::solveStart(int b, const Path *lo, const Path *hi, Path *extent, std::vector<std::pair<int, int>> *cells,
                           int bLast)
{
  const int m = static_cast<int>(m_m), n = static_cast<int>(m_n), W = 2 * n;
  // Column range of each row. Row 0 starts at b by definition; the end cell (m, b + n) is inside any band
  // whose bounding starts enclose b.
  m_L.resize(m + 2);
  m_R.resize(m + 2);
  for (int i = 0; i <= m; ++i) {
    m_L[i] = (i == 0 || !lo) ? b : std::max(b, lo->left[i]);
    m_R[i] = std::min(hi ? hi->right[i] : b + n, W - 1);
  }
  m_L[m + 1] = m_L[m];
  m_R[m + 1] = m_R[m];
  // The table D of the band, row by row. Row i is stored on columns [L(i) - 1, R(i + 1)], padded with +inf on
  // both sides, so that row i+1 reads its neighbours without bound checks.
  m_rowOff.resize(m + 2);
  m_rowOff[0] = 0;
  for (int i = 0; i <= m; ++i)
    m_rowOff[i + 1] = m_rowOff[i] + static_cast<std::size_t>(m_R[i + 1] - m_L[i] + 2);
  m_table.resize(m_rowOff[m + 1]);
  double *const table = m_table.data();
  auto row = [&](int i) { return table + m_rowOff[i] - (m_L[i] - 1); }; // row(i)[j] = D[i][j]

  {
    double *d = row(0);
    d[b - 1] = kInf;
    d[b] = 0.0; // the start cell; its own step is the one that closes the path into (m, b + n), charged there
    for (int j = b + 1; j <= m_R[0]; ++j)
      d[j] = j <= bLast ? 0.0 : d[j - 1] + m_costB[j]; // A's vertex 0 matched to B's b, b+1, ...: only B steps
    for (int j = m_R[0] + 1; j <= m_R[1]; ++j)
      d[j] = kInf;
  }
  for (int i = 1; i <= m; ++i) {
    const int l = m_L[i], r = m_R[i];
    const int ii = (i == m) ? 0 : i; // row m is A's vertex 0 again
    double *d = row(i);
    d[l - 1] = kInf;
    dpRow(row(i - 1), &m_costDiag[static_cast<std::size_t>(ii) * W], m_costA[ii], m_prefB.data(), l, r, d);
    for (int j = r + 1; j <= m_R[i + 1]; ++j)
      d[j] = kInf;
  }
  if (bLast > b) {
    // Relaxed problem: any start in [b, bLast] to any end in [b + n, bLast + n].
    double bound = kInf;
    for (int j = std::max(b + n, m_L[m]); j <= std::min(bLast + n, m_R[m]); ++j)
      bound = std::min(bound, row(m)[j]);
    return bound;
  }
  const int end = b + n;
  const double work = (end >= m_L[m] && end <= m_R[m]) ? row(m)[end] : kInf;
  if (!std::isfinite(work) || (!extent && !cells))
    return work;

  // Trace back: at each cell, the predecessor that gives the least sum (the choice the programme made, up to
  // rounding ties, which are equally optimal).
  if (extent) {
    extent->left.assign(m + 1, std::numeric_limits<int>::max());
    extent->right.assign(m + 1, std::numeric_limits<int>::min());
  }
  if (cells)
    cells->clear();
  int i = m, j = end;
  for (;;) {
    if (extent) {
      extent->left[i] = std::min(extent->left[i], j);
      extent->right[i] = std::max(extent->right[i], j);
    }
    if (cells)
      cells->emplace_back(i, j);
    if (i == 0 && j == b)
      break;
    if (i == 0) {
      --j;
      continue;
    }
    const int ii = (i == m) ? 0 : i;
    const double *p = row(i - 1);
    const double dg = p[j - 1] + m_costDiag[static_cast<std::size_t>(ii) * W + j];
    const double up = p[j] + m_costA[ii];
    const double lf = (j > m_L[i]) ? row(i)[j - 1] + m_costB[j] : kInf;
    if (dg <= up && dg <= lf) {
      --i;
      --j;
    } else if (up <= lf) {
      --i;
    } else {
      --j;
    }
  }
  if (cells)
    std::reverse(cells->begin(), cells->end()); // (0, b) ... (m, b + n)
  return work;
}

namespace
{
// Whether the path \e lo lies weakly left of \e hi in every row (Maes' bound holds between them).
bool leftOf(const std::vector<int> &loLeft, const std::vector<int> &loRight, const std::vector<int> &hiLeft,
            const std::vector<int> &hiRight)
{
  for (std::size_t i = 0; i < loLeft.size(); ++i)
    if (loLeft[i] > hiLeft[i] || loRight[i] > hiRight[i])
      return false;
  return true;
}
} // namespace

// Maes' divide and conquer: the optimal paths of starts bLo < b < bHi lie between those of bLo and bHi (null: the
// grid's edge).
void vpMorphMatcher::solveBetween(int bLo, int bHi, const Path *lo, const Path *hi, std::size_t depth, Best &best)
{
  if (bHi - bLo < 2)
    return;
  // The lemma holds for some optimal paths, not for every traced one: tied optima may be traced crossing, and the
  // band between them would be empty. Such a range is solved on the whole grid.
  if (lo && hi && !leftOf(lo->left, lo->right, hi->left, hi->right))
    lo = hi = nullptr;
  auto keep = [&](double w, int b) {
    if (w < best.work) {
      best.work = w;
      best.b = b;
      best.hasLo = lo != nullptr;
      best.hasHi = hi != nullptr;
      if (lo)
        best.lo = *lo;
      if (hi)
        best.hi = *hi;
    }
  };
  // Lower bound for every start of the range: the same programme with all of them as sources at once and any
  // of their ends as the end. A range that cannot beat the best start found so far is skipped, subtree and all.
  // Only narrow ranges are tested: the bound relaxes the start-end pairing by the range's width, so it is
  // tight (and pays for itself) only there.
  if (bHi - bLo <= kBoundGap && solveStart(bLo + 1, lo, hi, nullptr, nullptr, bHi - 1) >= best.work)
    return;
  if (bHi - bLo <= kDirectGap) {
    // A narrow band: solving its few starts directly in it costs less than tracing mid paths to split it.
    for (int b = bLo + 1; b < bHi; ++b)
      keep(solveStart(b, lo, hi, nullptr, nullptr), b);
    return;
  }
  const int mid = bLo + (bHi - bLo) / 2;
  Path &p = m_pool[depth];
  const double w = solveStart(mid, lo, hi, &p, nullptr);
  keep(w, mid);
  const Path *split = std::isfinite(w) ? &p : nullptr; // traced only when finite
  solveBetween(bLo, mid, lo, split, depth + 1, best);
  solveBetween(mid, bHi, split, hi, depth + 1, best);
}

// Best path over the starts 0 .. count-1 of the prepared problem (count <= n).
vpMorphCorrespondence vpMorphMatcher::solveRange(int count)
{
  const int n = static_cast<int>(m_n);
  Path first, last;
  Best best;
  best.work = solveStart(0, nullptr, nullptr, &first, nullptr);
  best.b = 0;
  if (count > 1) {
    if (count == n) {
      // Start n is start 0 again, shifted by one period of the doubled grid.
      last = first;
      for (int &c : last.left)
        c += n;
      for (int &c : last.right)
        c += n;
    } else {
      const double w = solveStart(count - 1, nullptr, nullptr, &last, nullptr);
      if (w < best.work) {
        best.work = w;
        best.b = count - 1;
      }
    }
    // One bounding path per recursion level, allocated once (the recursion keeps references to them).
    std::size_t levels = 1;
    while ((1 << levels) < count + 1)
      ++levels;
    m_pool.resize(levels + 1);
    solveBetween(0, count == n ? n : count - 1, &first, &last, 0, best);
  }
  // Trace the winner again, in the same band, to get its cells.
  std::vector<std::pair<int, int>> cells;
  const double w =
      solveStart(best.b, best.hasLo ? &best.lo : nullptr, best.hasHi ? &best.hi : nullptr, nullptr, &cells);
  return toCorrespondence(cells, w);
}

vpMorphCorrespondence vpMorphMatcher::toCorrespondence(const std::vector<std::pair<int, int>> &cells, double tableWork)
{
  const std::size_t m = m_m, n = m_n;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  pairs.reserve(cells.size());
  double stretching = 0.0, bending = 0.0;
  for (std::size_t k = 0; k + 1 < cells.size(); ++k) {
    const int i = cells[k].first, j = cells[k].second;
    const std::size_t ra = (m_a0 + static_cast<std::size_t>(i)) % m, rb = (m_b0 + static_cast<std::size_t>(j)) % n;
    pairs.emplace_back(m_reversedA ? (m - ra) % m : ra, m_reversedB ? (n - rb) % n : rb);
    // Work of the step into the next cell (the last one closes the path onto the start).
    const int i1 = cells[k + 1].first, j1 = cells[k + 1].second;
    const std::size_t ii = static_cast<std::size_t>(i1) % m;
    const double lA = (i1 != i) ? m_lenA[ii] : 0.0, lB = (j1 != j) ? m_lenB[j1] : 0.0;
    const double pA = (i1 != i) ? m_phiA[ii] : 0.0, pB = (j1 != j) ? m_phiB[j1] : 0.0;
    stretching += m_model.stretching(lA, lB);
    bending += m_model.bending(pA, pB);
  }
  // The programme optimises the cost tables; the work is reported from the model. They must agree, or the
  // tables no longer implement the documented model: never return such a result silently.
  if (!(std::fabs(stretching + bending - tableWork) <= 1e-9 * std::max(1.0, tableWork))) {
    std::ostringstream os;
    os << "vpMorphMatcher: internal error, the work of the path (" << stretching + bending
       << ") differs from the programme's (" << tableWork << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  return vpMorphCorrespondence(m, n, std::move(pairs), stretching, bending);
}

vpMorphCorrespondence vpMorphMatcher::matchFromStart(const vpMorphContour &A, const vpMorphContour &B, std::size_t a,
                                                     std::size_t b)
{
  checkStart(A, B, a, b);
  prepare(A, B, A.signedArea() < 0 ? (A.size() - a) % A.size() : a, 0);
  // Column of target vertex b in the positive traversal.
  const int col = static_cast<int>(m_reversedB ? (m_n - b) % m_n : b);
  std::vector<std::pair<int, int>> cells;
  const double w = solveStart(col, nullptr, nullptr, nullptr, &cells);
  return toCorrespondence(cells, w);
}

vpMorphCorrespondence vpMorphMatcher::matchBruteForce(const vpMorphContour &A, const vpMorphContour &B)
{
  prepare(A, B, 0, 0);
  double bestWork = kInf;
  int bestB = 0;
  for (int b = 0; b < static_cast<int>(m_n); ++b) {
    const double w = solveStart(b, nullptr, nullptr, nullptr, nullptr);
    if (w < bestWork) {
      bestWork = w;
      bestB = b;
    }
  }
  std::vector<std::pair<int, int>> cells;
  const double w = solveStart(bestB, nullptr, nullptr, nullptr, &cells);
  return toCorrespondence(cells, w);
}

vpMorphCorrespondence vpMorphMatcher::match(const vpMorphContour &A, const vpMorphContour &B)
{
  prepare(A, B, 0, 0);
  return solveRange(static_cast<int>(m_n));
}

vpMorphCorrespondence vpMorphMatcher::matchWindow(const vpMorphContour &A, const vpMorphContour &B, std::size_t a,
                                                  std::size_t bCenter, std::size_t halfWidth)
{
  checkStart(A, B, a, bCenter);
  const std::size_t m = A.size(), n = B.size();
  const std::size_t ta = A.signedArea() < 0 ? (m - a) % m : a;
  if (2 * halfWidth + 1 >= n) {
    prepare(A, B, ta, 0);
    return solveRange(static_cast<int>(n));
  }
  // Column 0 of the prepared grid is the first start of the window, in the positive traversal.
  const std::size_t col = B.signedArea() < 0 ? (n - bCenter) % n : bCenter;
  prepare(A, B, ta, (col + n - halfWidth) % n);
  return solveRange(static_cast<int>(2 * halfWidth + 1));
}

double vpMorphMatcher::distance(const vpMorphContour &A, const vpMorphContour &B) { return match(A, B).work(); }

bool vpMorphMatcher::matchTurned(const vpMorphContour &A, const vpMorphContour &B, double theta, double tolerance,
                                 vpMorphCorrespondence &placed)
{
  bool found = false;
  for (std::size_t b = 0; b < B.size(); ++b) {
    vpMorphCorrespondence c = matchFromStart(A, B, 0, b);
    if (found && c.work() >= placed.work())
      continue;
    const vpMorphRigidTransform Tc = vpMorphRigidTransform::fitLeastSquares(A, B, c, true);
    if (std::fabs(std::remainder(Tc.theta() - theta, 2.0 * M_PI)) <= tolerance) {
      placed = std::move(c);
      found = true;
    }
  }
  return found;
}

namespace
{
// Least share of the target's outline that a view laid half a turn round must show to be planned that way.
const double kHalfTurnMinShare = 0.75;

/*
  Intersection over union of A moved by T and B (0 when the regions are degenerate). \throw vpMorphException when
  the overlap is not one of two regions (negative, or larger than either: self-intersecting contours, whose
  overlapArea() is not defined), so that the caller leaves the regions out.
*/
double placedIoU(const vpMorphContour &A, const vpMorphContour &B, const vpMorphRigidTransform &T)
{
  const vpMorphContour moved = T.apply(A);
  const double inter = moved.overlapArea(B);
  const double a = std::fabs(moved.signedArea()), b = std::fabs(B.signedArea());
  if (inter < -1e-9 * (a + b) || inter > std::min(a, b) * (1.0 + 1e-9) + 1e-300)
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphMatcher::matchOnRegions: the regions' overlap is not a region's (self-intersecting "
                           "contours?)");
  const double uni = a + b - inter;
  return uni > 0.0 && std::isfinite(inter) ? inter / uni : 0.0;
}
} // namespace

vpMorphCorrespondence vpMorphMatcher::matchOnRegions(const vpMorphContour &A, const vpMorphContour &B, double minGain,
                                                     double *gain, const vpMorphCorrespondence *leastWork)
{
  if (!(minGain > 0.0 && minGain <= 1.0)) {
    std::ostringstream os;
    os << "vpMorphMatcher::matchOnRegions: minGain must be in (0, 1], got " << minGain;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (gain)
    *gain = 0.0;
  vpMorphCorrespondence best = leastWork ? *leastWork : match(A, B);
  // Past match(), the contours are valid: a failure of the check is a placement that degenerates in floating
  // point (huge coordinates whose moved vertices merge) or self-intersecting contours (their overlap is no region's),
  // where the regions cannot be compared and the work decides.
  try {
    const double areaA = std::fabs(A.signedArea()), areaB = std::fabs(B.signedArea());
    const double s = std::sqrt(areaB / areaA);
    if (!std::isfinite(s) || !(s > 0.0))
      return best; // no region to compare: the work alone decides
    // Refinement budgets: a placement is compared, not measured, so a few dozen rounds from a coarse step suffice.
    const unsigned int rounds = 20;
    const double step = 0.02;
    const vpMorphRigidTransform Tw = vpMorphRigidTransform::fitLeastSquares(A, B, best, true);
    const vpMorphRigidTransform Tws(Tw.theta(), Tw.tx(), Tw.ty(), s, Tw.cx(), Tw.cy());
    double iouWork = placedIoU(A, B, Tws);
    if (iouWork >= 1.0 - minGain) // refining can only raise it: nothing can win by minGain
      return best;
    iouWork = placedIoU(A, B, vpMorphRigidTransform::refineOnOverlap(A, B, Tws, rounds, step));
    if (iouWork >= 1.0 - minGain)
      return best;
    double ax, ay, bx, by;
    A.centroid(ax, ay);
    B.centroid(bx, by);
    const int samples = 12;
    vpMorphRigidTransform Tbest;
    double iouBest = -1.0;
    for (int k = 0; k < samples; ++k) {
      const vpMorphRigidTransform Tk(Tw.theta() + 2.0 * M_PI * k / samples, bx - ax, by - ay, s, ax, ay);
      const double iou = placedIoU(A, B, Tk);
      if (iou > iouBest) {
        iouBest = iou;
        Tbest = Tk;
      }
    }
    Tbest = vpMorphRigidTransform::refineOnOverlap(A, B, Tbest, rounds, step);
    iouBest = placedIoU(A, B, Tbest);
    vpMorphCorrespondence placed;
    if (iouBest > iouWork + minGain) {
      // The least work among the starts whose own fit turns the way the placement does (within the sampling step).
      if (!matchTurned(A, B, Tbest.theta(), M_PI / samples, placed))
        return best;
      if (gain)
        *gain = iouBest - iouWork;
      return placed;
    }
    // The regions leave it to the work: checked on the outlines, half a turn round (an occluded view, its region
    // not its target's, matched end for end).
    const vpMorphOutlineShare shown(B);
    const vpMorphRigidTransform T0 = shown.fitted(A, best);
    // Only a view that shows most of B's outline from there: 3/4 of it, what an occluder hiding a fifth leaves
    // (vpMorphDatabase::minimumSupport()). Measured first: most views show far less half a turn round, and then the
    // work's side needs no measuring. A view in perspective (tilted, or through wrong intrinsics) is not a similarity
    // of B, and its fits can fall into another basin at either start: a wrench's fit from its right placement showed
    // 0.18 of its outline once, half a turn round 0.53, and the plan turned it away (a calib start of development).
    vpMorphRigidTransform Fhalf;
    const double shareHalf = shown.aligned(A, shown.halfTurned(T0), &Fhalf);
    if (!(shareHalf >= kHalfTurnMinShare))
      return best;
    // The least work on that side: within 45 deg of it, as the fit of a correspondence to a view with a part hidden
    // turns away from the outline's by more than the sampling's half step.
    const double shareWork = shown.aligned(A, T0);
    if (!(shareHalf > shareWork + minGain) || !matchTurned(A, B, Fhalf.theta(), M_PI / 4.0, placed))
      return best;
    if (gain)
      *gain = shareHalf - shareWork;
    return placed;
  } catch (const vpMorphException &) {
    if (gain)
      *gain = 0.0;
    return best;
  }
}
