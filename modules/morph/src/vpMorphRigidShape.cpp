#include <visp3/morph/vpMorphRigidShape.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <visp3/morph/vpMorphException.h>

#include "vpMorphRigidShapeData.h"
#include "vpMorphSimilarityFit.h"
#include "vpMorphSmoothing.h"

using namespace vpMorphSimilarityFit;

namespace
{
constexpr int kBins = vpMorphRigidShapeData::kBins;
constexpr int kTurns = 4;         // candidate turns (histogram correlation peaks)
constexpr int kVoteTolerance = 2; // +-2 bins: tangent directions that agree within 12.5 deg vote
constexpr int kSamples = vpMorphRigidShapeData::kSamples; // a target's votes; an input uses every other sample
constexpr int kGrid = vpMorphRigidShapeData::kGrid;
constexpr double kGridMargin = 1.25;
constexpr int kVoteCells = 32; // shift accumulator cells a side, over [-kVoteRange, kVoteRange] sizes
constexpr double kVoteRange = 1.2;
constexpr int kIterations = 6;      // Gauss-Newton steps on the grid at most
constexpr int kFirstIterations = 2; // of them, for every turn before the two best go on
constexpr int kSweepTurns = 18;     // the sweep's turns, 20 deg apart: within a refinement's reach (class description)
constexpr double kTwoPi = 2.0 * M_PI;
// Scale of the coarse stage (fraction of the perimeter): the finest of the multiscale distance's, several times the
// largest documented blur (1.5 px) on a part's outline of some hundreds of pixels.
constexpr double kTurnScale = 0.01;

vpMorphException badParameter(const std::string &m) { return vpMorphException(vpMorphException::badParameterError, m); }

// A normalised coordinate in shift-vote cells (offset so that the accumulator starts at 0), as houghShift() casts it.
float voteCell(double v)
{
  constexpr double cell = 2.0 * kVoteRange / kVoteCells;
  constexpr float inv = static_cast<float>(1.0 / cell), off = static_cast<float>(kVoteRange / cell);
  return static_cast<float>(v) * inv + off;
}

std::vector<vpMorphRigidShape::Symmetry> symmetriesOf(const vpMorphRigidShapeData &d); // below

int binOf(double angle)
{
  double f = angle / kTwoPi * kBins;
  f -= std::floor(f / kBins) * kBins;
  return std::min(kBins - 1, static_cast<int>(f));
}
} // namespace

