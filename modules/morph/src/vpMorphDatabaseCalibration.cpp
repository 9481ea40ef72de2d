#include <visp3/morph/vpMorphDatabase.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphRigidSearch.h"

// vpMorphDatabase::calibrate(): each template's distance to perturbed copies of itself and to its nearest neighbour.

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// Renders a pixel contour, filled (object 255 on background 0), into an image with a margin, after an optional
// rotation about its centroid; \e cut (if not empty) is a polygon painted back to background (an occluder).
// Returns the largest object's polygon, re-extracted: what a camera would see of the same outline.
vpMorphContour renderAndExtract(const vpMorphContour &c, double theta, double noiseSigma, unsigned int seed,
                                const std::vector<cv::Point2d> &cut)
{
  double cx, cy;
  c.centroid(cx, cy);
  vpMorphContour r = c.transformed(theta, 0.0, 0.0, 1.0);
  double minx = kInf, miny = kInf, maxx = -kInf, maxy = -kInf;
  for (std::size_t k = 0; k < r.size(); ++k) {
    minx = std::min(minx, r.x(k)), maxx = std::max(maxx, r.x(k));
    miny = std::min(miny, r.y(k)), maxy = std::max(maxy, r.y(k));
  }
  // Work at the contour's own pixel scale, within sane limits (normalised contours are tiny).
  const double side = std::max(maxx - minx, maxy - miny);
  const double s = side < 100.0 ? 100.0 / side : (side > 800.0 ? 800.0 / side : 1.0);
  const int margin = 10;
  const int W = static_cast<int>(std::ceil((maxx - minx) * s)) + 2 * margin;
  const int H = static_cast<int>(std::ceil((maxy - miny) * s)) + 2 * margin;
  cv::Mat img(H, W, CV_8UC1, cv::Scalar(0));
  std::vector<cv::Point> pts;
  auto toPix = [&](double x, double y) {
    return cv::Point(static_cast<int>(std::lround((x - minx) * s + margin)),
                     static_cast<int>(std::lround((y - miny) * s + margin)));
  };
  for (std::size_t k = 0; k < r.size(); ++k)
    pts.push_back(toPix(r.x(k), r.y(k)));
  cv::fillPoly(img, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(255));
  if (!cut.empty()) {
    // The cut is given in the unrotated contour's coordinates (theta is 0 for occlusions).
    std::vector<cv::Point> cp;
    for (const cv::Point2d &p : cut)
      cp.push_back(toPix(p.x, p.y));
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{cp}, cv::Scalar(0));
  }
  vpImage<unsigned char> I(static_cast<unsigned int>(H), static_cast<unsigned int>(W));
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, noiseSigma);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      double val = 40.0 + img.at<unsigned char>(v, u) * (160.0 / 255.0);
      if (noiseSigma > 0.0)
        val += g(rng);
      I[v][u] = static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::round(val))));
    }
  vpMorphContour e = vpMorphContourExtractor().extract(I);
  return e.units() == c.units() && c.units() == vpMorphContour::PIXEL ? e : vpMorphContour(e.xs(), e.ys(), c.units());
}

// The piece of outline from arc length s0 to s0 + fraction of the perimeter, closed by its chord: painting it
// with the background hides that part of the outline behind a straight edge.
std::vector<cv::Point2d> chordCut(const vpMorphContour &c, double s0, double fraction)
{
  const std::size_t n = 400;
  const vpMorphContour d = c.resampled(n);
  std::vector<cv::Point2d> cut;
  const std::size_t a = static_cast<std::size_t>(s0 * n) % n, len = static_cast<std::size_t>(fraction * n);
  for (std::size_t k = 0; k <= len; ++k) {
    const std::size_t i = (a + k) % n;
    cut.emplace_back(d.x(i), d.y(i));
  }
  return cut;
}
} // namespace

std::vector<vpMorphContour> vpMorphDatabase::perturbations(const vpMorphContour &c)
{
  std::vector<vpMorphContour> out;
  // New views: rotated (re-digitised) and noisy images of the same outline.
  out.push_back(renderAndExtract(c, 0.5, 0.0, 1, {}));
  out.push_back(renderAndExtract(c, 2.0, 25.0, 2, {}));
  out.push_back(renderAndExtract(c, -1.2, 40.0, 3, {}));
  // The same outline sampled from another start (for resampling models).
  out.push_back(c.rotatedStart(c.size() / 2));
  // A straight occluding edge hiding 20 % of the outline, at sixteen places.
  for (int k = 0; k < 16; ++k)
    out.push_back(renderAndExtract(c, 0.0, 0.0, 10 + k, chordCut(c, 0.0625 * k + 0.03, 0.20)));
  return out;
}

