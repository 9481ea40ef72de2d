/*!
  \file fuzz_polygon_correspondence.cpp
  \brief Fuzz target: vpMorphContour validation, vpMorphPolygonApproximation, vpMorphMatcher and vpMorph on
  arbitrary point lists (NaN, infinities, duplicates, collinear runs, huge and tiny coordinates).

  Input: a flags byte, a scale byte, the vertex counts of A and B (1 to 40), their coordinates
  (vpFuzzInput::coordinate), then the length (1 to 200) and points of a pixel chain for the polygonal
  approximation. A vpException is a correct outcome (bad contour, bad chain); otherwise the documented
  invariants must hold: the correspondence covers every vertex of both polygons, steps by 0 or 1 cyclically,
  has max(m, n) to m + n pairs and a finite non-negative work equal to the brute-force minimum; the morph's
  contours are finite and its last one is the target; the approximated polygon is simple, counter-clockwise and
  made of chain points.
*/
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>

#include "vpFuzzInput.h"

namespace
{
bool readContour(vpFuzzInput &in, std::size_t count, double scale, vpMorphContour &c)
{
  std::vector<double> x(count), y(count);
  for (std::size_t k = 0; k < count; ++k) {
    x[k] = in.coordinate(scale);
    y[k] = in.coordinate(scale);
  }
  try {
    c = vpMorphContour(x, y);
  } catch (const vpException &) {
    return false; // NaN, repeated vertices, zero area...: rejected with a clear message
  }
  VP_FUZZ_CHECK(c.size() == count, "a valid contour keeps its vertices");
  for (std::size_t k = 0; k < count; ++k)
    VP_FUZZ_CHECK(std::isfinite(c.x(k)) && std::isfinite(c.y(k)), "a valid contour has finite vertices");
  return true;
}

int step(std::size_t from, std::size_t to, std::size_t n)
{
  return static_cast<int>((to + n - from) % n);
}

//! The step a polygon may take between consecutive pairs: +1 when counter-clockwise, -1 (n - 1) otherwise.
bool stepOk(int d, std::size_t n, double signedArea)
{
  if (d == 0)
    return true;
  if (!std::isfinite(signedArea)) // overflowed area: the direction is not defined, accept either
    return d == 1 || d == static_cast<int>(n) - 1;
  return signedArea > 0.0 ? d == 1 : d == static_cast<int>(n) - 1;
}

void checkCorrespondence(const vpMorphCorrespondence &c, const vpMorphContour &A, const vpMorphContour &B)
{
  const std::size_t m = A.size(), n = B.size();
  VP_FUZZ_CHECK(c.inputSize() == m && c.targetSize() == n, "the correspondence has the polygons' sizes");
  VP_FUZZ_CHECK(c.size() >= std::max(m, n) && c.size() <= m + n, "max(m, n) <= pairs <= m + n");
  VP_FUZZ_CHECK(std::isfinite(c.work()) && c.stretchingWork() >= 0.0 && c.bendingWork() >= 0.0,
                "the work is finite and non-negative");
  std::vector<bool> seenA(m, false), seenB(n, false);
  const auto &p = c.pairs();
  for (std::size_t k = 0; k < p.size(); ++k) {
    VP_FUZZ_CHECK(p[k].first < m && p[k].second < n, "pair indices are in range");
    seenA[p[k].first] = seenB[p[k].second] = true;
    // Steps go in the direction of positive area: +1 or -1 (n - 1) in the caller's numbering, or stay.
    const auto &q = p[(k + 1) % p.size()];
    const int da = step(p[k].first, q.first, m), db = step(p[k].second, q.second, n);
    VP_FUZZ_CHECK(stepOk(da, m, A.signedArea()) && stepOk(db, n, B.signedArea()) && (da != 0 || db != 0),
                  "consecutive pairs advance by one vertex, cyclically, in the direction of positive area");
  }
  VP_FUZZ_CHECK(std::all_of(seenA.begin(), seenA.end(), [](bool b) { return b; }), "every input vertex is matched");
  VP_FUZZ_CHECK(std::all_of(seenB.begin(), seenB.end(), [](bool b) { return b; }), "every target vertex is matched");
}

void checkFinite(const vpMorphContour &c, const char *what)
{
  VP_FUZZ_CHECK(c.size() >= 3, what);
  for (std::size_t k = 0; k < c.size(); ++k)
    VP_FUZZ_CHECK(std::isfinite(c.x(k)) && std::isfinite(c.y(k)), what);
}

void fuzzMatch(const vpMorphContour &A, const vpMorphContour &B, uint8_t flags)
{
  const std::size_t m = A.size(), n = B.size();
  vpMorphMatcher matcher(vpMorphWorkModel(), (flags & 2) == 0);
  // Two valid contours of the same units: match() documents no other failure, so an exception here is a finding
  // (it escapes and aborts), e.g. its "internal error" when the path's work disagrees with the programme's.
  const vpMorphCorrespondence fast = matcher.match(A, B);
  checkCorrespondence(fast, A, B);
  const vpMorphCorrespondence brute = matcher.matchBruteForce(A, B);
  checkCorrespondence(brute, A, B);
  VP_FUZZ_CHECK(std::fabs(fast.work() - brute.work()) <= 1e-9 * (1.0 + brute.work()),
                "match() is the exact minimum (brute force)");
  const std::size_t b = (flags >> 4) % n;
  const vpMorphCorrespondence win = matcher.matchWindow(A, B, 0, b, 2);
  checkCorrespondence(win, A, B);
  VP_FUZZ_CHECK(win.work() >= brute.work() - 1e-9 * (1.0 + brute.work()), "no window beats the minimum");
  const vpMorphCorrespondence one = matcher.matchFromStart(A, B, (flags >> 2) % m, b);
  checkCorrespondence(one, A, B);
  double gain = -1.0;
  const vpMorphCorrespondence placed = matcher.matchOnRegions(A, B, 0.1, &gain);
  checkCorrespondence(placed, A, B);
  VP_FUZZ_CHECK(gain == 0.0 || (gain > 0.1 && gain <= 1.0), "matchOnRegions replaces only on a win above minGain");
  VP_FUZZ_CHECK(gain > 0.0 || placed.work() == fast.work(), "matchOnRegions keeps match() unless it replaces it");
  VP_FUZZ_CHECK(placed.work() >= brute.work() - 1e-9 * (1.0 + brute.work()), "no placement beats the minimum");

  const vpMorph::Estimator est = static_cast<vpMorph::Estimator>((flags >> 6) % 3);
  try {
    vpMorph morph(A, B, fast, est, (flags & 8) == 0);
    const std::vector<vpMorphContour> seq = morph.sequence(1 + (flags >> 5) % 6);
    for (const vpMorphContour &c : seq)
      checkFinite(c, "morph contours are finite");
    VP_FUZZ_CHECK(seq.back().xs() == B.xs() && seq.back().ys() == B.ys(), "the last morph contour is the target");
    checkFinite(morph.rectified(), "the rectified input is finite");
  } catch (const vpException &e) {
    // A degenerate frame is documented (badContourError, vpMorph.h); any other failure of a morph between two
    // valid contours is not (e.g. a rigid transform with infinite parameters).
    if (e.getCode() != vpMorphException::badContourError) {
      std::fprintf(stderr, "%s\n", e.getMessage());
      VP_FUZZ_CHECK(false, "a morph of two valid contours fails only with a degenerate frame");
    }
  }
}

void fuzzApproximation(vpFuzzInput &in, double scale)
{
  const std::size_t len = in.range(1, 200);
  std::vector<vpImagePoint> chain;
  const bool walk = (in.byte() & 1) != 0;
  double u = 0, v = 0;
  for (std::size_t k = 0; k < len; ++k) {
    if (walk) { // an 8-connected walk, as the extractor produces: the common case
      const uint8_t d = in.byte();
      u += static_cast<int>(d % 3) - 1;
      v += static_cast<int>((d / 3) % 3) - 1;
      chain.emplace_back(v, u);
    } else { // arbitrary points, not a chain at all
      const double x = in.coordinate(scale), y = in.coordinate(scale);
      chain.emplace_back(y, x);
    }
  }
  vpMorphContour c;
  try {
    c = vpMorphPolygonApproximation::approximate(chain);
  } catch (const vpException &) {
    return;
  }
  checkFinite(c, "an approximation has at least 3 finite vertices");
  VP_FUZZ_CHECK(c.signedArea() > 0.0, "an approximation is counter-clockwise");
  VP_FUZZ_CHECK(c.isSimple(), "an approximation is simple");
  std::set<std::pair<double, double>> pts;
  for (const vpImagePoint &p : chain)
    pts.insert({p.get_u(), p.get_v()});
  for (std::size_t k = 0; k < c.size(); ++k)
    VP_FUZZ_CHECK(pts.count({c.x(k), c.y(k)}) == 1, "approximation vertices are chain points");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  vpFuzzInput in(data, size);
  const uint8_t flags = in.byte();
  const double scale = in.scale();
  const std::size_t m = in.range(1, 40), n = in.range(1, 40);
  vpMorphContour A, B;
  const bool okA = readContour(in, m, scale, A);
  const bool okB = readContour(in, n, scale, B);
  if (okA && okB)
    fuzzMatch(A, B, flags);
  fuzzApproximation(in, scale);
  return 0;
}
