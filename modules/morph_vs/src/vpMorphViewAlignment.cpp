#include <visp3/morph_vs/vpMorphViewAlignment.h>

#include <algorithm>
#include <cmath>

const char *vpMorphViewAlignment::modelName(Model m)
{
  switch (m) {
  case RIGID:
    return "rigid";
  case PART_HIDDEN:
    return "part hidden";
  case PART_BENT:
    return "part bent";
  case UNEXPLAINED:
    return "unexplained";
  }
  return "?";
}

double vpMorphViewAlignment::rotationDeviation() const { return std::sqrt(covariance[0][0]); }

double vpMorphViewAlignment::translationDeviation() const
{
  // The larger eigenvalue of the translation block.
  const double a = covariance[1][1], b = covariance[1][2], c = covariance[2][2];
  if (!std::isfinite(a) || !std::isfinite(c))
    return std::numeric_limits<double>::infinity();
  return std::sqrt(std::max(0.0, 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b)));
}

double vpMorphViewAlignment::scaleDeviation() const { return std::sqrt(covariance[3][3]); }

std::vector<std::pair<vpImagePoint, vpImagePoint>>
vpMorphViewAlignment::lines(const vpMorphContour &view, const vpCameraParameters &cam, std::size_t count) const
{
  std::vector<std::pair<vpImagePoint, vpImagePoint>> out;
  if (view.empty() || !explained())
    return out;
  const auto pixel = [&cam](double x, double y) {
    return vpImagePoint(cam.get_v0() + cam.get_py() * y, cam.get_u0() + cam.get_px() * x);
  };
  const std::size_t step = std::max<std::size_t>(1, view.size() / std::max<std::size_t>(1, count));
  for (std::size_t k = 0; k < view.size(); k += step) {
    double x, y;
    transform.apply(view.x(k), view.y(k), x, y);
    out.emplace_back(pixel(view.x(k), view.y(k)), pixel(x, y));
  }
  return out;
}
