#include <visp3/morph/vpMorphShapeDistance.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>

#include "vpMorphSmoothing.h"

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// Incoming edge lengths (unit perimeter) and turning angles of the positive traversal, exactly as the matcher
// computes them (see vpMorphMatcher::prepare()).
void features(const vpMorphContour &C, std::vector<double> &len, std::vector<double> &phi)
{
  const std::size_t N = C.size();
  const bool reversed = C.signedArea() < 0;
  const double s = 1.0 / C.perimeter();
  len.resize(N);
  phi.resize(N);
  for (std::size_t r = 0; r < N; ++r) {
    if (!reversed) {
      len[r] = C.edgeLength(r) * s;
      phi[r] = C.turningAngle(r);
    } else {
      const std::size_t o = (N - r) % N;
      len[r] = C.edgeLength((o + 1) % N) * s;
      phi[r] = -C.turningAngle(o);
    }
  }
}

// Smallest (v - x)^2 over a sorted list: the nearest neighbours of x.
inline double nearestSq(const std::vector<double> &sorted, double x)
{
  auto it = std::lower_bound(sorted.begin(), sorted.end(), x);
  double best = kInf;
  if (it != sorted.end())
    best = (*it - x) * (*it - x);
  if (it != sorted.begin()) {
    const double d = *(it - 1) - x;
    best = std::min(best, d * d);
  }
  return best;
}

// Smallest stretching work from length l to any length of a sorted list (unimodal: zero at l).
inline double nearestStretch(const vpMorphWorkModel &w, const std::vector<double> &sorted, double l)
{
  auto it = std::lower_bound(sorted.begin(), sorted.end(), l);
  double best = kInf;
  if (it != sorted.end())
    best = w.stretching(l, *it);
  if (it != sorted.begin())
    best = std::min(best, w.stretching(l, *(it - 1)));
  return best;
}

// Sum over the vertices i of A of the cheapest step that can enter i: separable version (stretching and bending
// minimised independently, O(m log n)) or exact row minima (O(mn)).
double rowBound(const vpMorphWorkModel &w, const std::vector<double> &lA, const std::vector<double> &pA,
                const std::vector<double> &lBs, const std::vector<double> &pBs)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < lA.size(); ++i) {
    const double alone = w.stretching(lA[i], 0.0) + w.kb() * pA[i] * pA[i];
    const double diag = nearestStretch(w, lBs, lA[i]) + w.kb() * nearestSq(pBs, pA[i]);
    sum += std::min(alone, diag);
  }
  return sum;
}

double rowBoundExact(const vpMorphWorkModel &w, const std::vector<double> &lA, const std::vector<double> &pA,
                     const std::vector<double> &lB, const std::vector<double> &pB)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < lA.size(); ++i) {
    double best = w.stretching(lA[i], 0.0) + w.kb() * pA[i] * pA[i];
    for (std::size_t j = 0; j < lB.size(); ++j)
      best = std::min(best, w.stretching(lA[i], lB[j]) + w.bending(pA[i], pB[j]));
    sum += best;
  }
  return sum;
}
} // namespace

vpMorphShapeDistance::vpMorphShapeDistance(Model model) : m_model(model), m_points(0), m_mirrors(false), m_scales{0.0}
{
  switch (model) {
  case POLYGON:
    break;
  case PAPER:
    m_points = 64;
    m_mirrors = true;
    m_work = vpMorphWorkModel(1.0, 0.1, 0.5);
    break;
  case MULTISCALE:
    m_points = 48;
    m_mirrors = true;
    m_work = vpMorphWorkModel(1.0, 0.2, 0.5);
    m_scales = {0.01, 0.05, 0.1};
    break;
  case RIGID:
    break;
  case HEIGHT:
    m_points = m_height.getPoints();
    m_mirrors = m_height.getMirrors();
    break;
  }
}

vpMorphShapeDistance vpMorphShapeDistance::fromName(const std::string &name)
{
  if (name == "polygon")
    return vpMorphShapeDistance(POLYGON);
  if (name == "paper")
    return vpMorphShapeDistance(PAPER);
  if (name == "multiscale")
    return vpMorphShapeDistance(MULTISCALE);
  if (name == "rigid")
    return vpMorphShapeDistance(RIGID);
  if (name == "height")
    return vpMorphShapeDistance(HEIGHT);
  throw vpMorphException(vpMorphException::badParameterError, "vpMorphShapeDistance: unknown model '" + name +
                                                                  "' (polygon, paper, multiscale, rigid or height)");
}

