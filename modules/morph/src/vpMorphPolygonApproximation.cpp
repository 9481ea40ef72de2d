#include <visp3/morph/vpMorphPolygonApproximation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

#include <visp3/morph/vpMorphException.h>

#include "vpMorphPixelChain.h"

namespace
{
[[noreturn]] void fail(const std::string &what)
{
  throw vpMorphException(vpMorphException::badContourError, "vpMorphPolygonApproximation: " + what);
}

using Pt = vpMorphPixelChain::Pt;
using EdgeError = vpMorphPixelChain::EdgeError;
using Chain = vpMorphPixelChain;

// The pixels that can be vertices of the convex hull, in (y, x) order, each at the lowest index of its position. On a
// chain of integer rows (every traced boundary), only the leftmost and rightmost pixels of each row can: one pass,
// where sorting every pixel took a tenth of the approximation.
std::vector<std::size_t> hullCandidates(const std::vector<Pt> &p)
{
  double y0 = p[0].y, y1 = p[0].y;
  bool integral = true;
  for (const Pt &q : p) {
    y0 = std::min(y0, q.y);
    y1 = std::max(y1, q.y);
    integral = integral && q.y == std::floor(q.y);
  }
  std::vector<std::size_t> idx;
  // A chain of n 8-connected pixels spans at most n rows; other chains are sorted.
  if (integral && y1 - y0 < double(p.size())) {
    const std::size_t rows = std::size_t(y1 - y0) + 1, none = p.size();
    std::vector<std::size_t> left(rows, none), right(rows, none);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const std::size_t r = std::size_t(p[i].y - y0);
      if (left[r] == none || p[i].x < p[left[r]].x)
        left[r] = i;
      if (right[r] == none || p[i].x > p[right[r]].x)
        right[r] = i;
    }
    idx.reserve(2 * rows);
    for (std::size_t r = 0; r < rows; ++r) {
      if (left[r] == none)
        continue;
      idx.push_back(left[r]);
      if (p[right[r]].x != p[left[r]].x)
        idx.push_back(right[r]);
    }
    return idx;
  }
  idx.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return p[a].y < p[b].y || (p[a].y == p[b].y && (p[a].x < p[b].x || (p[a].x == p[b].x && a < b)));
  });
  idx.erase(std::unique(idx.begin(), idx.end(),
                        [&](std::size_t a, std::size_t b) { return p[a].x == p[b].x && p[a].y == p[b].y; }),
            idx.end());
  return idx;
}

// Andrew's monotone chain (on the (y, x) order, the same hull traversed the other way): indices of the strictly
// convex hull vertices.
std::vector<std::size_t> hullIndices(const std::vector<Pt> &p)
{
  const std::vector<std::size_t> idx = hullCandidates(p);
  if (idx.size() < 3)
    return idx;
  auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
    return (p[a].x - p[o].x) * (p[b].y - p[o].y) - (p[a].y - p[o].y) * (p[b].x - p[o].x);
  };
  std::vector<std::size_t> h(2 * idx.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < idx.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], idx[i]) <= 0)
      --k;
    h[k++] = idx[i];
  }
  for (std::size_t i = idx.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], idx[i]) <= 0)
      --k;
    h[k++] = idx[i];
  }
  h.resize(k - 1);
  return h;
}

