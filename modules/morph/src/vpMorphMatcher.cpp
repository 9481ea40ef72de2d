#include <visp3/morph/vpMorphMatcher.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
// Step that entered a cell.
constexpr unsigned char STEP_DIAG = 0, STEP_A = 1, STEP_B = 2;
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

void vpMorphMatcher::prepare(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b)
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
  m_costDiag.resize(m * 2 * n);
  for (std::size_t i = 0; i < m; ++i) {
    double *row = &m_costDiag[i * 2 * n];
    for (std::size_t j = 0; j < n; ++j)
      row[j] = m_model.stretching(m_lenA[i], m_lenB[j]) + m_model.bending(m_phiA[i], m_phiB[j]);
    std::copy(row, row + n, row + n);
  }
}

// Minimal work of a path from (0, b) to (m, b + n) whose row i stays within the columns spanned by the path
// \e lo (leftmost) and the path \e hi (rightmost) in that row; null bounds: unconstrained. Writes the path.
double vpMorphMatcher::solveStart(int b, const Path *lo, const Path *hi, Path &path)
{
  const int m = static_cast<int>(m_m), n = static_cast<int>(m_n), W = 2 * n;
  // Column range of row i. Row 0 starts at b by definition; the end cell (m, b + n) is inside any band
  // whose bounding starts enclose b.
  auto L = [&](int i) { return (i == 0 || !lo) ? b : std::max(b, lo->left[i]); };
  auto R = [&](int i) { return std::min(hi ? hi->right[i] : b + n, W - 1); };

  m_rowOff.resize(m + 2);
  m_rowOff[0] = 0;
  for (int i = 0; i <= m; ++i)
    m_rowOff[i + 1] = m_rowOff[i] + static_cast<std::size_t>(std::max(0, R(i) - L(i) + 1));
  m_step.resize(m_rowOff[m + 1]);
  // Rolling rows, offset by one cell so that column -1 exists.
  m_prev.assign(W + 2, kInf);
  m_cur.assign(W + 2, kInf);

  // Row 0: A's vertex 0 matched to B's b, b+1, ...: only B steps. The start cell's own step is the one
  // that closes the path into (m, b + n), charged there.
  int pl = b, pr = R(0);
  {
    unsigned char *st = &m_step[m_rowOff[0]] - b;
    double *prev = m_prev.data() + 1;
    prev[b] = 0.0;
    st[b] = STEP_DIAG;
    for (int j = b + 1; j <= pr; ++j) {
      prev[j] = prev[j - 1] + m_costB[j];
      st[j] = STEP_B;
    }
  }
  for (int i = 1; i <= m; ++i) {
    const int l = L(i), r = R(i);
    const int ii = (i == m) ? 0 : i; // row m is A's vertex 0 again
    const double *cd = &m_costDiag[static_cast<std::size_t>(ii) * W];
    const double ca = m_costA[ii];
    const double *pB = m_prefB.data();
    unsigned char *st = &m_step[m_rowOff[i]] - l;
    // prev[j] = D[i-1][j], +inf outside [pl, pr]; prev[-1] exists (+inf) thanks to the one-cell offset.
    const double *prev = m_prev.data() + 1;
    double *cur = m_cur.data() + 1;
    // With P[j] the prefix sum of the B-step costs, D[i][j] - P[j] is the running minimum of
    // min(diagonal, A step) - P[j] along the row, so the serial part is a bare minimum (no add in the chain).
    // Pass 1, independent cells (vectorisable): best of the diagonal and the A step, minus P[j].
    for (int j = l; j <= r; ++j) {
      const double up = prev[j] + ca, dg = prev[j - 1] + cd[j];
      cur[j] = (up < dg ? up : dg) - pB[j];
      st[j] = up < dg ? STEP_A : STEP_DIAG;
    }
    // Pass 2, serial: running minimum, then back to D[i][j].
    double run = cur[l];
    cur[l] += pB[l];
    for (int j = l + 1; j <= r; ++j) {
      const double y = cur[j];
      st[j] = run < y ? STEP_B : st[j];
      run = run < y ? run : y;
      cur[j] = run + pB[j];
    }
    for (int j = pl; j <= pr; ++j) // forget row i-1 so that m_prev is +inf outside row i's range
      m_prev[j + 1] = kInf;
    std::swap(m_prev, m_cur);
    pl = l;
    pr = r;
  }
  const int end = b + n;
  const double work = (end >= pl && end <= pr) ? m_prev[end + 1] : kInf;
  if (!std::isfinite(work))
    return work;

  path.left.assign(m + 1, std::numeric_limits<int>::max());
  path.right.assign(m + 1, std::numeric_limits<int>::min());
  path.cells.clear();
  int i = m, j = end;
  for (;;) {
    path.left[i] = std::min(path.left[i], j);
    path.right[i] = std::max(path.right[i], j);
    if (i == 0 && j == b)
      break;
    path.cells.emplace_back(i, j);
    const unsigned char s = m_step[m_rowOff[i] + static_cast<std::size_t>(j - L(i))];
    if (s != STEP_B)
      --i;
    if (s != STEP_A)
      --j;
  }
  path.cells.emplace_back(0, b);
  std::reverse(path.cells.begin(), path.cells.end()); // (0, b) ... (m, b + n)
  return work;
}

