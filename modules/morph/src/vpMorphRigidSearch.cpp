#include "vpMorphRigidSearch.h"

#include <algorithm>
#include <limits>

vpMorphRigidSearch::Outcome vpMorphRigidSearch::run(const vpMorphRigidShape &query, const std::vector<View> &views,
                                                    std::size_t shortlist)
{
  // Coarse stage: each template's coarsely best view.
  struct Coarse
  {
    double cost;
    std::size_t index, view;
    vpMorphRigidShape::Alignment alignment;
  };
  std::vector<Coarse> best;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const vpMorphRigidShape::Alignment a = query.alignOn(*views[v].shape);
    if (best.empty() || best.back().index != views[v].index)
      best.push_back(Coarse{a.cost, views[v].index, v, a});
    else if (a.cost < best.back().cost)
      best.back() = Coarse{a.cost, views[v].index, v, a};
  }
  std::stable_sort(best.begin(), best.end(), [](const Coarse &a, const Coarse &b) {
    return a.cost < b.cost || (a.cost == b.cost && a.index < b.index);
  });
  if (shortlist > 0 && best.size() > shortlist)
    best.resize(shortlist);
  // Exact stage on the shortlist.
  Outcome o;
  for (const Coarse &c : best) {
    const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(query, *views[c.view].shape, c.alignment);
    ++o.compared;
    const bool first = o.index == npos || r.cost < o.best.cost || (r.cost == o.best.cost && c.index < o.index);
    if (first) {
      o.second = o.index;
      o.runnerUp = o.best;
      o.index = c.index;
      o.pose = views[c.view].pose;
      o.best = r;
    } else if (o.second == npos || r.cost < o.runnerUp.cost || (r.cost == o.runnerUp.cost && c.index < o.second)) {
      o.second = c.index;
      o.runnerUp = r;
    }
  }
  return o;
}
