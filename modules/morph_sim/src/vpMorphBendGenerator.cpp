#include <visp3/morph_sim/vpMorphBendGenerator.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphCoverage.h"

namespace
{
const int K = 4;                               // supersampling of the outline's mapping
const double kMinShare = 0.2, kMaxShare = 0.4; // share of the area beyond the pivot
const double kMinAngleDeg = 10.0, kMaxAngleDeg = 25.0;

void badImage(const std::string &msg) { throw vpMorphException(vpMorphException::badImageError, msg); }

} // namespace

vpMorphBendGenerator::Bend vpMorphBendGenerator::generate(const vpImage<unsigned char> &object, unsigned int seed)
{
  const int W = static_cast<int>(object.getWidth()), H = static_cast<int>(object.getHeight());
  if (W < 8 || H < 8)
    badImage("vpMorphBendGenerator: the image is empty");
  const cv::Mat1f coverage = vpMorphCoverage::fromImage(object);
  cv::Mat1f up;
  cv::resize(coverage, up, cv::Size(W * K, H * K), 0, 0, cv::INTER_LINEAR);
  cv::Mat1b hi = up > 0.5f;
  hi /= 255;
  const cv::Moments m = cv::moments(hi, true);
  if (m.m00 < 9.0 * K * K)
    badImage("vpMorphBendGenerator: no object in the image");

  // Principal axes of the region; u along the long axis towards the bent end, v across.
  const double cx = m.m10 / m.m00, cy = m.m01 / m.m00;
  const double phi = 0.5 * std::atan2(2.0 * m.mu11, m.mu20 - m.mu02);
  std::mt19937 rng(seed * 2654435761u + 97u);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const double end = uni(0, 1) < 0.5 ? -1.0 : 1.0;
  const double dx = end * std::cos(phi), dy = end * std::sin(phi);
  std::vector<double> along;
  along.reserve(static_cast<std::size_t>(m.m00));
  for (int y = 0; y < hi.rows; ++y)
    for (int x = 0; x < hi.cols; ++x)
      if (hi(y, x))
        along.push_back((x - cx) * dx + (y - cy) * dy);
  std::sort(along.begin(), along.end());
  const double q = uni(kMinShare, kMaxShare);
  const double x0 = along[static_cast<std::size_t>((1.0 - q) * (along.size() - 1))];
  const double L = along.back() - x0;
  double halfWidth = 1.0;
  for (int y = 0; y < hi.rows; ++y)
    for (int x = 0; x < hi.cols; ++x)
      if (hi(y, x) && (x - cx) * dx + (y - cy) * dy > x0 - K)
        halfWidth = std::max(halfWidth, std::fabs(-(x - cx) * dy + (y - cy) * dx));
  const double cap = std::min(kMaxAngleDeg, vpMath::deg(0.8 * L / halfWidth));
  double theta = vpMath::rad((uni(0, 1) < 0.5 ? -1.0 : 1.0) * std::min(cap, uni(kMinAngleDeg, kMaxAngleDeg)));

  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(hi.clone(), contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
  // Hi-res pixel centres are points of the region: map them (about the pivot, in the axes' frame).
  auto bend = [&](const cv::Point &p, double th, bool &inside) {
    const double px = p.x - cx, py = p.y - cy;
    const double u = px * dx + py * dy - x0, v = -px * dy + py * dx;
    double ou = u, ov = v;
    if (u > 0.0) {
      const double a = th * std::min(1.0, u / L);
      ou = u * std::cos(a) - v * std::sin(a);
      ov = u * std::sin(a) + v * std::cos(a);
    }
    const double X = cx + (ou + x0) * dx - ov * dy, Y = cy + (ou + x0) * dy + ov * dx;
    inside = inside && X >= K && Y >= K && X <= hi.cols - 1 - K && Y <= hi.rows - 1 - K;
    return cv::Point(static_cast<int>(std::lround(X)), static_cast<int>(std::lround(Y)));
  };
  std::vector<std::vector<cv::Point>> bent;
  bool fits = false;
  for (int attempt = 0; attempt < 6 && !fits; ++attempt, theta *= 0.5) {
    fits = true;
    bent = contours;
    for (auto &c : bent)
      for (cv::Point &p : c)
        p = bend(p, theta, fits);
  }
  if (!fits)
    badImage("vpMorphBendGenerator: the bent part finds no room in the canvas");
  theta *= 2.0; // the loop halved it once more after the one that fitted

  cv::Mat1b bentHi(hi.size(), 0);
  cv::drawContours(bentHi, bent, -1, cv::Scalar(1), cv::FILLED, cv::LINE_8, hierarchy);
  cv::Mat1b partHi = hi.clone();
  long part = 0, all = 0;
  for (int y = 0; y < hi.rows; ++y)
    for (int x = 0; x < hi.cols; ++x) {
      if (!hi(y, x))
        continue;
      ++all;
      if ((x - cx) * dx + (y - cy) * dy > x0)
        partHi(y, x) = 0;
      else
        ++part;
    }
  Bend out;
  cv::Mat1f f, c;
  bentHi.convertTo(f, CV_32F);
  cv::resize(f, c, cv::Size(W, H), 0, 0, cv::INTER_AREA);
  // Away from the pivot, the undeformed side keeps the input's own pixels (its anti-aliasing included): there the
  // variant is the template to the bit.
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double X = K * (x + 0.5) - 0.5, Y = K * (y + 0.5) - 0.5;
      if ((X - cx) * dx + (Y - cy) * dy < x0 - 2 * K)
        c(y, x) = coverage(y, x);
    }
  out.image = vpMorphCoverage::toImage(c);
  partHi.convertTo(f, CV_32F);
  cv::resize(f, c, cv::Size(W, H), 0, 0, cv::INTER_AREA);
  out.undeformedMask = vpMorphCoverage::toImage(c);
  out.undeformedShare = static_cast<double>(part) / all;
  out.angleDeg = vpMath::deg(theta);
  return out;
}