vpMorphRigidShape::vpMorphRigidShape(const vpMorphContour &c)
{
  if (c.size() < 3 || !(c.area() > 0.0))
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphRigidShape: a contour of at least 3 vertices and a positive area is needed");
  auto d = std::make_shared<vpMorphRigidShapeData>(c);
  c.regionCentroid(d->cx, d->cy);
  d->size = std::sqrt(c.regionArea());
  const vpMorphContour &P = d->polygon;
  // The turn and shift are estimated on the outline smoothed at kTurnScale, where the details that blur and depth
  // change alter (teeth of a few pixels) are gone from every view alike.
  const vpMorphContour S = vpMorphSmoothed(c.outline().counterClockwise(), kTurnScale, 4 * kSamples);
  // Samples evenly along the smoothed outline; as an input, every other one votes and is fitted, those on the
  // object's own edges only when the outline tells them and they are enough to fit a similarity (4 parameters).
  const vpMorphContour s = S.resampled(kSamples);
  const std::size_t n = s.size();
  std::size_t own = 0;
  for (std::size_t i = 0; i < n; i += 2)
    own += s.ownEdge(i);
  const bool ownOnly = S.hasOwnEdges() && own >= 4;
  for (std::size_t i = 0; i < n; i += 2)
    if (!ownOnly || s.ownEdge(i))
      d->inputs.push_back(static_cast<int>(i));
  // Orientation histogram of the same edges: each edge's length split between the two bins nearest its direction,
  // smoothed by [1 2 1] / 4 (a direction measured within a bin's width of another votes for both).
  std::array<double, kBins> h{};
  double total = 0.0;
  for (std::size_t k = 0; k < S.size(); ++k) {
    if (ownOnly && !S.ownEdge(k))
      continue;
    const std::size_t l = (k + 1) % S.size();
    const double dx = S.x(l) - S.x(k), dy = S.y(l) - S.y(k), len = std::hypot(dx, dy);
    double f = std::atan2(dy, dx) / kTwoPi * kBins;
    f -= std::floor(f / kBins) * kBins;
    const int b0 = static_cast<int>(f) % kBins;
    const double w = f - std::floor(f);
    h[b0] += (1.0 - w) * len;
    h[(b0 + 1) % kBins] += w * len;
    total += len;
  }
  for (int k = 0; k < kBins; ++k) {
    const float v = static_cast<float>((h[(k + kBins - 1) % kBins] + 2.0 * h[k] + h[(k + 1) % kBins]) / (4.0 * total));
    d->hist[k] = d->hist[k + kBins] = v;
  }
  // The samples' tangent directions.
  std::vector<int> count(kBins, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, b = (i + 1) % n;
    d->x.push_back((s.x(i) - d->cx) / d->size);
    d->y.push_back((s.y(i) - d->cy) / d->size);
    d->bin.push_back(binOf(std::atan2(s.y(b) - s.y(a), s.x(b) - s.x(a))));
    ++count[d->bin.back()];
  }
  auto padded = [](std::vector<float> &v) {
    constexpr std::size_t L = vpMorphRigidShapeData::kLanes;
    v.resize((v.size() + L - 1) / L * L, 0.0f);
  };
  for (const int i : d->inputs) {
    d->inputX.push_back(static_cast<float>(d->x[static_cast<std::size_t>(i)]));
    d->inputY.push_back(static_cast<float>(d->y[static_cast<std::size_t>(i)]));
  }
  for (std::size_t i = 0; i < n; i += 2) {
    d->evenX.push_back(static_cast<float>(d->x[i]));
    d->evenY.push_back(static_cast<float>(d->y[i]));
  }
  padded(d->inputX);
  padded(d->inputY);
  padded(d->evenX);
  padded(d->evenY);
  d->bucketStart.assign(kBins + 1, 0);
  for (int k = 0; k < kBins; ++k)
    d->bucketStart[k + 1] = d->bucketStart[k] + count[k];
  d->bucket.resize(n);
  std::vector<int> fill(d->bucketStart.begin(), d->bucketStart.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    d->bucket[fill[d->bin[i]]++] = static_cast<int>(i);
  for (int j : d->bucket) {
    d->voteX.push_back(voteCell(d->x[static_cast<std::size_t>(j)]));
    d->voteY.push_back(voteCell(d->y[static_cast<std::size_t>(j)]));
  }
  {
    // Signed distance to the polygon (negative inside: the sign from the even-odd rule along each row), over 1.25 times
    // the largest radius, so that an input laid a little off still falls on the grid.
    double r = 0.0;
    for (std::size_t k = 0; k < P.size(); ++k)
      r = std::max(r, std::hypot(P.x(k) - d->cx, P.y(k) - d->cy));
    r = kGridMargin * r / d->size;
    d->lo = -r;
    d->step = 2.0 * r / (kGrid - 1);
    d->invStep = 1.0 / d->step;
    d->grid.resize(static_cast<std::size_t>(kGrid * kGrid));
    const vpMorphNearestEdge edges(P); // only the grid reads it
    std::vector<double> xs, px(kGrid), dist;
    for (int i = 0; i < kGrid; ++i)
      px[static_cast<std::size_t>(i)] = d->cx + (d->lo + i * d->step) * d->size;
    for (int j = 0; j < kGrid; ++j) {
      const double py = d->cy + (d->lo + j * d->step) * d->size;
      xs.clear();
      for (std::size_t k = 0; k < P.size(); ++k) {
        const std::size_t l = (k + 1) % P.size();
        const double y0 = P.y(k), y1 = P.y(l);
        if ((y0 <= py) != (y1 <= py))
          xs.push_back(P.x(k) + (py - y0) / (y1 - y0) * (P.x(l) - P.x(k)));
      }
      std::sort(xs.begin(), xs.end());
      edges.alongRow(py, px, dist);
      for (std::size_t i = 0; i < px.size(); ++i) {
        const bool inside = (std::upper_bound(xs.begin(), xs.end(), px[i]) - xs.begin()) % 2 == 1;
        const double e = std::fabs(dist[i]) / d->size;
        d->grid[static_cast<std::size_t>(j * kGrid) + i] = static_cast<float>(inside ? -e : e);
      }
    }
  }
  d->symmetries = symmetriesOf(*d);
  m_data = d;
}

const vpMorphContour &vpMorphRigidShape::contour() const
{
  static const vpMorphContour none;
  return m_data ? m_data->contour : none;
}

namespace
{
/*
  The cost of hypothesis \e s both ways, or 2 (nothing in common) when its scale leaves [0.5, 2] sizes: a view of the
  same part has the template's size up to what an occluder hides or a tilt shrinks (a fit that shrinks the input to a
  point lays all its samples on one edge).
*/
double hypothesisCost(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s)
{
  const double k = std::hypot(s.a, s.b);
  if (!(k >= 0.5 && k <= 2.0))
    return 2.0;
  return inputCost(in, t, s, vpMorphRigidShape::tau()) + targetCost(in, t, s, vpMorphRigidShape::tau());
}

// Shift votes at turn \e bins (in 72ths of a turn), at the scales kScales (one pass over the compatible pairs): per
// scale, the 3 x 3 cells with the most votes (centred on a cell with two votes at least), their number and mean shift.
struct Vote
{
  int votes = 0;
  Sim sim;
};
constexpr int kNScales = 3;
constexpr double kScales[kNScales] = {1.05, 0.92, 0.8};
void houghShift(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, int bins, Vote out[kNScales])
{
  constexpr double cell = 2.0 * kVoteRange / kVoteCells;
  constexpr int W = kVoteCells + 2; // a cell of margin all round: the 3 x 3 sums need no bounds
  constexpr int kOut = W * W;       // where a shift off the accumulator votes (never read): no branch to mispredict
  static_assert(W == 34, "the vectorised cell index below multiplies by 34 as 32 + 2");
  std::array<std::array<std::uint8_t, W * W + 1>, kNScales> acc{};
  // The cells that reached two votes. Every vote writes its cell after the last and counts it only then: no branch
  // to mispredict (hence one slot more than cells).
  std::array<std::array<int, kVoteCells * kVoteCells + 1>, kNScales> seeds;
  int nSeeds[kNScales] = {};
  const double th = bins * kTwoPi / kBins, c = std::cos(th), sn = std::sin(th);
  const float *vx = t.voteX.data(), *vy = t.voteY.data();
  for (const int i : in.inputs) {
    const float rx = static_cast<float>((c * in.x[i] - sn * in.y[i]) / cell),
                ry = static_cast<float>((sn * in.x[i] + c * in.y[i]) / cell);
    float ox[4], oy[4]; // a lane past the scales repeats the last (unused)
    for (int s = 0; s < 4; ++s) {
      ox[s] = static_cast<float>(kScales[std::min(s, kNScales - 1)]) * rx;
      oy[s] = static_cast<float>(kScales[std::min(s, kNScales - 1)]) * ry;
    }
    // The target's samples whose bins lie within kVoteTolerance of this sample's turned bin (mod kBins), in bucket
    // order (voteX, voteY: their cells, cast once at preparation): the buckets lie one after the other, so one range,
    // or two where the bins wrap, visited in the order of the bins.
    int b0 = in.bin[i] + bins - kVoteTolerance; // in [-kVoteTolerance, 2 kBins - kVoteTolerance)
    b0 = b0 < 0 ? b0 + kBins : (b0 >= kBins ? b0 - kBins : b0);
    const int b1 = b0 + 2 * kVoteTolerance + 1; // one past the last bin, unwrapped: up to kBins + 2 kVoteTolerance
    const int ranges[2][2] = {{t.bucketStart[b0], t.bucketStart[std::min(b1, kBins)]},
                              {t.bucketStart[0], t.bucketStart[std::max(b1 - kBins, 0)]}};
#ifdef __SSE2__
    // The scales' cells at once, in the lanes of one register: the same float differences and truncations as the
    // scalar loop below.
    static_assert(kNScales <= 4, "one lane a scale");
    const __m128 OX = _mm_loadu_ps(ox), OY = _mm_loadu_ps(oy);
    const __m128 zero = _mm_setzero_ps(), side = _mm_set1_ps(static_cast<float>(kVoteCells));
    const __m128i first = _mm_set1_epi32(W + 1), out = _mm_set1_epi32(kOut);
    for (const auto &range : ranges)
      for (int k = range[0]; k < range[1]; ++k) {
        const __m128 fx = _mm_sub_ps(_mm_set1_ps(vx[k]), OX), fy = _mm_sub_ps(_mm_set1_ps(vy[k]), OY);
        const __m128 on = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(fx, zero), _mm_cmpge_ps(fy, zero)),
                                     _mm_and_ps(_mm_cmplt_ps(fx, side), _mm_cmplt_ps(fy, side)));
        const __m128i ix = _mm_cvttps_epi32(fx), iy = _mm_cvttps_epi32(fy);
        // (iy + 1) W + ix + 1 with W = 34 = 32 + 2
        const __m128i cell =
            _mm_add_epi32(_mm_add_epi32(_mm_slli_epi32(iy, 5), _mm_slli_epi32(iy, 1)), _mm_add_epi32(ix, first));
        const __m128i mask = _mm_castps_si128(on);
        alignas(16) int g[4];
        _mm_store_si128(reinterpret_cast<__m128i *>(g),
                        _mm_or_si128(_mm_and_si128(mask, cell), _mm_andnot_si128(mask, out)));
        for (int s = 0; s < kNScales; ++s) { // one vote per input sample and direction bin at most: < 255
          const int votes = ++acc[s][g[s]];
          seeds[s][nSeeds[s]] = g[s];
          nSeeds[s] += (votes == 2) & (g[s] != kOut);
        }
      }
#else
    for (const auto &range : ranges)
      for (int k = range[0]; k < range[1]; ++k) {
        for (int s = 0; s < kNScales; ++s) {
          const float fx = vx[k] - ox[s], fy = vy[k] - oy[s];
          const bool on = (fx >= 0.0f) & (fy >= 0.0f) & (fx < kVoteCells) & (fy < kVoteCells);
          const int g = on ? (static_cast<int>(fy) + 1) * W + static_cast<int>(fx) + 1 : kOut;
          const int votes = ++acc[s][g]; // one vote per input sample and direction bin at most: < 255
          seeds[s][nSeeds[s]] = g;
          nSeeds[s] += (votes == 2) & on;
        }
      }
#endif
  }
  for (int s = 0; s < kNScales; ++s) {
    out[s] = Vote();
    int bestSeed = -1;
    const std::uint8_t *a = acc[s].data();
    for (int k = 0; k < nSeeds[s]; ++k) {
      const int g = seeds[s][k];
      const int sum =
          a[g - W - 1] + a[g - W] + a[g - W + 1] + a[g - 1] + a[g] + a[g + 1] + a[g + W - 1] + a[g + W] + a[g + W + 1];
      if (sum > out[s].votes) {
        out[s].votes = sum;
        bestSeed = g;
      }
    }
    if (bestSeed < 0)
      continue;
    double mx = 0.0, my = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int v = a[bestSeed + dy * W + dx];
        mx += v * (bestSeed % W + dx - 0.5); // accumulator column g % W is cell g % W - 1, centred at + 0.5
        my += v * (bestSeed / W + dy - 0.5);
      }
    out[s].sim = Sim{kScales[s] * c, kScales[s] * sn, mx / out[s].votes * cell - kVoteRange,
                     my / out[s].votes * cell - kVoteRange};
  }
}