std::string vpMorphShapeDistance::settingsJson() const
{
  nlohmann::json j = {{"model", name()},   {"points", points()}, {"mirrors", mirrors()}, {"scales", scales()},
                      {"ks", m_work.ks()}, {"kb", m_work.kb()},  {"cs", m_work.cs()}};
  if (m_model == HEIGHT)
    j.update({{"segments", m_height.getSegments()},
              {"skip", m_height.getSkipCost()},
              {"starts", m_height.getCandidateStarts()}});
  return j.dump();
}

std::string vpMorphShapeDistance::name() const
{
  switch (m_model) {
  case PAPER:
    return "paper";
  case MULTISCALE:
    return "multiscale";
  case RIGID:
    return "rigid";
  case HEIGHT:
    return "height";
  default:
    return "polygon";
  }
}

void vpMorphShapeDistance::setPoints(std::size_t n)
{
  if (m_model != POLYGON && m_model != RIGID && n < 8) {
    std::ostringstream os;
    os << "vpMorphShapeDistance: " << n << " points per outline is too few (at least 8)";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (m_model == HEIGHT)
    m_height.setPoints(n, m_height.getSegments());
  m_points = m_model == POLYGON || m_model == RIGID ? 0 : n;
}

void vpMorphShapeDistance::setHeightFunction(const vpMorphHeightFunction &h)
{
  m_height = h;
  m_height.setMirrors(m_mirrors);
  if (m_model == HEIGHT)
    m_points = m_height.getPoints();
}

void vpMorphShapeDistance::setScales(const std::vector<double> &sigmas)
{
  if (sigmas.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphShapeDistance: empty list of scales");
  for (double s : sigmas)
    if (!std::isfinite(s) || s < 0.0 || s > 0.25)
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphShapeDistance: scale widths must be in [0, 0.25] of the perimeter");
  m_scales = sigmas;
}

vpMorphShapeDistance::Shape vpMorphShapeDistance::prepare(const vpMorphContour &c, bool rigidMirror) const
{
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphShapeDistance: empty contour");
  Shape s;
  if (m_model == HEIGHT) {
    s.height = m_height.describe(c);
    return s;
  }
  if (m_model == RIGID) {
    s.forms.push_back(c);
    s.rigid.emplace_back(c);
    if (m_mirrors) {
      s.forms.push_back(c.mirrored());
      if (rigidMirror)
        s.rigid.emplace_back(s.forms.back());
    }
    return s;
  }
  const std::vector<double> scales = m_model == POLYGON ? std::vector<double>{0.0} : m_scales;
  for (double sigma : scales) {
    const vpMorphContour f = m_model == POLYGON ? c : vpMorphSmoothed(c, sigma, m_points);
    s.forms.push_back(f);
    if (m_mirrors)
      s.forms.push_back(f.mirrored());
    std::vector<double> len, phi;
    features(f, len, phi);
    s.len.push_back(len);
    s.phi.push_back(phi);
    std::sort(len.begin(), len.end());
    std::sort(phi.begin(), phi.end());
    s.lenSort.push_back(len);
    s.phiSort.push_back(phi);
  }
  return s;
}

vpMorphRigidShape vpMorphShapeDistance::rigidShape(const Shape &s, std::size_t m)
{
  if (s.rigid.empty() || m >= s.forms.size())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphShapeDistance::rigidShape: no such form of a shape prepared for RIGID");
  return m < s.rigid.size() ? s.rigid[m] : vpMorphRigidShape(s.forms[m]);
}

double vpMorphShapeDistance::distance(const Shape &a, const Shape &b, vpMorphMatcher &matcher, double abandonAbove,
                                      bool *mirrored, vpMorphRigidCheck::Result *check) const
{
  const std::size_t per = m_mirrors ? 2 : 1;
  if (m_model == HEIGHT)
    return m_height.distance(a.height, b.height, mirrored);
  if (m_model == RIGID) {
    if (a.rigid.empty() || a.forms.size() != per || b.rigid.empty())
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphShapeDistance: shapes prepared with another distance");
    vpMorphRigidCheck::Result best;
    bool bestMirror = false;
    for (std::size_t m = 0; m < per; ++m) {
      const vpMorphRigidShape view = rigidShape(a, m);
      const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(view, b.rigid[0], view.alignOn(b.rigid[0]));
      if (m == 0 || r.cost < best.cost) {
        best = r;
        bestMirror = m == 1;
      }
    }
    if (mirrored)
      *mirrored = bestMirror;
    if (check)
      *check = best;
    return best.cost;
  }
  const std::size_t nScales = a.len.size();
  if (nScales == 0 || b.len.size() != nScales || a.forms.size() != nScales * per || b.forms.size() != nScales * per)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphShapeDistance: shapes prepared with another distance");
  double best = kInf;
  bool bestMirror = false;
  for (std::size_t m = 0; m < per; ++m) {
    double sum = 0.0;
    for (std::size_t s = 0; s < nScales; ++s) {
      sum += matcher.distance(a.forms[s * per], b.forms[s * per + m]);
      // Partial sums only grow: stop when this mirror choice can no longer beat the best or the bound.
      if (sum >= best || (abandonAbove >= 0.0 && sum > abandonAbove))
        break;
    }
    if (sum < best) {
      best = sum;
      bestMirror = m == 1;
    }
  }
  if (mirrored)
    *mirrored = bestMirror;
  return best;
}

double vpMorphShapeDistance::distance(const vpMorphContour &a, const vpMorphContour &b) const
{
  vpMorphMatcher m = matcher();
  return distance(prepare(a), prepare(b), m);
}

double vpMorphShapeDistance::lowerBound(const Shape &a, const Shape &b) const
{
  if (m_model == RIGID || m_model == HEIGHT)
    return 0.0;
  double sum = 0.0;
  for (std::size_t s = 0; s < a.len.size() && s < b.len.size(); ++s) {
    const double cheap = std::max(rowBound(m_work, a.len[s], a.phi[s], b.lenSort[s], b.phiSort[s]),
                                  rowBound(m_work, b.len[s], b.phi[s], a.lenSort[s], a.phiSort[s]));
    const double exact = std::max(rowBoundExact(m_work, a.len[s], a.phi[s], b.len[s], b.phi[s]),
                                  rowBoundExact(m_work, b.len[s], b.phi[s], a.len[s], a.phi[s]));
    sum += std::max(cheap, exact);
  }
  // Rounding: the matcher sums the same non-negative terms in another order.
  return sum * (1.0 - 1e-9);
}

void vpMorphShapeDistance::parallelFor(std::size_t count, unsigned int threads,
                                       const std::function<void(std::size_t, vpMorphMatcher &)> &job,
                                       const Progress &progress,
                                       const std::function<std::size_t(std::size_t)> &weight) const
{
  if (threads == 0)
    threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned int>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
  std::size_t total = 0;
  for (std::size_t k = 0; k < count; ++k)
    total += weight ? weight(k) : 1;
  std::atomic<std::size_t> next(0), done(0);
  std::atomic<bool> failed(false);
  std::exception_ptr error;
  std::mutex mx;
  std::condition_variable cv;
  unsigned int running = threads;
  auto worker = [&]() {
    vpMorphMatcher matcher = this->matcher();
    for (;;) {
      const std::size_t k = next++;
      if (k >= count || failed)
        break;
      try {
        job(k, matcher);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mx);
        if (!failed.exchange(true))
          error = std::current_exception();
      }
      done += weight ? weight(k) : 1;
    }
    std::lock_guard<std::mutex> lock(mx);
    --running;
    cv.notify_all();
  };
  std::vector<std::thread> pool;
  for (unsigned int t = 0; t < threads; ++t)
    pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mx);
    while (running > 0) {
      cv.wait_for(lock, std::chrono::milliseconds(100));
      if (progress && running > 0) {
        lock.unlock();
        progress(done.load(), total);
        lock.lock();
      }
    }
  }
  for (std::thread &t : pool)
    t.join();
  if (error)
    std::rethrow_exception(error);
  if (progress)
    progress(total, total);
}

std::vector<vpMorphShapeDistance::Shape> vpMorphShapeDistance::prepareAll(const std::vector<vpMorphContour> &contours,
                                                                          unsigned int threads,
                                                                          const Progress &progress) const
{
  std::vector<Shape> out(contours.size());
  parallelFor(
      contours.size(), threads, [&](std::size_t k, vpMorphMatcher &) { out[k] = prepare(contours[k]); }, progress);
  return out;
}

std::vector<double> vpMorphShapeDistance::matrix(const std::vector<Shape> &shapes, unsigned int threads,
                                                 const Progress &progress) const
{
  const std::size_t N = shapes.size();
  std::vector<double> D(N * N, 0.0);
  // Row k computes the pairs (k, j > k): rows are handed out one at a time, so the long first rows and the
  // short last ones balance over the threads.
  parallelFor(
      N, threads,
      [&](std::size_t i, vpMorphMatcher &matcher) {
        for (std::size_t j = i + 1; j < N; ++j)
          D[i * N + j] = D[j * N + i] = distance(shapes[i], shapes[j], matcher);
      },
      progress, [N](std::size_t i) { return N - 1 - i; });
  return D;
}