// Lexicographic order on pixel coordinates, for start-independent tie breaking.
bool lessPt(const Pt &a, const Pt &b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Vertices as strictly increasing unwrapped chain indices spanning less than one turn.
using Vertices = std::vector<std::ptrdiff_t>;

std::ptrdiff_t prevOf(const Vertices &v, std::size_t j, std::ptrdiff_t n) { return j == 0 ? v.back() - n : v[j - 1]; }
std::ptrdiff_t nextOf(const Vertices &v, std::size_t j, std::ptrdiff_t n)
{
  return j + 1 == v.size() ? v.front() + n : v[j + 1];
}

void splitArc(const Chain &c, std::ptrdiff_t a, std::ptrdiff_t b, Vertices &out)
{
  std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>> stack{{a, b}};
  while (!stack.empty()) {
    const auto r = stack.back();
    stack.pop_back();
    if (r.second - r.first < 2)
      continue;
    const EdgeError e = c.error(r.first, r.second);
    if (e.argmax >= 0 && e.max > e.tol) {
      out.push_back(e.argmax);
      stack.push_back({r.first, e.argmax});
      stack.push_back({e.argmax, r.second});
    }
  }
}

// Placements known to stay: (previous, vertex, next) chain indices, shifted by a multiple of the chain's length so
// that the vertex is in [0, n) (the costs depend on the indices modulo n only).
using StablePlacements = std::set<std::array<std::ptrdiff_t, 3>>;

std::array<std::ptrdiff_t, 3> placement(std::ptrdiff_t p, std::ptrdiff_t x, std::ptrdiff_t q, std::ptrdiff_t n)
{
  const std::ptrdiff_t shift = (x >= 0 ? x / n : -((-x + n - 1) / n)) * n;
  return {p - shift, x - shift, q - shift};
}

// One Gauss-Seidel sweep of L1 placement; returns true if a vertex moved. A vertex already placed between the same
// neighbours would stay where it is (it is at the first minimum of the same costs, up to the same 1e-9): it is
// skipped (\e stable), which leaves the result exactly that of a full sweep.
bool refineSweep(const Chain &c, Vertices &v, StablePlacements &stable)
{
  const std::ptrdiff_t n = c.size();
  bool moved = false;
  for (std::size_t j = 0; j < v.size(); ++j) {
    const std::ptrdiff_t p = prevOf(v, j, n), q = nextOf(v, j, n);
    if (stable.count(placement(p, v[j], q, n)))
      continue;
    double best = c.l1(p, v[j]) + c.l1(v[j], q);
    std::ptrdiff_t arg = v[j];
    for (std::ptrdiff_t k = p + 1; k < q; ++k) {
      if (k == v[j])
        continue;
      // Exactly l1(p, k) + l1(k, q) summed in that order, abandoned once it cannot beat the best: most candidates
      // are far from it, and this search was most of the extraction's time (O(arc^2) per vertex).
      const double limit = best - 1e-9;
      // A candidate whose lower bound already reaches the limit is dropped without a sum (with a margin over the
      // sums' rounding): what is dropped here would have been dropped by the sums.
      const double second = c.lowerBound(k, q);
      if (c.atLeast(c.lowerBound(p, k) + second, limit))
        continue;
      const double first = c.l1(p, k, 0.0, limit);
      if (!(first < limit) || c.atLeast(first + second, limit))
        continue;
      const double cost = first + c.l1(k, q, first, limit);
      if (cost < limit) {
        best = cost;
        arg = k;
      }
    }
    stable.insert(placement(p, arg, q, n));
    if (arg != v[j]) {
      v[j] = arg;
      moved = true;
    }
  }
  return moved;
}

// \e stable carries over between calls on the same chain: after a merge, only the removed vertex's neighbours are
// placed anew.
void refine(const Chain &c, Vertices &v, StablePlacements &stable)
{
  // Each move strictly lowers the total L1 error, so the loop ends; the cap is only a guard against
  // floating-point cycling.
  for (int sweep = 0; sweep < 100 && refineSweep(c, v, stable); ++sweep) {
  }
}

// Merge score of vertex j, or a negative value when it must stay.
double mergeScore(const Chain &c, const Vertices &v, std::size_t j)
{
  const std::ptrdiff_t n = c.size();
  const EdgeError e = c.error(prevOf(v, j, n), nextOf(v, j, n));
  if (e.mean() <= 0.75 * e.tol && e.max <= 2.0 * e.tol)
    return e.mean() / e.tol;
  return -1.0;
}

void merge(const Chain &c, Vertices &v)
{
  std::vector<double> score(v.size());
  for (std::size_t j = 0; j < v.size(); ++j)
    score[j] = mergeScore(c, v, j);
  while (v.size() > 3) {
    std::size_t best = v.size();
    for (std::size_t j = 0; j < v.size(); ++j)
      if (score[j] >= 0.0 && (best == v.size() || score[j] < score[best]))
        best = j;
    if (best == v.size())
      break;
    v.erase(v.begin() + static_cast<std::ptrdiff_t>(best));
    score.erase(score.begin() + static_cast<std::ptrdiff_t>(best));
    const std::size_t m = v.size();
    const std::size_t jp = (best + m - 1) % m, jn = best % m;
    score[jp] = mergeScore(c, v, jp);
    score[jn] = mergeScore(c, v, jn);
  }
}

// Polygon from vertex indices: consecutive repeated pixels removed, counter-clockwise in (x, y).
bool toContour(const std::vector<Pt> &p, const Vertices &v, vpMorphContour &out)
{
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  std::vector<double> xs, ys;
  for (std::ptrdiff_t i : v) {
    const Pt &q = p[static_cast<std::size_t>(((i % n) + n) % n)];
    if (!xs.empty() && xs.back() == q.x && ys.back() == q.y)
      continue;
    xs.push_back(q.x);
    ys.push_back(q.y);
  }
  while (xs.size() > 1 && xs.back() == xs.front() && ys.back() == ys.front()) {
    xs.pop_back();
    ys.pop_back();
  }
  if (xs.size() < 3)
    return false;
  double a = 0.0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const std::size_t k1 = (k + 1) % xs.size();
    a += xs[k] * ys[k1] - xs[k1] * ys[k];
  }
  if (std::fabs(a) < 1e-12)
    return false;
  out = vpMorphContour(xs, ys, vpMorphContour::PIXEL);
  if (a < 0.0)
    out = out.reversed();
  return out.isSimple();
}