// The local maxima of the circular correlation of the orientation histograms of \e in and \e t (turns in 72ths of a
// turn), highest first; their number.
typedef std::array<std::pair<float, int>, kBins> Peaks;
int turnPeaks(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, Peaks &peaks)
{
  std::array<float, kBins> corr;
  for (int d = 0; d < kBins; ++d) {
    float s[8] = {}; // independent partial sums: the products pipeline (kBins is a multiple of 8)
    for (int k = 0; k < kBins; k += 8)
      for (int l = 0; l < 8; ++l)
        s[l] += in.hist[k + l] * t.hist[k + l + d];
    corr[d] = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  }
  int n = 0;
  for (int d = 0; d < kBins; ++d)
    if (corr[d] >= corr[(d + 1) % kBins] && corr[d] > corr[(d + kBins - 1) % kBins])
      peaks[n++] = {-corr[d], d};
  std::sort(peaks.begin(), peaks.begin() + n);
  return n;
}

// Whether the turns of \e s and \e t differ by more than two histogram bins (10 deg): distinct hypotheses.
bool turnsApart(const Sim &s, const Sim &t)
{
  return std::fabs(std::remainder(std::atan2(s.b, s.a) - std::atan2(t.b, t.a), kTwoPi)) > 2.0 * kTwoPi / kBins;
}

