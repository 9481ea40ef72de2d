#include <visp3/morph/vpMorphDatabase.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphOutlineShare.h"
#include "vpMorphRigidSearch.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPoseStep = 3.14159265358979323846 / 45.0; // 4 deg between an articulated template's poses
const char *kFormat = "vispmorph-template-database";
constexpr int kVersion = 1;
constexpr double kRigidSupport = 0.5; // RIGID's minimum support (class description)

vpMorphException ioError(const std::string &msg) { return vpMorphException(vpMorphException::ioError, msg); }

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

// vpMorphDatabase::support() of view q on template t, from the correspondence q -> t.
double shownShare(const vpMorphContour &q, const vpMorphContour &t, const vpMorphCorrespondence &correspondence)
{
  double best = 0.0;
  try {
    const vpMorphOutlineShare shown(t);
    const vpMorphRigidTransform T0 = shown.fitted(q, correspondence);
    // From the fit and from it turned half a turn about the template's centre: the correspondence of a nearly
    // symmetric outline (a wedge, end for end) can put the view the wrong way round, where the refinement stays.
    for (const vpMorphRigidTransform &start : {T0, shown.halfTurned(T0)})
      best = std::max(best, shown.aligned(q, start));
  } catch (const vpException &) {
    // no similarity aligns them (a degenerate fit): the view shows nothing more of the template
  }
  return best;
}

/*
  shownShare() of q from \e direct, the minimal-work correspondence of q itself, and when \e mirrored also of q's mirror
  image: the better counts. A nearly symmetric part (the screwdriver) can be matched by its mirror image for a hair
  less work, and the polygons of its mirror image then align badly (0.05 of the outline shown).
*/
double shownEitherWay(const vpMorphContour &q, const vpMorphContour &t, vpMorphMatcher &matcher, bool mirrored,
                      const vpMorphCorrespondence &direct)
{
  const double s = shownShare(q, t, direct);
  if (!mirrored)
    return s;
  const vpMorphContour m = q.mirrored();
  return std::max(shownShare(m, t, matcher.match(m, t)), s);
}

json poseToJson(const vpHomogeneousMatrix &M)
{
  json a = json::array();
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      a.push_back(M[i][j]);
  return a;
}

template <typename T> T field(const json &j, const char *key, const std::string &where)
{
  if (!j.is_object() || !j.contains(key))
    throw ioError("vpMorphDatabase: " + where + " has no \"" + key + "\" field");
  try {
    return j.at(key).get<T>();
  } catch (const json::exception &e) {
    throw ioError("vpMorphDatabase: " + where + ": field \"" + key + "\" has the wrong type (" + e.what() + ")");
  }
}

// JSON has no infinity: +inf (no other template) is written as null.
json finiteOrNull(const std::vector<double> &v)
{
  json a = json::array();
  for (double x : v)
    a.push_back(std::isfinite(x) ? json(x) : json(nullptr));
  return a;
}

std::vector<double> numbersOrInf(const json &cal, const char *key)
{
  if (!cal.contains(key) || !cal[key].is_array())
    throw ioError(std::string("vpMorphDatabase: \"calibration\" has no \"") + key + "\" array");
  std::vector<double> v;
  for (const json &x : cal[key]) {
    if (x.is_null())
      v.push_back(kInf);
    else if (x.is_number() && x.get<double>() >= 0.0)
      v.push_back(x.get<double>());
    else
      throw ioError(std::string("vpMorphDatabase: \"calibration\": \"") + key + "\" must hold numbers >= 0");
  }
  return v;
}

//! A contour's fields of a template object: units, vertices, and the measured region and outline when present.
void contourToJson(const vpMorphContour &c, json &o)
{
  o["units"] = c.units() == vpMorphContour::PIXEL ? "pixel" : "normalized";
  o["x"] = c.xs();
  o["y"] = c.ys();
  if (c.hasRegion()) {
    double cx, cy, mu20, mu11, mu02;
    c.regionCentroid(cx, cy);
    c.regionMoments(mu20, mu11, mu02);
    o["region"] = {{"area", c.regionArea()}, {"cx", cx}, {"cy", cy}, {"mu20", mu20}, {"mu11", mu11}, {"mu02", mu02}};
  }
  if (c.hasOutline()) // the measured edge, for the out-of-plane estimate of vpServoMorph
    o["outline"] = {{"x", c.outline().xs()}, {"y", c.outline().ys()}};
}

//! Runs \e f, the errors of what it builds reported as a malformed file at \e where.
template <typename F> void asFileError(const std::string &where, F f)
{
  try {
    f();
  } catch (const vpMorphException &e) {
    if (e.getCode() == vpMorphException::ioError)
      throw;
    throw ioError("vpMorphDatabase: " + where + ": " + e.getStringMessage());
  }
}

