#include <visp3/morph/vpMorphArticulation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>
#include <visp3/morph/vpMorphRigidTransform.h>

namespace
{
const double kPi = 3.14159265358979323846;
const int kSuper = 8;                       // fine pixels per pixel, each way, of pose()
const double kFitSigma = 0.5;               // px: the robust fit's floor (contours extracted from images)
const int kMargin = 6;                      // px of background around the drawn pose
const double kCoarseStep = 4.0;             // deg: the grid of estimate()
const unsigned int kPartFitRounds = 3;      // part fits of estimate()
const unsigned int kPartFitIterations = 20; // ICP rounds of each
const double kPartFitSigma = 0.05;          // px: their robust scale's floor (measured edges)
const double kOpeningGain = 0.02;           // intersection over union another opening must add to the taught one's

void badParameter(const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); }

//! Sets to 0 the pixels of \e img whose centre (integer coordinates) lies inside polygon \e p (even-odd rule), row
//! by row over the edges that span it.
void fillCentres(cv::Mat &img, const std::vector<cv::Point2d> &p)
{
  struct Edge
  {
    double y0, y1, x0, dxdy;
  };
  std::vector<Edge> edges;
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const cv::Point2d &a = p[j].y < p[i].y ? p[j] : p[i], &b = p[j].y < p[i].y ? p[i] : p[j];
    if (a.y != b.y) // a horizontal edge crosses no row centre from one side
      edges.push_back({a.y, b.y, a.x, (b.x - a.x) / (b.y - a.y)});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge &e, const Edge &f) { return e.y0 < f.y0; });
  std::vector<const Edge *> active;
  std::vector<double> xs;
  std::size_t next = 0;
  for (int r = 0; r < img.rows; ++r) {
    const double y = r;
    // An edge spans row y when y0 <= y < y1 (a vertex on the row counts once).
    for (; next < edges.size() && edges[next].y0 <= y; ++next)
      active.push_back(&edges[next]);
    active.erase(std::remove_if(active.begin(), active.end(), [y](const Edge *e) { return e->y1 <= y; }), active.end());
    xs.clear();
    for (const Edge *e : active)
      xs.push_back(e->x0 + (y - e->y0) * e->dxdy);
    std::sort(xs.begin(), xs.end());
    unsigned char *row = img.ptr<unsigned char>(r);
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const int c0 = std::max(0, static_cast<int>(std::ceil(xs[k])));
      const int c1 = std::min(img.cols, static_cast<int>(std::ceil(xs[k + 1])));
      for (int c = c0; c < c1; ++c)
        row[c] = 0;
    }
  }
}
//! The robust least-squares similarity that lays \e view on \e pose over their minimal-work correspondence.
vpMorphRigidTransform layOn(const vpMorphContour &view, const vpMorphContour &pose, vpMorphMatcher &matcher)
{
  return vpMorphRigidTransform::fitLeastSquares(view, pose, matcher.match(view, pose), true,
                                                vpMorphRigidTransform::TUKEY, 30, kFitSigma);
}
} // namespace

vpMorphArticulation::vpMorphArticulation(const vpMorphContour &part0, const vpMorphContour &part1,
                                         const vpImagePoint &pivot, double minAngle, double maxAngle)
  : m_pivot(pivot), m_min(minAngle), m_max(maxAngle)
{
  if (part0.empty() || part1.empty())
    badParameter("vpMorphArticulation: both parts need a contour");
  if (part0.units() != vpMorphContour::PIXEL || part1.units() != vpMorphContour::PIXEL)
    badParameter("vpMorphArticulation: the parts must be in pixels (the taught view's)");
  if (!std::isfinite(pivot.get_u()) || !std::isfinite(pivot.get_v()))
    badParameter("vpMorphArticulation: the pivot must be finite");
  if (!std::isfinite(minAngle) || !std::isfinite(maxAngle) || minAngle > 0.0 || maxAngle < 0.0 || minAngle <= -kPi ||
      maxAngle >= kPi) {
    std::ostringstream os;
    os << "vpMorphArticulation: the opening's range must hold 0 and lie within a half turn either way, got ["
       << minAngle << ", " << maxAngle << "] rad";
    badParameter(os.str());
  }
  m_parts[0] = part0;
  m_parts[1] = part1;
}