std::vector<vpMorphRigidShape::Symmetry> symmetriesOf(const vpMorphRigidShapeData &d)
{
  Peaks peaks;
  const int n = turnPeaks(d, d, peaks);
  std::vector<vpMorphRigidShape::Symmetry> out;
  const Sim none;
  std::vector<Sim> kept;
  for (int p = 0; p < n; ++p) {
    const double turn = kTwoPi * peaks[p].second / kBins;
    Sim s{std::cos(turn), std::sin(turn), 0.0, 0.0};
    if (!turnsApart(s, none))
      continue;
    s = refine(d, d, s, vpMorphRigidShape::tau(), kIterations);
    const double cost = hypothesisCost(d, d, s);
    // A peak refined back onto no turn, onto one already kept, or off the plausible scales is no symmetry.
    if (!(cost < 2.0) || !turnsApart(s, none) ||
        std::any_of(kept.begin(), kept.end(), [&s](const Sim &k) { return !turnsApart(s, k); }))
      continue;
    kept.push_back(s);
    out.push_back(vpMorphRigidShape::Symmetry{s.a, s.b, s.tx, s.ty, cost});
  }
  std::sort(out.begin(), out.end(),
            [](const vpMorphRigidShape::Symmetry &x, const vpMorphRigidShape::Symmetry &y) { return x.cost < y.cost; });
  return out;
}

