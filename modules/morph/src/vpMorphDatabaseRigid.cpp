#include <visp3/morph/vpMorphDatabase.h>

#include <limits>

#include "vpMorphRigidSearch.h"

// vpMorphDatabase with the RIGID distance: the two-stage search and the comparison with one template.

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
} // namespace

bool vpMorphDatabase::rigidFits(const vpMorphRigidCheck::Result &r) const
{
  return r.fitted && r.targetShare >= m_minSupport && r.outsideShare <= maximumOutside();
}

bool vpMorphDatabase::rigidAccepted(const vpMorphRigidCheck::Result &r) const
{
  // The same majority both ways: the view shows at least minimumSupport() of the template's outline, and the template
  // explains as much of the view's outline (an occluder's edge aside: it only hides).
  return rigidFits(r) && r.absentShare <= maximumOutside() && r.unexplainedShare <= 1.0 - m_minSupport;
}

const vpMorphRigidShape &vpMorphDatabase::rigidView(std::size_t k, std::size_t pose) const
{
  return pose == vpMorphRecognition::npos ? m_shapes[k].rigid[0] : m_poses[k][pose].shape.rigid[0];
}

std::vector<vpMorphRigidSearch::View> vpMorphDatabase::rigidViews(bool poses, std::size_t skip) const
{
  std::vector<vpMorphRigidSearch::View> views;
  for (std::size_t k = 0; k < m_templates.size(); ++k) {
    if (k == skip)
      continue;
    views.push_back(vpMorphRigidSearch::View{k, vpMorphRecognition::npos, &rigidView(k, vpMorphRecognition::npos)});
    for (std::size_t p = 0; poses && p < m_poses[k].size(); ++p)
      views.push_back(vpMorphRigidSearch::View{k, p, &rigidView(k, p)});
  }
  return views;
}

vpMorphRigidCheck::Result vpMorphDatabase::rigidCheck(const vpMorphShapeDistance::Shape &q, std::size_t k,
                                                      bool mirrored, bool poses) const
{
  std::vector<vpMorphRigidSearch::View> views;
  views.push_back(vpMorphRigidSearch::View{k, vpMorphRecognition::npos, &rigidView(k, vpMorphRecognition::npos)});
  for (std::size_t p = 0; poses && p < m_poses[k].size(); ++p)
    views.push_back(vpMorphRigidSearch::View{k, p, &rigidView(k, p)});
  vpMorphRigidCheck::Result best;
  for (std::size_t m = 0; m < (mirrored ? q.forms.size() : 1); ++m) {
    const vpMorphRigidSearch::Outcome o = vpMorphRigidSearch::run(vpMorphShapeDistance::rigidShape(q, m), views, 1);
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
  for (std::size_t m = 0; m < q.forms.size(); ++m) {
    const vpMorphRigidShape view = vpMorphShapeDistance::rigidShape(q, m); // the mirror image's made only when needed
    const vpMorphRigidSearch::Outcome o = vpMorphRigidSearch::run(
        view, views, prune ? rigidShortlist() : 0, m_lookAlikes.empty() ? nullptr : &m_lookAlikes,
        [this](const vpMorphRigidCheck::Result &b) { return rigidFits(b); });
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
    // Two acceptable templates that the view's outline does not tell apart: no telling which. Weighed only when the
    // best would be accepted.
    const bool acceptable = rigidAccepted(o.best);
    a.ambiguous = acceptable && o.second != vpMorphRecognition::npos && rigidAccepted(o.runnerUp) &&
                  vpMorphRigidCheck::evidence(view, rigidView(o.index, o.pose), o.best,
                                              rigidView(o.second, o.secondPose), o.runnerUp) < ambiguity();
    a.accepted = acceptable && !a.ambiguous;
    if (m == 0 || a.accepted) {
      r = a;
      r.correspondence = matcher.match(c, templateView(r.index, o.pose));
    }
    if (r.accepted)
      break;
  }
  return r;
}