void vpMorphDatabase::calibrate(unsigned int threads, const Progress &progress)
{
  const std::size_t T = m_templates.size();
  if (T == 0)
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphDatabase::calibrate: empty database");
  std::vector<double> within(T, 0.0);
  const std::size_t perRow = T > 1 ? T : 0;
  const bool rigid = m_distance.model() == vpMorphShapeDistance::RIGID;
  std::vector<double> D(T * T, rigid ? kInf : 0.0);     // RIGID fills only each row's nearest other template
  std::vector<std::vector<Found>> found(rigid ? T : 0); // RIGID: the look-alikes each row finds
  // Jobs 0..T-1: within(t); jobs T..2T-1: row t of the between-template matrix.
  m_distance.parallelFor(
      T + (perRow ? T : 0), threads,
      [&](std::size_t k, vpMorphMatcher &matcher) {
        if (k < T) {
          for (const vpMorphContour &p : perturbations(m_templates[k].contour()))
            within[k] = std::max(within[k], m_distance.distance(m_distance.prepare(p), m_shapes[k], matcher));
        } else if (rigid) {
          // The nearest other template and the look-alikes: every other one compared exactly.
          const std::size_t i = k - T;
          std::size_t nearest;
          const double d = rigidRow(i, found[i], nearest);
          if (nearest != vpMorphRecognition::npos)
            D[i * T + nearest] = d;
        } else {
          const std::size_t i = k - T;
          for (std::size_t j = i + 1; j < T; ++j)
            D[i * T + j] = D[j * T + i] = m_distance.distance(m_shapes[i], m_shapes[j], matcher);
        }
      },
      progress);
  std::vector<double> between(T, kInf);
  for (std::size_t i = 0; i < T; ++i)
    for (std::size_t j = 0; j < T; ++j)
      if (i != j)
        between[i] = std::min(between[i], D[i * T + j]);
  m_within = within;
  m_between = between;
  m_lookAlikes = gathered(found);
  m_calibrated = true;
}

double vpMorphDatabase::rigidRow(std::size_t i, std::vector<Found> &found, std::size_t &nearest) const
{
  // Every other template, not a shortlist: the coarse cost ranks whole outlines, and a template that i's outline
  // only partly coincides with, as a view of i under a card can be taken for, may rank anywhere. Its hypotheses
  // beyond the alignment and its alternative are bounded as a query's search bounds them (the shortlist's cost).
  const vpMorphRigidSearch::Outcome o =
      vpMorphRigidSearch::run(m_shapes[i].rigid[0], rigidViews(false, i), rigidShortlist(), nullptr, {}, false, true);
  // Template i is a look-alike of j when its whole outline shows at least the minimum support of j's.
  for (const vpMorphRigidSearch::Exact &e : o.exact)
    if (e.result.fitted && e.result.targetShare >= m_minSupport)
      found.push_back(Found{e.index, LookAlike{i, e.result.start.inverse()}});
  nearest = o.index;
  return o.best.cost;
}

std::vector<std::vector<vpMorphDatabase::LookAlike>>
vpMorphDatabase::gathered(const std::vector<std::vector<Found>> &found) const
{
  std::vector<std::vector<LookAlike>> lookAlikes(m_templates.size());
  for (const std::vector<Found> &row : found) // rows in index order: each list sorted by index
    for (const Found &f : row)
      lookAlikes[f.of].push_back(f.lookAlike);
  return lookAlikes;
}

void vpMorphDatabase::findLookAlikes(unsigned int threads)
{
  const std::size_t T = m_templates.size();
  std::vector<std::vector<Found>> found(T);
  m_distance.parallelFor(T, threads, [&](std::size_t i, vpMorphMatcher &) {
    std::size_t nearest;
    rigidRow(i, found[i], nearest);
  });
  m_lookAlikes = gathered(found);
}