const vpMorphContour &vpMorphArticulation::part(unsigned int k) const
{
  if (k > 1)
    badParameter("vpMorphArticulation::part: the parts are 0 and 1");
  return m_parts[k];
}

vpMorphContour vpMorphArticulation::pose(double angle, unsigned int fixedPart) const
{
  return draw(angle, fixedPart, true);
}

vpMorphContour vpMorphArticulation::draw(double angle, unsigned int fixedPart, bool measured) const
{
  if (empty())
    badParameter("vpMorphArticulation::pose: empty articulation");
  if (fixedPart > 1)
    badParameter("vpMorphArticulation::pose: the fixed part is 0 or 1");
  if (!std::isfinite(angle) || angle < m_min - 1e-9 || angle > m_max + 1e-9) {
    std::ostringstream os;
    os << "vpMorphArticulation::pose: opening " << angle << " rad outside [" << m_min << ", " << m_max << "]";
    badParameter(os.str());
  }
  // Part 1 turns by +angle relative to part 0: the fixed part stays, the other turns about the pin.
  const unsigned int moving = 1 - fixedPart;
  const double turn = moving == 1 ? angle : -angle;
  const vpMorphRigidTransform T(turn, 0.0, 0.0, 1.0, m_pivot.get_u(), m_pivot.get_v());
  std::vector<std::vector<cv::Point2d>> polys(2);
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  for (unsigned int k = 0; k < 2; ++k) {
    const vpMorphContour &c = m_parts[k].outline();
    for (std::size_t i = 0; i < c.size(); ++i) {
      double x = c.x(i), y = c.y(i);
      if (k == moving)
        T.apply(c.x(i), c.y(i), x, y);
      polys[k].emplace_back(x, y);
      xmin = std::min(xmin, x), xmax = std::max(xmax, x);
      ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
  }
  const int x0 = static_cast<int>(std::floor(xmin)) - kMargin, y0 = static_cast<int>(std::floor(ymin)) - kMargin;
  const int W = static_cast<int>(std::ceil(xmax)) + kMargin - x0 + 1,
            H = static_cast<int>(std::ceil(ymax)) + kMargin - y0 + 1;
  const int super = measured ? kSuper : 1;
  if (W <= 0 || H <= 0 || static_cast<double>(W) * H * super * super > 4e7)
    badParameter("vpMorphArticulation::pose: the parts span no image of a sensible size");
  // Drawn super times finer, then averaged over each pixel: grey levels that are the share of the pixel covered, as
  // a camera integrates them. Not by cv::fillPoly: it takes the pixels on the edge too, which grows a shape by half a
  // fine pixel (0.07 px, 1 % of a thin tool's area, 2 mm of depth at 0.5 m).
  cv::Mat fine(H * super, W * super, CV_8UC1, cv::Scalar(255));
  for (std::vector<cv::Point2d> &p : polys) {
    // Pixel (i, j) of the image covers fine pixels super i .. super i + super - 1, whose centres are at
    // super x + (super - 1) / 2 for x the image coordinate.
    for (cv::Point2d &v : p)
      v = cv::Point2d((v.x - x0) * super + 0.5 * (super - 1), (v.y - y0) * super + 0.5 * (super - 1));
    fillCentres(fine, p);
  }
  if (!measured) { // the pixels' outer boundary polygonised, as the extractor does, without measuring the edges
    std::vector<std::vector<cv::Point>> contours;
    cv::Mat bin = fine == 0;
    cv::findContours(bin, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty())
      badParameter("vpMorphArticulation: the parts draw no region");
    const auto largest = std::max_element(contours.begin(), contours.end(), [](const auto &a, const auto &b) {
      return cv::contourArea(a) < cv::contourArea(b);
    });
    std::vector<vpImagePoint> chain;
    for (const cv::Point &q : *largest)
      chain.emplace_back(q.y + y0, q.x + x0);
    return vpMorphPolygonApproximation::approximate(chain);
  }
  cv::Mat img;
  cv::resize(fine, img, cv::Size(W, H), 0.0, 0.0, cv::INTER_AREA);
  vpImage<unsigned char> I(static_cast<unsigned int>(H), static_cast<unsigned int>(W));
  for (int r = 0; r < H; ++r)
    std::copy(img.ptr<unsigned char>(r), img.ptr<unsigned char>(r) + W, I[static_cast<unsigned int>(r)]);
  const vpMorphContour drawn = vpMorphContourExtractor().extract(I);
  return vpMorphRigidTransform(0.0, x0, y0).apply(drawn);
}

double vpMorphArticulation::fitOverlap(const vpMorphContour &view, const vpMorphContour &pose, vpMorphMatcher &matcher)
{
  vpMorphContour v;
  try {
    v = layOn(view, pose, matcher).apply(view);
  } catch (const vpException &) {
    // The robust fit collapsed the view (its weight left on pairs that meet one vertex of the pose: scale 0, found on
    // MPEG-7 shapes against the pliers' poses): no similarity lays it on the pose.
    return 0.0;
  }
  const double inter = v.overlapArea(pose), uni = v.area() + pose.area() - inter;
  return uni > 0.0 && std::isfinite(inter / uni) ? inter / uni : 0.0;
}

double vpMorphArticulation::estimate(const vpMorphContour &view, double *overlap) const
{
  if (empty())
    badParameter("vpMorphArticulation::estimate: empty articulation");
  if (view.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphArticulation::estimate: empty view");
  vpMorphMatcher matcher;
  auto score = [&](double a) { return fitOverlap(view, draw(a, 0, false), matcher); };
  const int n = std::max(2, static_cast<int>(std::ceil((m_max - m_min) / (kCoarseStep * kPi / 180.0))));
  const double h = (m_max - m_min) / n;
  std::vector<double> coarse(static_cast<std::size_t>(n) + 1);
  std::size_t top = 0;
  for (std::size_t i = 0; i < coarse.size(); ++i)
    if ((coarse[i] = score(m_min + h * static_cast<double>(i))) > coarse[top])
      top = i;
  // The peak of the parabola through the best node and its neighbours...
  double angle = m_min + h * static_cast<double>(top);
  if (top > 0 && top + 1 < coarse.size()) {
    const double den = coarse[top - 1] - 2.0 * coarse[top] + coarse[top + 1];
    if (den < 0.0)
      angle += 0.5 * h * std::max(-1.0, std::min(1.0, (coarse[top - 1] - coarse[top + 1]) / den));
  }
  // ...then each part laid on the view's edges alone (trimmed ICP with scale, from the pose's fit): the turn between
  // the two is the correction. Each arm's own edges fix its direction to a few hundredths of a degree, where the
  // overlap of the whole pose moves by thousandths.
  for (unsigned int it = 0; it < kPartFitRounds; ++it) {
    const vpMorphContour g = draw(angle, 0, false);
    const vpMorphContour v = layOn(view, g, matcher).apply(view.outline());
    const vpMorphContour p1 =
        vpMorphRigidTransform(angle, 0.0, 0.0, 1.0, m_pivot.get_u(), m_pivot.get_v()).apply(m_parts[1].outline());
    const double t0 = vpMorphRigidTransform::refineOnOutline(m_parts[0].outline(), v, vpMorphRigidTransform(), true,
                                                             kPartFitSigma, kPartFitIterations)
                          .theta();
    const double t1 =
        vpMorphRigidTransform::refineOnOutline(p1, v, vpMorphRigidTransform(), true, kPartFitSigma, kPartFitIterations)
            .theta();
    angle = std::max(m_min, std::min(m_max, angle + std::remainder(t1 - t0, 2.0 * kPi)));
  }
  // The taught opening unless another lays the view clearly better: an occluded view of the closed tool lies on
  // some other opening about as well (a card that bites an arm), and is no opened tool.
  const double taught = score(0.0), opened = score(angle);
  const bool open = opened - taught > kOpeningGain;
  const double best = open ? angle : 0.0, bestScore = open ? opened : taught;
  if (overlap)
    *overlap = bestScore;
  return best;
}

vpMorphContour vpMorphArticulation::poseFor(const vpMorphContour &view, double opening, unsigned int *fixedPart) const
{
  vpMorphMatcher matcher;
  vpMorphContour goal;
  double best = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < 2; ++k) {
    const vpMorphContour g = pose(opening, k);
    const double turn = std::fabs(layOn(view, g, matcher).theta());
    if (turn < best) {
      best = turn;
      goal = g;
      if (fixedPart)
        *fixedPart = k;
    }
  }
  return goal;
}
