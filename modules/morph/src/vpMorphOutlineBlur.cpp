#include <visp3/morph/vpMorphOutlineBlur.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Sub-rows a pixel of the filled outline is sampled on, at their centres: the coverage is exact along a row and a
// midpoint rule across rows (a nearly horizontal edge's position to 1/8 px in one column, unbiased along the edge).
const int kSubRows = 8;
// Grey levels of the object and its background: a contrast far above the 8-bit quantisation, no level clipped.
const double kObjectLevel = 40.0, kBackgroundLevel = 210.0;

// The share of each pixel (width x height, pixel (u, v) centred at (u, v)) that the closed polygon (x, y) covers
// (even-odd rule), as a camera's pixel integrates the light over its area.
cv::Mat coverage(const std::vector<double> &x, const std::vector<double> &y, int width, int height)
{
  const int rows = height * kSubRows;
  std::vector<std::vector<double>> crossings(static_cast<std::size_t>(rows));
  const std::size_t n = x.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double xa = x[k], ya = y[k], xb = x[(k + 1) % n], yb = y[(k + 1) % n];
    if (ya == yb)
      continue;
    // Sub-row r has its centre at y = (r + 0.5) / S - 0.5; an edge crosses it when it lies in [min y, max y).
    const double lo = std::min(ya, yb), hi = std::max(ya, yb);
    const int r0 = std::max(0, int(std::ceil((lo + 0.5) * kSubRows - 0.5)));
    const int r1 = std::min(rows - 1, int(std::ceil((hi + 0.5) * kSubRows - 0.5)) - 1);
    for (int r = r0; r <= r1; ++r) {
      const double yc = (r + 0.5) / kSubRows - 0.5;
      crossings[static_cast<std::size_t>(r)].push_back(xa + (yc - ya) * (xb - xa) / (yb - ya));
    }
  }
  cv::Mat cover = cv::Mat::zeros(height, width, CV_64F);
  for (int r = 0; r < rows; ++r) {
    std::vector<double> &c = crossings[static_cast<std::size_t>(r)];
    std::sort(c.begin(), c.end());
    double *row = cover.ptr<double>(r / kSubRows);
    for (std::size_t k = 0; k + 1 < c.size(); k += 2) {
      // The span [a, b] over pixels [u - 0.5, u + 0.5].
      const double a = std::max(-0.5, c[k]), b = std::min(width - 0.5, c[k + 1]);
      for (int u = int(std::floor(a + 0.5)); u <= int(std::floor(b + 0.5)) && u < width; ++u)
        row[u] += std::max(0.0, std::min(b, u + 0.5) - std::max(a, u - 0.5)) / kSubRows;
    }
  }
  return cover;
}
/*
  The ownEdge() marks of \e from for the outline (x, y) measured on its blurred image: each vertex takes its
  nearest vertex's of \e from. Both run the same way round from nearby starts, so after the first vertex the nearest
  is sought a few vertices about the last one's (the whole outline again when none is within the blur's reach).
*/
std::vector<bool> carriedMarks(const vpMorphContour &from, const std::vector<double> &x, const std::vector<double> &y,
                               double reach)
{
  const std::size_t m = from.size();
  auto d2 = [&](std::size_t i, std::size_t j) {
    const double dx = x[i] - from.x(j), dy = y[i] - from.y(j);
    return dx * dx + dy * dy;
  };
  auto nearestOf = [&](std::size_t i, std::size_t j0, std::size_t count) {
    std::size_t best = j0 % m;
    for (std::size_t k = 0; k < count; ++k)
      if (d2(i, (j0 + k) % m) < d2(i, best))
        best = (j0 + k) % m;
    return best;
  };
  constexpr std::size_t kBack = 8, kWindow = 40; // a blurred corner's vertices spread over a few old ones
  std::vector<bool> marks(x.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    j = i == 0 ? nearestOf(i, 0, m) : nearestOf(i, j + m - kBack, std::min(m, kWindow));
    if (d2(i, j) > reach * reach)
      j = nearestOf(i, 0, m);
    marks[i] = from.ownEdge(j);
  }
  return marks;
}
} // namespace

vpMorphContour vpMorphOutlineBlur::blurred(const vpMorphContour &contour, double sigma)
{
  if (!(sigma >= 0.0) || !std::isfinite(sigma))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphOutlineBlur::blurred: the blur must be finite and >= 0");
  if (contour.units() != vpMorphContour::PIXEL || !contour.hasOutline())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphOutlineBlur::blurred: a contour in pixels, with a measured outline, is needed");
  const vpMorphContour &o = contour.outline();
  const auto [xmin, xmax] = std::minmax_element(o.xs().begin(), o.xs().end());
  const auto [ymin, ymax] = std::minmax_element(o.ys().begin(), o.ys().end());
  // A margin for the blur's tails (3 sigma) and the extractor's band and background ring about the edge (6 px).
  const int margin = int(std::ceil(3.0 * sigma)) + 8;
  const int u0 = int(std::floor(*xmin)) - margin, v0 = int(std::floor(*ymin)) - margin;
  const int width = int(std::ceil(*xmax)) + margin - u0 + 1, height = int(std::ceil(*ymax)) + margin - v0 + 1;
  if (!(double(width) * height < 1e8))
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphOutlineBlur::blurred: outline too large");
  std::vector<double> x(o.xs()), y(o.ys());
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] -= u0;
    y[k] -= v0;
  }
  cv::Mat level = coverage(x, y, width, height) * (kObjectLevel - kBackgroundLevel) + kBackgroundLevel;
  if (sigma > 0.0)
    cv::GaussianBlur(level, level, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  vpImage<unsigned char> I(static_cast<unsigned int>(height), static_cast<unsigned int>(width));
  for (int v = 0; v < height; ++v) {
    const double *p = level.ptr<double>(v);
    for (int u = 0; u < width; ++u)
      I[v][u] = static_cast<unsigned char>(std::lround(std::min(255.0, std::max(0.0, p[u]))));
  }
  vpMorphContour measured;
  try {
    measured = vpMorphContourExtractor().extract(I);
  } catch (const vpMorphException &e) {
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphOutlineBlur::blurred: no object on the blurred image: " + e.getStringMessage());
  }
  if (!measured.hasOutline())
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphOutlineBlur::blurred: the blurred image shows no measured outline");
  std::vector<double> ex(measured.outline().xs()), ey(measured.outline().ys());
  for (std::size_t k = 0; k < ex.size(); ++k) {
    ex[k] += u0;
    ey[k] += v0;
  }
  vpMorphContour outline(ex, ey);
  if (o.hasOwnEdges())
    outline.setOwnEdges(carriedMarks(o, ex, ey, 3.0 * sigma + 1.0));
  vpMorphContour out(contour);
  out.setOutline(outline, measured.outlineBlur());
  return out;
}

double vpMorphOutlineBlur::leastBlur(const vpMorphContour &contour)
{
  return std::sqrt(contour.outlineBlur() * contour.outlineBlur() + pixelVariance());
}

vpMorphContour vpMorphOutlineBlur::blurredTo(const vpMorphContour &contour, double blur)
{
  const double least = leastBlur(contour);
  if (!(blur >= least) || !std::isfinite(blur))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphOutlineBlur::blurredTo: the blur must be finite and at least the outline's own and "
                           "the pixel's (leastBlur())");
  return blurred(contour, std::sqrt(blur * blur - least * least));
}
