#include <visp3/morph/vpMorphDatabase.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidShape.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphOutlineShare.h"

// The database's templates, the D_morph distances' search and the support of a view (vpMorphDatabaseRigid.cpp: the
// RIGID search; vpMorphDatabaseCalibration.cpp: calibrate(); vpMorphDatabaseFile.cpp: files and image folders).

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPoseStep = 3.14159265358979323846 / 45.0; // 4 deg between an articulated template's poses
constexpr double kRigidSupport = 0.5;                       // RIGID's minimum support (class description)

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
  \e share, q's share of t's outline from the correspondence, or where it is less than \e enough the share from the
  alignment of q's outline shape (\e view, built on first use) on t's (\e shape) if that shows at least \e enough. An
  occluder's notch throws the correspondence off (it is matched somewhere), not the shapes' alignment, voted by the
  parts of the outline that show. Below \e enough the correspondence's share stands: the best of more alignments
  shows more of any template, and the floor that rejects unknown shapes holds for one.
*/
double orAligned(double share, double enough, const vpMorphContour &q, const vpMorphContour &t, vpMorphRigidShape &view,
                 const vpMorphRigidShape &shape)
{
  if (share >= enough)
    return share;
  if (view.empty())
    view = vpMorphRigidShape(q);
  const vpMorphOutlineShare shown(t);
  const vpMorphRigidShape::Alignment a = view.alignOn(shape, false);
  double aligned = shown.aligned(q, a.transform);
  if (a.hasAlternative)
    aligned = std::max(aligned, shown.aligned(q, a.alternative));
  return aligned >= enough ? aligned : share;
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
} // namespace

vpMorphDatabase::vpMorphDatabase(const vpMorphShapeDistance &distance) : m_distance(distance), m_threshold(kInf)
{
  if (distance.model() == vpMorphShapeDistance::RIGID)
    m_minSupport = kRigidSupport;
}
void vpMorphDatabase::invalidate()
{
  m_calibrated = false;
  m_within.clear();
  m_between.clear();
  m_lookAlikes.clear();
}

const std::vector<vpMorphDatabase::LookAlike> &vpMorphDatabase::lookAlikes(std::size_t k) const
{
  static const std::vector<LookAlike> none;
  (void)operator[](k);
  return k < m_lookAlikes.size() ? m_lookAlikes[k] : none;
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
  pushShapes(t.contour());
  m_poses.push_back(poses(t));
  m_templates.push_back(t);
  invalidate();
}

void vpMorphDatabase::pushShapes(const vpMorphContour &c)
{
  m_shapes.push_back(m_distance.prepare(c, false));
  m_outlineShapes.push_back(m_shapes.back().rigid.empty() ? vpMorphRigidShape(c) : vpMorphRigidShape());
}

void vpMorphDatabase::remove(const std::string &name)
{
  const std::size_t k = find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphDatabase: no template named '" + name + "'");
  m_templates.erase(m_templates.begin() + static_cast<long>(k));
  m_shapes.erase(m_shapes.begin() + static_cast<long>(k));
  m_outlineShapes.erase(m_outlineShapes.begin() + static_cast<long>(k));
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
      vpMorphShapeDistance::Shape q = m_distance.prepare(c, false);
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
  m_outlineShapes.clear();
  for (const vpMorphTemplate &t : m_templates)
    pushShapes(t.contour());
  // The poses are drawn from the articulation alone: only their shapes depend on the distance.
  for (std::vector<Pose> &poses : m_poses)
    for (Pose &p : poses)
      p.shape = m_distance.prepare(p.contour, false);
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
  vpMorphRigidShape view;
  return support(c, k, mirrored, poses, view);
}

double vpMorphDatabase::support(const vpMorphContour &c, std::size_t k, bool mirrored, bool poses,
                                vpMorphRigidShape &view) const
{
  const vpMorphContour &t = operator[](k).contour();
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::support: empty contour");
  if (c.units() != t.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphDatabase::support: the contour's units are not those of template '" +
                               m_templates[k].name() + "'");
  if (m_distance.model() == vpMorphShapeDistance::RIGID)
    return rigidCheck(m_distance.prepare(c, false), k, mirrored, poses).targetShare;
  vpMorphMatcher matcher = m_distance.matcher();
  const double taught = orAligned(shownEitherWay(c, t, matcher, mirrored, matcher.match(c, t)), m_minSupport, c, t,
                                  view, outlineShape(k));
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
  // From here the candidates, the distance's choice included, are also aligned by their outline shapes (orAligned()):
  // that lays a look-alike well too, so it only compares candidates, never accepts the distance's choice unseen.
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
  // The nearest by the distance, and those the view's outline shape aligns on at least cost (vpMorphRigidShape): the
  // notch an occluder bites costs work, and can rank the view's own template far down, where the shapes' alignment is
  // voted by the parts of the outline that show.
  vpMorphRigidShape view(c);
  std::vector<std::pair<double, std::size_t>> aligned;
  for (const auto &o : others)
    aligned.emplace_back(view.alignOn(outlineShape(o.second), false).cost, o.second);
  const std::size_t R = std::min(rerankCandidates(), others.size());
  std::partial_sort(aligned.begin(), aligned.begin() + static_cast<long>(R), aligned.end());
  std::sort(others.begin(), others.end());
  std::vector<std::pair<double, std::size_t>> candidates(others.begin(), others.begin() + static_cast<long>(R));
  for (std::size_t i = 0; i < R; ++i) {
    const auto same = [&](const std::pair<double, std::size_t> &o) { return o.second == aligned[i].second; };
    if (std::none_of(candidates.begin(), candidates.end(), same))
      candidates.push_back(*std::find_if(others.begin(), others.end(), same));
  }
  double bestSupport =
      bestPose != vpMorphRecognition::npos
          ? r.support
          : orAligned(r.support, m_minSupport, c, templateView(r.index, bestPose), view, outlineShape(r.index));
  std::size_t bestIndex = r.index;
  double bestDistance = r.distance;
  for (const auto &o : candidates) {
    if (m_templates[o.second].contour().units() != c.units())
      continue; // support() refuses them
    const double s = support(c, o.second, mirroredOther[o.second], poses, view);
    if (s > bestSupport) {
      bestSupport = s;
      bestIndex = o.second;
      bestDistance = o.first;
    }
  }
  if (!(bestSupport >= m_minSupport)) {
    r.accepted = distanceAccepted && r.support >= m_supportFloor;
    return r;
  }
  if (bestIndex == r.index) {
    r.support = bestSupport;
    r.accepted = true;
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
  return search(c, m_distance.prepare(c, false), prune, matcher);
}

vpMorphRecognition vpMorphDatabase::recognize(const std::vector<vpMorphContour> &candidates, std::size_t &chosen) const
{
  if (candidates.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphDatabase::recognize: no candidate contour");
  vpMorphRecognition best;
  chosen = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    vpMorphRecognition r = recognize(candidates[k]);
    if (k == 0 || (r.accepted && (!best.accepted || r.relativeDistance() < best.relativeDistance()))) {
      best = std::move(r);
      chosen = k;
    }
  }
  return best;
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
        out[k] = search(contours[k], m_distance.prepare(contours[k], false), true, matcher);
      },
      progress);
  return out;
}