double orient(const Pt &a, const Pt &b, const Pt &c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

bool onSeg(const Pt &a, const Pt &b, const Pt &c)
{
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

bool segsIntersect(const Pt &a, const Pt &b, const Pt &c, const Pt &d)
{
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && onSeg(c, d, a)) || (d2 == 0 && onSeg(c, d, b)) || (d3 == 0 && onSeg(a, b, c)) ||
         (d4 == 0 && onSeg(a, b, d));
}

// Positions in \e v of the vertices of the first violation of simplicity (the test of vpMorphContour::isSimple()
// on the polygon toContour() builds: a fold-back at a vertex, or two crossing edges); empty when there is none.
// Removing a vertex changes only its two edges, so a single removal can restore simplicity only if it is one of
// these vertices: repair() tries them instead of every vertex.
std::vector<std::size_t> firstViolation(const std::vector<Pt> &p, const Vertices &v)
{
  const std::ptrdiff_t np = static_cast<std::ptrdiff_t>(p.size());
  std::vector<Pt> q;
  std::vector<std::vector<std::size_t>> pos; // positions of v that give polygon vertex k
  for (std::size_t j = 0; j < v.size(); ++j) {
    const Pt &r = p[static_cast<std::size_t>(((v[j] % np) + np) % np)];
    if (!q.empty() && q.back().x == r.x && q.back().y == r.y) {
      pos.back().push_back(j);
      continue;
    }
    q.push_back(r);
    pos.push_back({j});
  }
  while (q.size() > 1 && q.back().x == q.front().x && q.back().y == q.front().y) {
    pos.front().insert(pos.front().end(), pos.back().begin(), pos.back().end());
    q.pop_back();
    pos.pop_back();
  }
  const std::size_t n = q.size();
  std::vector<std::size_t> ks;
  for (std::size_t i = 0; i < n && ks.empty(); ++i) {
    const std::size_t i1 = (i + 1) % n, i2 = (i + 2) % n;
    if (orient(q[i], q[i1], q[i2]) == 0.0 &&
        (q[i1].x - q[i].x) * (q[i2].x - q[i1].x) + (q[i1].y - q[i].y) * (q[i2].y - q[i1].y) < 0.0) {
      ks = {i, i1, i2};
      break;
    }
    for (std::size_t j = i + 2; j < n; ++j) {
      const std::size_t j1 = (j + 1) % n;
      if (j1 != i && segsIntersect(q[i], q[i1], q[j], q[j1])) {
        ks = {i, i1, j, j1};
        break;
      }
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t k : ks)
    out.insert(out.end(), pos[k].begin(), pos[k].end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// \e v rotated to start where the cyclic sequence of its pixels is lexicographically least (the next turn's indices
// shifted by n): a polygon's own order, whatever pixel the chain starts at.
Vertices canonical(const std::vector<Pt> &p, const Vertices &v)
{
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  const std::size_t m = v.size();
  auto pixel = [&](std::size_t j) -> const Pt & { return p[static_cast<std::size_t>(((v[j % m] % n) + n) % n)]; };
  std::size_t first = 0;
  for (std::size_t s = 1; s < m; ++s)
    for (std::size_t k = 0; k < m; ++k) {
      if (lessPt(pixel(s + k), pixel(first + k))) {
        first = s;
        break;
      }
      if (lessPt(pixel(first + k), pixel(s + k)))
        break;
    }
  Vertices w(m);
  for (std::size_t k = 0; k < m; ++k)
    w[k] = first + k < m ? v[first + k] : v[first + k - m] + n;
  const std::ptrdiff_t turns = w[0] / n; // the first vertex back in [0, n): indices stay within two turns
  for (std::ptrdiff_t &i : w)
    i -= turns * n;
  return w;
}

// Last resort: drop the vertex whose removal best restores simplicity, one at a time. Each round tries, in the
// polygon's own order (canonical()), the single removals that can help (the vertices of the first violation; the others
// cannot), so a round costs O(V^2) instead of O(V^3) and the repair O(V^3) instead of O(V^4): with every vertex tried,
// a jagged boundary of a few hundred vertices took minutes (found by fuzz_contour_extraction). The choice is the same
// as trying every vertex (the first helpful one in order, else the vertex closest to its neighbours' chord), except for
// a removal that only helps by merging two equal neighbours, which is tried when those are in the violation.
bool repair(const std::vector<Pt> &p, Vertices v, vpMorphContour &out)
{
  while (v.size() > 3) {
    // From the chain's start instead, a chain that passes a pixel twice (a spur one pixel wide) lost or kept the spur
    // depending on where it started.
    v = canonical(p, v);
    bool done = false;
    std::vector<std::size_t> candidates = firstViolation(p, v);
    if (candidates.empty()) { // simple already, yet refused (degenerate): try every vertex, as before
      candidates.resize(v.size());
      for (std::size_t j = 0; j < v.size(); ++j)
        candidates[j] = j;
    }
    for (std::size_t j : candidates) {
      if (done)
        break;
      Vertices w(v);
      w.erase(w.begin() + static_cast<std::ptrdiff_t>(j));
      vpMorphContour c;
      try {
        if (toContour(p, w, c)) {
          out = c;
          return true;
        }
      } catch (const vpMorphException &) {
      }
    }
    // No single removal suffices: drop the vertex closest to its neighbours' chord and try again. Polygons over
    // 32 vertices drop the sixteenth of their vertices closest to their chords at once: one at a time, the rounds
    // on a thousand-vertex noisy outline still cost O(V^3) (a benchmark run stuck for 45 minutes in one image).
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
    const Chain c(p);
    std::vector<std::pair<double, std::size_t>> d(v.size());
    for (std::size_t j = 0; j < v.size(); ++j)
      d[j] = {Chain::segDist(c.at(prevOf(v, j, n)), c.at(nextOf(v, j, n)), c.at(v[j])), j};
    const std::size_t drop = v.size() <= 32 ? 1 : (v.size() + 15) / 16;
    std::partial_sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(drop), d.end());
    std::vector<bool> gone(v.size(), false);
    for (std::size_t k = 0; k < drop; ++k)
      gone[d[k].second] = true;
    Vertices w;
    for (std::size_t j = 0; j < v.size(); ++j)
      if (!gone[j])
        w.push_back(v[j]);
    v.swap(w);
  }
  return false;
}

std::vector<Pt> toPts(const std::vector<vpImagePoint> &chain)
{
  std::vector<Pt> p;
  p.reserve(chain.size());
  for (const vpImagePoint &ip : chain) {
    if (!std::isfinite(ip.get_u()) || !std::isfinite(ip.get_v()))
      fail("the chain has a non-finite point");
    Pt q{ip.get_u(), ip.get_v()};
    if (!p.empty() && p.back().x == q.x && p.back().y == q.y)
      continue; // a repeated pixel carries no shape
    p.push_back(q);
  }
  while (p.size() > 1 && p.back().x == p.front().x && p.back().y == p.front().y)
    p.pop_back();
  return p;
}

// The three stages; fills the intermediate vertex sets so that a fallback can use them.
void stages(const std::vector<Pt> &p, Vertices &split, Vertices &refined, Vertices &merged)
{
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  Chain c(p);

  // Mutually farthest pixels: diameter of the convex hull.
  const std::vector<std::size_t> h = hullIndices(p);
  if (h.size() < 3)
    fail("the chain encloses no area (all its pixels are collinear)");
  std::size_t ia = h[0], ib = h[1];
  double best = -1.0;
  for (std::size_t i = 0; i < h.size(); ++i)
    for (std::size_t j = i + 1; j < h.size(); ++j) {
      std::size_t a = h[i], b = h[j];
      if (lessPt(p[b], p[a]))
        std::swap(a, b);
      const double d = (p[a].x - p[b].x) * (p[a].x - p[b].x) + (p[a].y - p[b].y) * (p[a].y - p[b].y);
      const bool tie =
          d == best && (lessPt(p[a], p[ia]) || (p[a].x == p[ia].x && p[a].y == p[ia].y && lessPt(p[b], p[ib])));
      if (d > best || tie) {
        best = d;
        ia = a;
        ib = b;
      }
    }
  std::ptrdiff_t a = static_cast<std::ptrdiff_t>(std::min(ia, ib)), b = static_cast<std::ptrdiff_t>(std::max(ia, ib));

  split = {a, b};
  splitArc(c, a, b, split);
  splitArc(c, b, a + n, split);
  for (std::ptrdiff_t &i : split)
    if (i >= n)
      i -= n;
  std::sort(split.begin(), split.end());
  if (split.size() < 3) {
    // Thin shape: both arcs are within the digitisation bound of the diameter; keep their extremes.
    const EdgeError e1 = c.error(a, b), e2 = c.error(b, a + n);
    if (e1.argmax >= 0 && e1.max > 0.0)
      split.push_back(e1.argmax);
    if (e2.argmax >= 0 && e2.max > 0.0)
      split.push_back(e2.argmax >= n ? e2.argmax - n : e2.argmax);
    std::sort(split.begin(), split.end());
    if (split.size() < 3)
      fail("the chain encloses no area (all its pixels lie on one segment)");
  }

  refined = split;
  StablePlacements stable;
  refine(c, refined, stable);
  // Merging changes the neighbours that the L1 placement depends on, and re-placed vertices may allow
  // further merges: alternate until no vertex is removed (V decreases at each round, so this ends).
  merged = refined;
  for (;;) {
    const std::size_t before = merged.size();
    merge(c, merged);
    refine(c, merged, stable);
    if (merged.size() == before)
      break;
  }
}
} // namespace

double vpMorphPolygonApproximation::tolerance(double x0, double y0, double x1, double y1)
{
  const double dx = x1 - x0, dy = y1 - y0, l = std::hypot(dx, dy);
  if (l <= 0.0)
    return 1.0;
  return (std::fabs(dx) + std::fabs(dy)) / l;
}

std::vector<std::size_t> vpMorphPolygonApproximation::vertexIndices(const std::vector<vpImagePoint> &chain)
{
  const std::vector<Pt> p = toPts(chain);
  if (p.size() != chain.size())
    fail("vertexIndices() needs a chain without repeated consecutive pixels");
  if (p.size() < 3) {
    std::ostringstream os;
    os << "a closed chain needs at least 3 distinct pixels (got " << p.size() << ")";
    fail(os.str());
  }
  Vertices s, r, m;
  stages(p, s, r, m);
  std::vector<std::size_t> out;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  for (std::ptrdiff_t i : m)
    out.push_back(static_cast<std::size_t>(((i % n) + n) % n));
  std::sort(out.begin(), out.end());
  return out;
}

vpMorphContour vpMorphPolygonApproximation::approximate(const std::vector<vpImagePoint> &chain)
{
  const std::vector<Pt> p = toPts(chain);
  if (p.size() < 3) {
    std::ostringstream os;
    os << "a closed chain needs at least 3 distinct pixels (got " << p.size() << ")";
    fail(os.str());
  }
  Vertices split, refined, merged;
  stages(p, split, refined, merged);

  vpMorphContour out;
  for (const Vertices *v : {&merged, &refined, &split}) {
    try {
      if (toContour(p, *v, out))
        return out;
    } catch (const vpMorphException &) {
      // a degenerate stage result: try the previous stage
    }
  }
  if (repair(p, split, out))
    return out;
  std::ostringstream os;
  os << "no simple polygon could be formed from the " << p.size() << "-pixel chain";
  fail(os.str());
}