//! The contour written by contourToJson(); \e where names it in the errors.
vpMorphContour contourFromJson(const json &o, const std::string &where)
{
  const std::string units = field<std::string>(o, "units", where);
  if (units != "pixel" && units != "normalized")
    throw ioError("vpMorphDatabase: " + where + ": units must be \"pixel\" or \"normalized\"");
  const std::vector<double> x = field<std::vector<double>>(o, "x", where);
  const std::vector<double> y = field<std::vector<double>>(o, "y", where);
  vpMorphContour c;
  try {
    c = vpMorphContour(x, y, units == "pixel" ? vpMorphContour::PIXEL : vpMorphContour::NORMALIZED);
  } catch (const vpException &e) {
    throw ioError("vpMorphDatabase: " + where + ": invalid contour: " + e.getStringMessage());
  }
  if (o.contains("region")) { // optional: the region measured on the template image
    const json &r = o["region"];
    if (!r.is_object())
      throw ioError("vpMorphDatabase: " + where + ": \"region\" must be an object {area, cx, cy, mu20, mu11, mu02}");
    const std::string w = where + " \"region\"";
    asFileError(w, [&] {
      c.setRegion(field<double>(r, "area", w), field<double>(r, "cx", w), field<double>(r, "cy", w),
                  field<double>(r, "mu20", w), field<double>(r, "mu11", w), field<double>(r, "mu02", w));
    });
  }
  if (o.contains("outline")) { // optional: the edge measured on the template image
    const json &e = o["outline"];
    if (!e.is_object())
      throw ioError("vpMorphDatabase: " + where + ": \"outline\" must be an object {x, y}");
    const std::string w = where + " \"outline\"";
    asFileError(w, [&] {
      c.setOutline(
          vpMorphContour(field<std::vector<double>>(e, "x", w), field<std::vector<double>>(e, "y", w), c.units()));
    });
  }
  return c;
}

bool isImageFile(const fs::path &p)
{
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".pgm" || e == ".ppm" || e == ".bmp" || e == ".tif" ||
         e == ".tiff";
}
} // namespace

vpMorphDatabase::vpMorphDatabase(const vpMorphShapeDistance &distance) : m_distance(distance), m_threshold(kInf)
{
  if (distance.model() == vpMorphShapeDistance::RIGID)
    m_minSupport = kRigidSupport;
}

bool vpMorphDatabase::rigidAccepted(const vpMorphRigidCheck::Result &r) const
{
  return r.fitted && r.targetShare >= m_minSupport && r.outsideShare <= maximumOutside();
}

std::vector<vpMorphRigidSearch::View> vpMorphDatabase::rigidViews(bool poses, std::size_t skip) const
{
  std::vector<vpMorphRigidSearch::View> views;
  for (std::size_t k = 0; k < m_templates.size(); ++k) {
    if (k == skip)
      continue;
    views.push_back(vpMorphRigidSearch::View{k, vpMorphRecognition::npos, &m_shapes[k].rigid[0]});
    for (std::size_t p = 0; poses && p < m_poses[k].size(); ++p)
      views.push_back(vpMorphRigidSearch::View{k, p, &m_poses[k][p].shape.rigid[0]});
  }
  return views;
}

vpMorphRigidCheck::Result vpMorphDatabase::rigidCheck(const vpMorphShapeDistance::Shape &q, std::size_t k,
                                                      bool mirrored, bool poses) const
{
  std::vector<vpMorphRigidSearch::View> views;
  views.push_back(vpMorphRigidSearch::View{k, vpMorphRecognition::npos, &m_shapes[k].rigid[0]});
  for (std::size_t p = 0; poses && p < m_poses[k].size(); ++p)
    views.push_back(vpMorphRigidSearch::View{k, p, &m_poses[k][p].shape.rigid[0]});
  vpMorphRigidCheck::Result best;
  for (std::size_t m = 0; m < (mirrored ? q.rigid.size() : 1); ++m) {
    const vpMorphRigidSearch::Outcome o = vpMorphRigidSearch::run(q.rigid[m], views, 1);
    if (m == 0 || o.best.cost < best.cost)
      best = o.best;
  }
  return best;
}

vpMorphRecognition vpMorphDatabase::rigidSearch(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q,
                                                bool prune, vpMorphMatcher &matcher, bool poses) const
{
  const std::vector<vpMorphRigidSearch::View> views = rigidViews(poses);
  vpMorphRecognition r;
  // The view as it is, then (mirrors on) its mirror image when that is not accepted: a part turned over.
  for (std::size_t m = 0; m < q.rigid.size(); ++m) {
    const vpMorphRigidSearch::Outcome o = vpMorphRigidSearch::run(q.rigid[m], views, prune ? rigidShortlist() : 0);
    vpMorphRecognition a;
    a.index = o.index;
    a.distance = o.best.cost;
    a.secondIndex = o.second;
    a.secondDistance = o.second == vpMorphRecognition::npos ? kInf : o.runnerUp.cost;
    a.margin = o.second == vpMorphRecognition::npos
                   ? 1.0
                   : (a.secondDistance > 0.0 ? (a.secondDistance - a.distance) / a.secondDistance : 0.0);
    a.threshold = threshold(a.index);
    a.support = o.best.targetShare;
    a.mirrored = m == 1;
    a.articulation = o.pose == vpMorphRecognition::npos ? 0.0 : m_poses[a.index][o.pose].angle;
    a.evaluated = o.compared;
    // Two templates that both explain the view within the cost's noise: no telling which.
    const bool ambiguous = o.second != vpMorphRecognition::npos && rigidAccepted(o.runnerUp) &&
                           o.runnerUp.cost - o.best.cost < ambiguity();
    a.accepted = rigidAccepted(o.best) && !ambiguous;
    if (m == 0 || a.accepted) {
      r = a;
      r.correspondence = matcher.match(c, templateView(r.index, o.pose));
    }
    if (r.accepted)
      break;
  }
  return r;
}