// Maes' divide and conquer: the optimal paths of starts bLo < b < bHi lie between those of bLo and bHi.
void vpMorphMatcher::solveBetween(int bLo, int bHi, const Path &lo, const Path &hi, double &bestWork, Path &best)
{
  if (bHi - bLo < 2)
    return;
  const int mid = bLo + (bHi - bLo) / 2;
  Path p;
  const double w = solveStart(mid, &lo, &hi, p);
  if (w < bestWork) {
    bestWork = w;
    best = p;
  }
  solveBetween(bLo, mid, lo, p, bestWork, best);
  solveBetween(mid, bHi, p, hi, bestWork, best);
}

// Best path over the starts 0 .. count-1 of the prepared problem (count <= n).
vpMorphCorrespondence vpMorphMatcher::solveRange(int count)
{
  const int n = static_cast<int>(m_n);
  Path first, last;
  double bestWork = solveStart(0, nullptr, nullptr, first);
  Path best = first;
  if (count > 1) {
    if (count == n) {
      // Start n is start 0 again, shifted by one period of the doubled grid.
      last = first;
      for (int &c : last.left)
        c += n;
      for (int &c : last.right)
        c += n;
    } else {
      const double w = solveStart(count - 1, nullptr, nullptr, last);
      if (w < bestWork) {
        bestWork = w;
        best = last;
      }
    }
    solveBetween(0, count == n ? n : count - 1, first, last, bestWork, best);
  }
  return toCorrespondence(best);
}

vpMorphCorrespondence vpMorphMatcher::toCorrespondence(const Path &path)
{
  const std::size_t m = m_m, n = m_n;
  std::vector<std::pair<std::size_t, std::size_t> > pairs;
  pairs.reserve(path.cells.size());
  double stretching = 0.0, bending = 0.0;
  for (std::size_t k = 0; k + 1 < path.cells.size(); ++k) {
    const int i = path.cells[k].first, j = path.cells[k].second;
    const std::size_t ra = (m_a0 + static_cast<std::size_t>(i)) % m, rb = (m_b0 + static_cast<std::size_t>(j)) % n;
    pairs.emplace_back(m_reversedA ? (m - ra) % m : ra, m_reversedB ? (n - rb) % n : rb);
    // Work of the step into the next cell (the last one closes the path onto the start).
    const int i1 = path.cells[k + 1].first, j1 = path.cells[k + 1].second;
    const std::size_t ii = static_cast<std::size_t>(i1) % m;
    const double lA = (i1 != i) ? m_lenA[ii] : 0.0, lB = (j1 != j) ? m_lenB[j1] : 0.0;
    const double pA = (i1 != i) ? m_phiA[ii] : 0.0, pB = (j1 != j) ? m_phiB[j1] : 0.0;
    stretching += m_model.stretching(lA, lB);
    bending += m_model.bending(pA, pB);
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
  Path p;
  solveStart(col, nullptr, nullptr, p);
  return toCorrespondence(p);
}

vpMorphCorrespondence vpMorphMatcher::matchBruteForce(const vpMorphContour &A, const vpMorphContour &B)
{
  prepare(A, B, 0, 0);
  Path p, best;
  double bestWork = kInf;
  for (int b = 0; b < static_cast<int>(m_n); ++b) {
    const double w = solveStart(b, nullptr, nullptr, p);
    if (w < bestWork) {
      bestWork = w;
      best = p;
    }
  }
  return toCorrespondence(best);
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