void check(const vpMorphRigidShape &in, const vpMorphRigidShape &t)
{
  if (in.empty() || t.empty())
    throw badParameter("vpMorphRigidShape: an empty shape cannot be aligned");
}
} // namespace

vpMorphRigidShape::Alignment vpMorphRigidShape::alignOn(const vpMorphRigidShape &target) const
{
  return alignOn(target, true);
}

vpMorphRigidShape::Alignment vpMorphRigidShape::alignOn(const vpMorphRigidShape &target, bool symmetric) const
{
  check(*this, target);
  const vpMorphRigidShapeData &in = *m_data, &t = *target.m_data;
  // Turns: the highest local maxima of the circular correlation of the orientation histograms.
  Peaks peaks;
  const int nPeaks = turnPeaks(in, t, peaks);
  // Per turn, two starts: the shift by the votes at the best-voted scale, and the whole view's (the centroids and
  // sizes laid on each other, exact for a view that hides nothing); the turn keeps the one that costs less after the
  // first steps.
  Alignment best;
  Sim sims[kTurns];
  double costs[kTurns];
  int n = 0;
  for (int p = 0; p < std::min(nPeaks, kTurns); ++p) {
    Vote v[kNScales];
    houghShift(in, t, peaks[p].second, v);
    const Vote *w = &v[0];
    for (int k = 1; k < kNScales; ++k)
      if (v[k].votes > w->votes)
        w = &v[k];
    const double turn = kTwoPi * peaks[p].second / kBins;
    sims[n] = refine(in, t, Sim{std::cos(turn), std::sin(turn), 0.0, 0.0}, tau(), kFirstIterations);
    costs[n] = hypothesisCost(in, t, sims[n]);
    if (w->votes > 0) {
      const Sim voted = refine(in, t, w->sim, tau(), kFirstIterations);
      const double cost = hypothesisCost(in, t, voted);
      if (cost < costs[n]) {
        sims[n] = voted;
        costs[n] = cost;
      }
    }
    ++n;
  }
  if (n == 0)
    return best; // no turn: nothing in common
  // The two best go on to convergence (the others stay where their first steps left them).
  for (int round = 0; round < std::min(n, 2); ++round) {
    int k = round;
    for (int j = round + 1; j < n; ++j)
      if (costs[j] < costs[k])
        k = j;
    std::swap(sims[round], sims[k]);
    std::swap(costs[round], costs[k]);
    sims[round] = refine(in, t, sims[round], tau(), kIterations - kFirstIterations);
    costs[round] = hypothesisCost(in, t, sims[round]);
  }
  int b = 0, c = -1; // the best and the best that turns elsewhere
  for (int k = 1; k < n; ++k)
    if (costs[k] < costs[b])
      b = k;
  for (int k = 0; k < n; ++k)
    if (k != b && turnsApart(sims[k], sims[b]) && (c < 0 || costs[k] < costs[c]))
      c = k;
  if (!(costs[b] < 2.0))
    return best; // every hypothesis left the plausible scales
  best.transform = toPixels(in, t, sims[b]);
  best.cost = costs[b];
  // The best that turns elsewhere: a nearly symmetric outline lies almost as well on its template turned by its
  // symmetry, which the samples cannot tell apart and the outlines can (vpMorphRigidCheck).
  if (c >= 0) {
    best.alternative = toPixels(in, t, sims[c]);
    best.hasAlternative = true;
  }
  if (symmetric)
    addSymmetric(target, best);
  return best;
}

