// Images shared by the morph unit tests: the six tools' images, a test polygon rendered anti-aliased and blurred,
// distances to an outline, the largest object's boundary, the benchmark scene's square occluder, views seen through a
// map (turned, shifted, scaled), blurred and noisy, and their objects extracted, and the bench views and goal databases
// saved in data/. Include after catch.hpp.
#ifndef VP_MORPH_TEST_IMAGES_H
#define VP_MORPH_TEST_IMAGES_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>

namespace vpMorphTest
{
//! A polygon's vertices, pixels.
struct Poly
{
  std::vector<double> x, y;
};

//! One of the six tools' images (data/objects/<name>.png), grey levels.
inline cv::Mat readObject(const std::string &name)
{
  cv::Mat m = cv::imread(std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png", cv::IMREAD_GRAYSCALE);
  REQUIRE_FALSE(m.empty());
  return m;
}

//! The object of \e m (vpMorphContourExtractor::extract()); \e joined: across an occluder (extractJoined(), as the
//! benchmark extracts).
inline vpMorphContour extract(const cv::Mat &m, bool joined = false)
{
  vpImage<unsigned char> I;
  vpImageConvert::convert(m, I);
  return joined ? vpMorphContourExtractor().extractJoined(I) : vpMorphContourExtractor().extract(I);
}

//! \e src seen through the 3x3 map M (white comes in from the borders), blurred by sigma 0.7 px as a lens does and
//! with Gaussian noise of std \e noise.
inline cv::Mat warp(const cv::Mat &src, const cv::Mat &M, double noise, unsigned int seed)
{
  cv::Mat out;
  cv::warpPerspective(src, out, M, src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255));
  cv::GaussianBlur(out, out, cv::Size(0, 0), 0.7);
  if (noise > 0) {
    cv::Mat n(out.size(), CV_32F), f;
    cv::RNG rng(seed);
    rng.fill(n, cv::RNG::NORMAL, 0.0, noise);
    out.convertTo(f, CV_32F);
    f += n;
    f.convertTo(out, CV_8U);
  }
  return out;
}

//! The 3x3 map that turns by \e deg about the image centre, scales, and shifts by (tx, ty) px.
inline cv::Mat similarity(const cv::Mat &src, double deg, double scale, double tx, double ty)
{
  cv::Mat R = cv::getRotationMatrix2D(cv::Point2f(src.cols / 2.f, src.rows / 2.f), deg, scale), M;
  R.at<double>(0, 2) += tx;
  R.at<double>(1, 2) += ty;
  cv::vconcat(R, cv::Mat((cv::Mat_<double>(1, 3) << 0, 0, 1)), M);
  return M;
}

// A ten-vertex, non-convex polygon (about 300 x 220 px) with acute and obtuse corners.
inline Poly testPolygon(double cx = 320, double cy = 240, double theta = 0.0)
{
  const double px[] = {0, 120, 150, 90, 160, 40, -80, -60, -140, -100};
  const double py[] = {-100, -90, -20, 10, 80, 120, 100, 30, 0, -80};
  Poly p;
  for (int k = 0; k < 10; ++k) {
    p.x.push_back(cx + std::cos(theta) * px[k] - std::sin(theta) * py[k]);
    p.y.push_back(cy + std::sin(theta) * px[k] + std::cos(theta) * py[k]);
  }
  return p;
}

// Distance from (px, py) to the segment (ax, ay)-(bx, by).
inline double segDist(double ax, double ay, double bx, double by, double px, double py)
{
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

// Distance from (px, py) to the closed outline (X, Y).
inline double distToOutline(const std::vector<double> &X, const std::vector<double> &Y, double px, double py)
{
  double m = 1e300;
  for (std::size_t k = 0; k < X.size(); ++k) {
    const std::size_t k1 = (k + 1) % X.size();
    m = std::min(m, segDist(X[k], Y[k], X[k1], Y[k1], px, py));
  }
  return m;
}

// Renders the polygons with area anti-aliasing (8x supersampling): grey level = coverage, object = obj,
// background = bg, then adds Gaussian noise of std sigma (seeded).
inline vpImage<unsigned char> render(const std::vector<Poly> &polys, unsigned char obj, unsigned char bg,
                                     double sigma = 0.0, unsigned int seed = 0, int w = 640, int h = 480)
{
  const int S = 8;
  cv::Mat big(h * S, w * S, CV_8UC1, cv::Scalar(255));
  std::vector<std::vector<cv::Point>> pts;
  for (const Poly &p : polys) {
    pts.emplace_back();
    for (std::size_t k = 0; k < p.x.size(); ++k)
      pts.back().emplace_back(cvRound((p.x[k] + 0.5) * S - 0.5), cvRound((p.y[k] + 0.5) * S - 0.5));
  }
  cv::fillPoly(big, pts, cv::Scalar(0));
  cv::Mat cover;
  cv::resize(big, cover, cv::Size(w, h), 0, 0, cv::INTER_AREA); // 255 = background, 0 = object
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  vpImage<unsigned char> I(static_cast<unsigned int>(h), static_cast<unsigned int>(w));
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double a = cover.at<unsigned char>(r, c) / 255.0;
      const double v = a * bg + (1.0 - a) * obj + (sigma > 0 ? g(rng) : 0.0);
      I[r][c] = cv::saturate_cast<unsigned char>(v);
    }
  return I;
}

// \e I blurred by a Gaussian of std \e sigma px (a camera's edge), as an OpenCV image of its own.
inline cv::Mat blurred(const vpImage<unsigned char> &I, double sigma)
{
  const cv::Mat m(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1, I.bitmap);
  cv::Mat b;
  cv::GaussianBlur(m, b, cv::Size(0, 0), sigma);
  return b;
}

//! The pixel boundary of the largest dark object.
inline std::vector<cv::Point> largestBoundary(const cv::Mat &src)
{
  cv::Mat bin = src < 128;
  std::vector<std::vector<cv::Point>> cs;
  cv::findContours(bin, cs, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  REQUIRE_FALSE(cs.empty());
  return *std::max_element(cs.begin(), cs.end(),
                           [](const auto &a, const auto &b) { return cv::contourArea(a) < cv::contourArea(b); });
}

/*!
  Hides \e share of the object's outline behind a grey square (neither background nor object) centred on the
  outline point at \e where (fraction of the perimeter), grown until that share of the outline lies inside it: the
  benchmark scene's occluder, which bites a notch into a straight side instead of cutting it off.
*/
inline cv::Mat squareOccluder(const cv::Mat &src, double where, double share)
{
  const std::vector<cv::Point> c = largestBoundary(src);
  const cv::Point o = c[static_cast<std::size_t>(where * c.size()) % c.size()];
  int h = 1;
  for (;; ++h) {
    std::size_t in = 0;
    for (const cv::Point &p : c)
      in += (std::abs(p.x - o.x) <= h && std::abs(p.y - o.y) <= h) ? 1 : 0;
    if (in >= share * c.size())
      break;
  }
  cv::Mat out = src.clone();
  cv::rectangle(out, cv::Point(o.x - h, o.y - h), cv::Point(o.x + h, o.y + h), cv::Scalar(170), cv::FILLED);
  return out;
}

//! \e src with a tab 40 px long and 8 px wide sticking out of its outline three tenths of the way round (a look-alike
//! that differs in one place), and the tab's middle in \e centre.
inline cv::Mat withTab(const cv::Mat &src, cv::Point &centre)
{
  const std::vector<cv::Point> boundary = largestBoundary(src);
  const std::size_t i = boundary.size() * 3 / 10;
  const cv::Point at = boundary[i],
                  t = boundary[(i + 5) % boundary.size()] - boundary[(i + boundary.size() - 5) % boundary.size()];
  cv::Point2d n(-t.y, t.x);
  n /= cv::norm(n);
  if (src.at<unsigned char>(cv::Point(at + cv::Point(cvRound(4 * n.x), cvRound(4 * n.y)))) == 0)
    n = -n; // outward
  auto along = [&](double s, double w) {
    return cv::Point(cvRound(at.x + s * n.x - w * n.y), cvRound(at.y + s * n.y + w * n.x));
  };
  cv::Mat out = src.clone();
  const std::vector<cv::Point> tab{along(-3, -4), along(40, -4), along(40, 4), along(-3, 4)};
  cv::fillConvexPoly(out, tab, cv::Scalar(0));
  centre = along(20, 0);
  return out;
}

//! A bench view saved in data/ (as vispmorph-reid or the servo bench renders it, cropped).
inline vpImage<unsigned char> readView(const char *name)
{
  vpImage<unsigned char> V;
  vpImageIo::read(V, (std::filesystem::path(__FILE__).parent_path() / "data" / name).string());
  return V;
}

//! A database of goals saved in data/ beside the views.
inline vpMorphDatabase readGoals(const char *name)
{
  return vpMorphDatabase::load((std::filesystem::path(__FILE__).parent_path() / "data" / name).string(), false);
}
} // namespace vpMorphTest

#endif