void vpMorphDatabase::invalidate()
{
  m_calibrated = false;
  m_within.clear();
  m_between.clear();
}

double vpMorphDatabase::threshold(std::size_t k) const
{
  (void)operator[](k);
  if (m_manual)
    return m_threshold;
  return m_calibrated && k < m_within.size() ? calibrationSlack() * m_within[k] : kInf;
}

void vpMorphDatabase::clearThreshold()
{
  m_manual = false;
  m_threshold = kInf;
}

void vpMorphDatabase::add(const vpMorphTemplate &t)
{
  if (t.contour().empty() || t.name().empty())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::add: a template needs a name and a contour");
  if (find(t.name()) != vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::add: duplicate template name '" + t.name() + "'");
  m_shapes.push_back(m_distance.prepare(t.contour()));
  m_poses.push_back(poses(t));
  m_templates.push_back(t);
  invalidate();
}

void vpMorphDatabase::remove(const std::string &name)
{
  const std::size_t k = find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase: no template named '" + name + "'");
  m_templates.erase(m_templates.begin() + static_cast<long>(k));
  m_shapes.erase(m_shapes.begin() + static_cast<long>(k));
  m_poses.erase(m_poses.begin() + static_cast<long>(k));
  invalidate();
}

const vpMorphTemplate &vpMorphDatabase::operator[](std::size_t k) const
{
  if (k >= m_templates.size()) {
    std::ostringstream os;
    os << "vpMorphDatabase: template index " << k << " out of range (" << m_templates.size() << " templates)";
    throw vpMorphException(vpMorphException::notFoundError, os.str());
  }
  return m_templates[k];
}

const vpMorphTemplate &vpMorphDatabase::operator[](const std::string &name) const
{
  const std::size_t k = find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase: no template named '" + name + "'");
  return m_templates[k];
}

std::size_t vpMorphDatabase::find(const std::string &name) const
{
  for (std::size_t k = 0; k < m_templates.size(); ++k)
    if (m_templates[k].name() == name)
      return k;
  return vpMorphRecognition::npos;
}

std::vector<vpMorphDatabase::Pose> vpMorphDatabase::poses(const vpMorphTemplate &t) const
{
  std::vector<Pose> out;
  if (!t.isArticulated())
    return out;
  const vpMorphArticulation &a = t.articulation();
  // Every kPoseStep from the taught opening (0) both ways, the range's ends included: a view lies within half a
  // step of a pose.
  std::vector<double> angles;
  for (double x = -kPoseStep; x > a.minAngle(); x -= kPoseStep)
    angles.push_back(x);
  angles.push_back(a.minAngle());
  for (double x = kPoseStep; x < a.maxAngle(); x += kPoseStep)
    angles.push_back(x);
  angles.push_back(a.maxAngle());
  for (double x : angles)
    if (x != 0.0) {
      vpMorphContour c = a.pose(x);
      vpMorphShapeDistance::Shape q = m_distance.prepare(c);
      out.push_back(Pose{x, std::move(c), std::move(q)});
    }
  return out;
}

double vpMorphDatabase::templateDistance(const vpMorphShapeDistance::Shape &q, std::size_t k, vpMorphMatcher &matcher,
                                         double abandonAbove, bool *mirrored, bool poses) const
{
  bool mir = false;
  double best = m_distance.distance(q, m_shapes[k], matcher, abandonAbove, &mir);
  if (poses)
    best = poseDistance(q, k, matcher, best, abandonAbove, mir);
  if (mirrored)
    *mirrored = mir;
  return best;
}

double vpMorphDatabase::poseDistance(const vpMorphShapeDistance::Shape &q, std::size_t k, vpMorphMatcher &matcher,
                                     double best, double abandonAbove, bool &mirrored) const
{
  for (std::size_t p = 0; p < m_poses[k].size(); ++p) {
    const double bound = std::isfinite(best) && (abandonAbove < 0.0 || best < abandonAbove) ? best : abandonAbove;
    if (bound >= 0.0 && m_distance.lowerBound(q, m_poses[k][p].shape) > bound)
      continue; // this pose cannot beat the best so far
    bool m = false;
    const double d = m_distance.distance(q, m_poses[k][p].shape, matcher, bound, &m);
    if (d < best) {
      best = d;
      mirrored = m;
    }
  }
  return best;
}

double vpMorphDatabase::templateLowerBound(const vpMorphShapeDistance::Shape &q, std::size_t k, bool poses) const
{
  double b = m_distance.lowerBound(q, m_shapes[k]);
  for (std::size_t p = 0; poses && p < m_poses[k].size(); ++p)
    b = std::min(b, m_distance.lowerBound(q, m_poses[k][p].shape));
  return b;
}

std::size_t vpMorphDatabase::overlapPose(const vpMorphContour &c, std::size_t k, vpMorphMatcher &matcher) const
{
  double best = vpMorphArticulation::fitOverlap(c, m_templates[k].contour(), matcher);
  std::size_t bestPose = vpMorphRecognition::npos;
  for (std::size_t p = 0; p < m_poses[k].size(); ++p) {
    const double o = vpMorphArticulation::fitOverlap(c, m_poses[k][p].contour, matcher);
    if (o > best) {
      best = o;
      bestPose = p;
    }
  }
  return bestPose;
}

const vpMorphContour &vpMorphDatabase::templateView(std::size_t k, std::size_t pose) const
{
  return pose == vpMorphRecognition::npos ? m_templates[k].contour() : m_poses[k][pose].contour;
}

void vpMorphDatabase::setArticulation(const std::string &name, const vpMorphArticulation &a)
{
  const std::size_t k = find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase: no template named '" + name + "'");
  m_templates[k].setArticulation(a);
  m_poses[k] = poses(m_templates[k]);
}

void vpMorphDatabase::setDistance(const vpMorphShapeDistance &d)
{
  m_distance = d;
  m_minSupport = vpMorphDatabase(d).m_minSupport; // the model's default
  m_shapes.clear();
  for (const vpMorphTemplate &t : m_templates)
    m_shapes.push_back(m_distance.prepare(t.contour()));
  // The poses are drawn from the articulation alone: only their shapes depend on the distance.
  for (std::vector<Pose> &poses : m_poses)
    for (Pose &p : poses)
      p.shape = m_distance.prepare(p.contour);
  invalidate();
}

void vpMorphDatabase::setThreshold(double t)
{
  if (!std::isfinite(t) || t <= 0.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::setThreshold: the threshold must be finite and > 0");
  m_threshold = t;
  m_manual = true;
}

void vpMorphDatabase::setMinimumSupport(double s)
{
  if (!(s > 0.0 && (s <= 1.0 || s == kInf)))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::setMinimumSupport: the support must be in (0, 1] or +inf");
  m_minSupport = s;
}

void vpMorphDatabase::setSupportFloor(double s)
{
  if (!(s >= 0.0 && s <= 1.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::setSupportFloor: the floor must be in [0, 1]");
  m_supportFloor = s;
}

double vpMorphDatabase::support(const vpMorphContour &c, std::size_t k, bool mirrored) const
{
  return support(c, k, mirrored, true);
}

double vpMorphDatabase::support(const vpMorphContour &c, std::size_t k, bool mirrored, bool poses) const
{
  const vpMorphContour &t = operator[](k).contour();
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::support: empty contour");
  if (c.units() != t.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::support: the contour's units are not those of template '" +
                               m_templates[k].name() + "'");
  if (m_distance.model() == vpMorphShapeDistance::RIGID)
    return rigidCheck(m_distance.prepare(c), k, mirrored, poses).targetShare;
  vpMorphMatcher matcher = m_distance.matcher();
  const double taught = shownEitherWay(c, t, matcher, mirrored, matcher.match(c, t));
  if (!poses || m_poses[k].empty())
    return taught;
  // An articulated template: also the pose the view lies on best.
  const vpMorphContour &v = templateView(k, overlapPose(c, k, matcher));
  return std::max(taught, shownEitherWay(c, v, matcher, mirrored, matcher.match(c, v)));
}

bool vpMorphDatabase::accepts(const vpMorphContour &c, std::size_t k, double slack, double *distance) const
{
  if (!std::isfinite(slack) || slack < 1.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::accepts: the slack must be finite and >= 1");
  (void)operator[](k);
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::accepts: empty contour");
  vpMorphMatcher matcher = m_distance.matcher();
  bool mirrored = false;
  const vpMorphShapeDistance::Shape q = m_distance.prepare(c);
  if (m_distance.model() == vpMorphShapeDistance::RIGID) {
    const vpMorphRigidCheck::Result r = rigidCheck(q, k, true, true);
    if (distance)
      *distance = r.cost;
    return r.cost <= slack * threshold(k) || rigidAccepted(r);
  }
  double d = m_distance.distance(q, m_shapes[k], matcher, -1.0, &mirrored);
  if (d > slack * threshold(k)) // an articulated template: its other openings too
    d = poseDistance(q, k, matcher, d, -1.0, mirrored);
  if (distance)
    *distance = d;
  if (d <= slack * threshold(k))
    return true;
  return std::isfinite(m_minSupport) && support(c, k, mirrored) >= m_minSupport;
}

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
  std::vector<double> D(T * T, rigid ? kInf : 0.0); // RIGID fills only each row's nearest other template
  // Jobs 0..T-1: within(t); jobs T..2T-1: row t of the between-template matrix.
  m_distance.parallelFor(
      T + (perRow ? T : 0), threads,
      [&](std::size_t k, vpMorphMatcher &matcher) {
        if (k < T) {
          for (const vpMorphContour &p : perturbations(m_templates[k].contour()))
            within[k] = std::max(within[k], m_distance.distance(m_distance.prepare(p), m_shapes[k], matcher));
        } else if (rigid) {
          // The nearest other template by the two-stage search (the full matrix would take T^2 exact comparisons).
          const std::size_t i = k - T;
          const vpMorphRigidSearch::Outcome o =
              vpMorphRigidSearch::run(m_shapes[i].rigid[0], rigidViews(false, i), rigidShortlist());
          if (o.index != vpMorphRecognition::npos)
            D[i * T + o.index] = o.best.cost;
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
  m_calibrated = true;
}

vpMorphRecognition vpMorphDatabase::search(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                                           vpMorphMatcher &matcher) const
{
  // The taught views first; only a view they leave unaccepted is compared with the articulated templates' other
  // openings too (an opened pliers), so that every other view costs and gets what it did without them.
  const vpMorphRecognition r = search(c, q, prune, matcher, false);
  if (r.accepted || std::all_of(m_poses.begin(), m_poses.end(), [](const std::vector<Pose> &p) { return p.empty(); }))
    return r;
  const vpMorphRecognition a = search(c, q, prune, matcher, true);
  return a.accepted ? a : r;
}

vpMorphRecognition vpMorphDatabase::search(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                                           vpMorphMatcher &matcher, bool poses) const
{
  if (m_distance.model() == vpMorphShapeDistance::RIGID)
    return rigidSearch(c, q, prune, matcher, poses);
  const std::size_t T = m_templates.size();
  vpMorphRecognition r;
  // Keeps the two best (distance, index) pairs, ordered lexicographically: ties go to the lower index.
  auto offer = [&r](double d, std::size_t k, bool mirrored) {
    if (d < r.distance || (d == r.distance && k < r.index)) {
      r.secondDistance = r.distance;
      r.secondIndex = r.index;
      r.distance = d;
      r.index = k;
      r.mirrored = mirrored;
    } else if (d < r.secondDistance || (d == r.secondDistance && k < r.secondIndex)) {
      r.secondDistance = d;
      r.secondIndex = k;
    }
  };
  if (!prune) {
    for (std::size_t k = 0; k < T; ++k) {
      bool mir = false;
      const double d = templateDistance(q, k, matcher, -1.0, &mir, poses);
      offer(d, k, mir);
      ++r.evaluated;
    }
  } else {
    std::vector<std::pair<double, std::size_t>> order(T);
    for (std::size_t k = 0; k < T; ++k)
      order[k] = std::make_pair(templateLowerBound(q, k, poses), k);
    std::sort(order.begin(), order.end());
    for (const auto &o : order) {
      // Every later template has a bound at least as large: none of them can enter the top two.
      if (o.first > r.secondDistance)
        break;
      bool mir = false;
      const double d = templateDistance(q, o.second, matcher, std::isfinite(r.secondDistance) ? r.secondDistance : -1.0,
                                        &mir, poses);
      ++r.evaluated;
      if (d <= r.secondDistance)
        offer(d, o.second, mir);
    }
  }
  if (T == 1)
    r.margin = 1.0;
  else
    r.margin = r.secondDistance > 0.0 ? (r.secondDistance - r.distance) / r.secondDistance : 0.0;
  r.threshold = threshold(r.index);
  r.accepted = r.distance <= r.threshold;
  // An articulated template's pose: the one the view lies on best (overlapPose()), not the distance's.
  const std::size_t bestPose =
      !poses || m_poses[r.index].empty() ? vpMorphRecognition::npos : overlapPose(c, r.index, matcher);
  r.articulation = bestPose == vpMorphRecognition::npos ? 0.0 : m_poses[r.index][bestPose].angle;
  r.correspondence = matcher.match(c, templateView(r.index, bestPose));
  if (!std::isfinite(m_minSupport))
    return r;
  // Not through support(), which refuses other units: the similarity fit does not need them equal.
  r.support = shownEitherWay(c, templateView(r.index, bestPose), matcher, r.mirrored, r.correspondence);
  if (r.support >= m_minSupport) {
    r.accepted = true;
    return r;
  }
  // The view does not show its nearest template's outline. A notch bitten into an occluded view can cost less work
  // on another tool's outline than on its own: a key under a card was accepted as the wrench, a wedge under one was
  // nearest the screwdriver and rejected, while it shows 0.90 of the wedge's outline. The nearest other templates are
  // aligned on the view too, whatever their distance (a notch put the wedge at 2.3 times its threshold), and the one
  // it shows most replaces the distance's choice if it reaches the minimum. If none does (a deformed view shows no
  // outline whole), the distance's choice stands, accepted by the distance unless the view shows almost nothing of it
  // (an unknown shape). Accepting a template that its own distance accepts and that shows at least the floor, when
  // the distance's choice does not, was tried: it took 50 more MPEG-7 images for the tools (126 of 1400).
  const bool distanceAccepted = r.accepted;
  std::vector<std::pair<double, std::size_t>> others;
  std::vector<bool> mirroredOther(T, false);
  for (std::size_t k = 0; k < T; ++k)
    if (k != r.index) {
      bool mir = false;
      others.emplace_back(m_distance.distance(q, m_shapes[k], matcher, -1.0, &mir), k);
      mirroredOther[k] = mir; // re-ranking is for occluded views: the other templates as taught
    }
  r.evaluated = T;
  std::sort(others.begin(), others.end());
  if (others.size() > rerankCandidates())
    others.resize(rerankCandidates());
  double bestSupport = r.support;
  std::size_t bestIndex = r.index;
  double bestDistance = r.distance;
  for (const auto &o : others) {
    if (m_templates[o.second].contour().units() != c.units())
      continue; // support() refuses them
    const double s = support(c, o.second, mirroredOther[o.second], poses);
    if (s > bestSupport) {
      bestSupport = s;
      bestIndex = o.second;
      bestDistance = o.first;
    }
  }
  if (bestIndex == r.index || !(bestSupport >= m_minSupport)) {
    r.accepted = distanceAccepted && r.support >= m_supportFloor;
    return r;
  }
  r.secondIndex = r.index;
  r.secondDistance = r.distance;
  r.index = bestIndex;
  r.distance = bestDistance;
  r.mirrored = mirroredOther[bestIndex];
  r.support = bestSupport;
  r.accepted = true;
  r.margin = 0.0; // not the distance's choice
  r.threshold = threshold(r.index);
  r.reranked = true;
  r.articulation = 0.0;
  r.correspondence = matcher.match(c, m_templates[r.index].contour());
  return r;
}

vpMorphRecognition vpMorphDatabase::recognize(const vpMorphContour &c, bool prune) const
{
  if (m_templates.empty())
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase::recognize: the database is empty");
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::recognize: empty contour");
  vpMorphMatcher matcher = m_distance.matcher();
  return search(c, m_distance.prepare(c), prune, matcher);
}

std::vector<vpMorphRecognition> vpMorphDatabase::recognizeAll(const std::vector<vpMorphContour> &contours,
                                                              unsigned int threads, const Progress &progress) const
{
  if (m_templates.empty())
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase::recognizeAll: the database is empty");
  std::vector<vpMorphRecognition> out(contours.size());
  m_distance.parallelFor(
      contours.size(), threads,
      [&](std::size_t k, vpMorphMatcher &matcher) {
        if (contours[k].empty())
          throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::recognizeAll: empty contour");
        out[k] = search(contours[k], m_distance.prepare(contours[k]), true, matcher);
      },
      progress);
  return out;
}

vpMorphDatabase vpMorphDatabase::fromImages(const std::string &dir, const vpMorphShapeDistance &distance,
                                            const Progress &progress)
{
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw ioError("vpMorphDatabase::fromImages: '" + dir + "' is not a readable directory");
  std::vector<fs::path> files;
  for (const auto &e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && isImageFile(e.path()))
      files.push_back(e.path());
  if (ec)
    throw ioError("vpMorphDatabase::fromImages: cannot list '" + dir + "': " + ec.message());
  if (files.empty())
    throw ioError("vpMorphDatabase::fromImages: no image (png, jpg, pgm, ppm, bmp, tif) in '" + dir + "'");
  std::sort(files.begin(), files.end(), [](const fs::path &a, const fs::path &b) {
    return a.stem() < b.stem() || (a.stem() == b.stem() && a.filename() < b.filename());
  });
  for (std::size_t k = 1; k < files.size(); ++k)
    if (files[k].stem() == files[k - 1].stem())
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphDatabase::fromImages: two images named '" + files[k].stem().string() + "' (" +
                                 files[k - 1].filename().string() + ", " + files[k].filename().string() + ")");
  std::vector<vpMorphContour> contours(files.size());
  distance.parallelFor(
      files.size(), 0,
      [&](std::size_t k, vpMorphMatcher &) {
        vpImage<unsigned char> I;
        try {
          vpImageIo::read(I, files[k].string());
        } catch (const vpException &e) {
          throw ioError("vpMorphDatabase::fromImages: cannot read image '" + files[k].string() +
                        "': " + e.getStringMessage());
        }
        try {
          contours[k] = vpMorphContourExtractor().extract(I);
        } catch (const vpException &e) {
          throw vpMorphException(vpMorphException::badImageError,
                                 "vpMorphDatabase::fromImages: '" + files[k].string() + "': " + e.getStringMessage());
        }
      },
      progress);
  vpMorphDatabase db(distance);
  for (std::size_t k = 0; k < files.size(); ++k)
    db.add(vpMorphTemplate(files[k].stem().string(), contours[k], files[k].string()));
  db.calibrate(0, progress);
  return db;
}

std::string vpMorphDatabase::toJson() const { return toJson(std::string()); }

std::string vpMorphDatabase::toJson(const std::string &relativeTo) const
{
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  const vpMorphShapeDistance &d = m_distance;
  j["distance"] = {{"model", d.name()},       {"points", d.points()},     {"mirrors", d.mirrors()},
                   {"scales", d.scales()},    {"ks", d.workModel().ks()}, {"kb", d.workModel().kb()},
                   {"cs", d.workModel().cs()}};
  json cal;
  cal["calibrated"] = m_calibrated;
  cal["manual"] = m_manual;
  cal["threshold"] = m_manual ? json(m_threshold) : json(nullptr);
  cal["slack"] = calibrationSlack();
  cal["within"] = finiteOrNull(m_within);
  cal["between"] = finiteOrNull(m_between);
  cal["support"] = std::isfinite(m_minSupport) ? json(m_minSupport) : json(nullptr);
  cal["support_floor"] = m_supportFloor;
  j["calibration"] = cal;
  json ts = json::array();
  for (const vpMorphTemplate &t : m_templates) {
    json o;
    o["name"] = t.name();
    std::string image = t.imagePath();
    if (!image.empty() && !relativeTo.empty()) {
      std::error_code ec;
      const fs::path rel = fs::absolute(image, ec).lexically_normal().lexically_relative(
          fs::absolute(relativeTo, ec).lexically_normal());
      if (!ec && !rel.empty())
        image = rel.generic_string();
    }
    o["image"] = image;
    contourToJson(t.contour(), o);
    if (t.isArticulated()) {
      const vpMorphArticulation &a = t.articulation();
      json parts = json::array();
      for (unsigned int k = 0; k < 2; ++k) {
        json pj;
        contourToJson(a.part(k), pj);
        parts.push_back(pj);
      }
      o["articulation"] = {
          {"parts", parts}, {"pivot", {a.pivot().get_u(), a.pivot().get_v()}}, {"range", {a.minAngle(), a.maxAngle()}}};
    }
    o["cdMo"] = poseToJson(t.cdMo());
    o["metadata"] = t.metadata();
    ts.push_back(o);
  }
  j["templates"] = ts;
  return j.dump(1);
}

void vpMorphDatabase::save(const std::string &path) const
{
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string text = toJson(dir.string());
  // Temporary file in the same directory, so that the rename is atomic (same file system).
  std::ostringstream name;
  name << "." << target.filename().string() << ".tmp-" << std::random_device()();
  const fs::path tmp = dir / name.str();
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f)
      throw ioError("vpMorphDatabase::save: cannot write in '" + dir.string() + "'");
    f << text << "\n";
    f.flush();
    if (!f) {
      f.close();
      std::remove(tmp.string().c_str());
      throw ioError("vpMorphDatabase::save: write error on '" + tmp.string() + "' (disk full?)");
    }
  }
  if (std::rename(tmp.string().c_str(), path.c_str()) != 0) {
    std::remove(tmp.string().c_str());
    throw ioError("vpMorphDatabase::save: cannot rename the temporary file onto '" + path + "'");
  }
}

vpMorphDatabase vpMorphDatabase::load(const std::string &path, bool checkImages)
{
  std::ifstream f(path, std::ios::binary);
  if (!f)
    throw ioError("vpMorphDatabase::load: cannot open '" + path + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  const fs::path p(path);
  try {
    return fromJson(ss.str(), checkImages, p.has_parent_path() ? p.parent_path().string() : std::string("."));
  } catch (const vpMorphException &e) {
    throw vpMorphException(e.getCode(), e.getStringMessage() + " (file '" + path + "')");
  }
}

vpMorphDatabase vpMorphDatabase::fromJson(const std::string &text, bool checkImages, const std::string &baseDir)
{
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception &e) {
    // parse_error, and also out_of_range for a number beyond double (1e400): both are a malformed file.
    throw ioError(std::string("vpMorphDatabase: not valid JSON (malformed or truncated file): ") + e.what());
  }
  if (!j.is_object())
    throw ioError("vpMorphDatabase: the file is not a JSON object");
  if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != kFormat)
    throw ioError(std::string("vpMorphDatabase: not a template database (\"format\" must be \"") + kFormat + "\")");
  if (!j.contains("version") || !j["version"].is_number_integer())
    throw ioError("vpMorphDatabase: missing or non-integer \"version\"");
  const int version = j["version"].get<int>();
  if (version != kVersion) {
    std::ostringstream os;
    os << "vpMorphDatabase: unsupported version " << version << " (this build reads version " << kVersion << ")";
    throw ioError(os.str());
  }
  const json dj = j.contains("distance") ? j["distance"] : json();
  vpMorphShapeDistance d = vpMorphShapeDistance::fromName(field<std::string>(dj, "model", "\"distance\""));
  try {
    d.setWorkModel(vpMorphWorkModel(field<double>(dj, "ks", "\"distance\""), field<double>(dj, "kb", "\"distance\""),
                                    field<double>(dj, "cs", "\"distance\"")));
    if (d.model() != vpMorphShapeDistance::POLYGON) {
      d.setPoints(field<std::size_t>(dj, "points", "\"distance\""));
      d.setScales(field<std::vector<double>>(dj, "scales", "\"distance\""));
    }
    d.setMirrors(field<bool>(dj, "mirrors", "\"distance\""));
  } catch (const vpMorphException &e) {
    if (e.getCode() == vpMorphException::ioError)
      throw;
    throw ioError("vpMorphDatabase: invalid \"distance\": " + e.getStringMessage());
  }
  vpMorphDatabase db(d);
  if (!j.contains("templates") || !j["templates"].is_array())
    throw ioError("vpMorphDatabase: no \"templates\" array");
  std::size_t k = 0;
  for (const json &o : j["templates"]) {
    std::ostringstream where;
    where << "template " << k++;
    const std::string name = field<std::string>(o, "name", where.str());
    where << " ('" << name << "')";
    const vpMorphContour c = contourFromJson(o, where.str());
    const std::vector<double> m = field<std::vector<double>>(o, "cdMo", where.str());
    if (m.size() != 16)
      throw ioError("vpMorphDatabase: " + where.str() + ": \"cdMo\" needs 16 numbers (row-major 4x4)");
    vpHomogeneousMatrix M;
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int cc = 0; cc < 4; ++cc)
        M[r][cc] = m[4 * r + cc];
    std::string image = o.contains("image") ? field<std::string>(o, "image", where.str()) : std::string();
    if (!image.empty() && fs::path(image).is_relative() && !baseDir.empty()) {
      std::error_code ec;
      image = (fs::absolute(baseDir, ec) / image).lexically_normal().string();
    }
    if (checkImages && !image.empty()) {
      std::error_code ec;
      if (!fs::exists(image, ec))
        throw ioError("vpMorphDatabase: " + where.str() + ": image '" + image + "' not found");
    }
    vpMorphTemplate t(name, c, image, M);
    if (o.contains("articulation")) { // optional: two parts about a pin
      const json &a = o["articulation"];
      const std::string w = where.str() + " \"articulation\"";
      if (!a.is_object() || !a.contains("parts") || !a["parts"].is_array() || a["parts"].size() != 2)
        throw ioError("vpMorphDatabase: " + w + " must be an object {parts: [2 contours], pivot, range}");
      const std::vector<double> pivot = field<std::vector<double>>(a, "pivot", w);
      const std::vector<double> range = field<std::vector<double>>(a, "range", w);
      if (pivot.size() != 2 || range.size() != 2)
        throw ioError("vpMorphDatabase: " + w + ": \"pivot\" is (u, v) and \"range\" (min, max) radians");
      asFileError(w, [&] {
        t.setArticulation(vpMorphArticulation(contourFromJson(a["parts"][0], w + " part 0"),
                                              contourFromJson(a["parts"][1], w + " part 1"),
                                              vpImagePoint(pivot[1], pivot[0]), range[0], range[1]));
      });
    }
    if (o.contains("metadata"))
      t.setMetadata(field<std::map<std::string, std::string>>(o, "metadata", where.str()));
    if (db.find(name) != vpMorphRecognition::npos)
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphDatabase: duplicate template name '" + name + "'");
    db.add(t);
  }
  if (j.contains("calibration")) {
    const json &cal = j["calibration"];
    const std::string w = "\"calibration\"";
    const bool calibrated = field<bool>(cal, "calibrated", w);
    const bool manual = field<bool>(cal, "manual", w);
    const json &th = cal.contains("threshold") ? cal["threshold"] : json();
    if (!th.is_null() && !(th.is_number() && th.get<double>() > 0.0))
      throw ioError("vpMorphDatabase: \"calibration\": threshold must be a positive number or null");
    if (manual && th.is_null())
      throw ioError("vpMorphDatabase: \"calibration\": a manual threshold needs a value");
    db.m_within = numbersOrInf(cal, "within");
    db.m_between = numbersOrInf(cal, "between");
    if (calibrated && (db.m_within.size() != db.size() || db.m_between.size() != db.size()))
      throw ioError("vpMorphDatabase: \"calibration\" does not match the number of templates");
    db.m_calibrated = calibrated;
    db.m_manual = manual;
    db.m_threshold = manual ? th.get<double>() : kInf;
    if (cal.contains("support")) { // absent from the files written before it existed: the default
      const json &su = cal["support"];
      if (!su.is_null() && !(su.is_number() && su.get<double>() > 0.0 && su.get<double>() <= 1.0))
        throw ioError("vpMorphDatabase: \"calibration\": support must be a number in (0, 1] or null");
      db.m_minSupport = su.is_null() ? kInf : su.get<double>();
    }
    if (cal.contains("support_floor")) { // idem
      const json &fl = cal["support_floor"];
      if (!(fl.is_number() && fl.get<double>() >= 0.0 && fl.get<double>() <= 1.0))
        throw ioError("vpMorphDatabase: \"calibration\": support_floor must be a number in [0, 1]");
      db.m_supportFloor = fl.get<double>();
    }
  }
  return db;
}