void vpMorphRigidShape::addSymmetric(const vpMorphRigidShape &target, Alignment &a) const
{
  if (!(a.cost < 2.0))
    return; // no alignment to turn
  const vpMorphRigidShapeData &in = *m_data, &t = *target.m_data;
  const Sim best = toSim(in, t, a.transform), other = toSim(in, t, a.alternative);
  // Least cost first: the turns the alignment's cost cannot rule out, unless the alternative already is one.
  for (const Symmetry &y : t.symmetries) {
    if (y.cost > 2.0 * a.cost)
      break;
    const Sim turned = compose(Sim{y.a, y.b, y.tx, y.ty}, best);
    if (!a.hasAlternative || turnsApart(turned, other))
      a.symmetric.push_back(Hypothesis{toPixels(in, t, turned), hypothesisCost(in, t, turned)});
  }
  a.selfTurns = a.symmetric.size();
  // The sweep: the winner turned about the target's centre and refined on this view, two steps each and the rest for
  // those still within the bound, as alignOn()'s turns are.
  const double bound = 2.0 * a.cost;
  std::vector<Sim> kept{best};
  if (a.hasAlternative)
    kept.push_back(other);
  for (const Hypothesis &h : a.symmetric)
    kept.push_back(toSim(in, t, h.transform));
  for (int k = 1; k < kSweepTurns; ++k) {
    const double turn = kTwoPi * k / kSweepTurns;
    Sim s = refine(in, t, compose(Sim{std::cos(turn), std::sin(turn), 0.0, 0.0}, best), tau(), kFirstIterations);
    double cost = hypothesisCost(in, t, s);
    if (!(cost < 2.0) || cost > bound)
      continue; // off the plausible scales, or ruled out
    s = refine(in, t, s, tau(), kIterations - kFirstIterations);
    cost = hypothesisCost(in, t, s);
    if (!(cost < 2.0) || cost > bound ||
        std::any_of(kept.begin(), kept.end(), [&s](const Sim &q) { return !turnsApart(s, q); }))
      continue;
    kept.push_back(s);
    a.symmetric.push_back(Hypothesis{toPixels(in, t, s), cost});
  }
}

const std::vector<vpMorphRigidShape::Symmetry> &vpMorphRigidShape::symmetries() const
{
  static const std::vector<Symmetry> none;
  return m_data ? m_data->symmetries : none;
}

double vpMorphRigidShape::cost(const vpMorphRigidShape &target, const vpMorphRigidTransform &transform) const
{
  check(*this, target);
  const Sim s = toSim(*m_data, *target.m_data, transform);
  return inputCost(*m_data, *target.m_data, s, tau()) + targetCost(*m_data, *target.m_data, s, tau());
}
