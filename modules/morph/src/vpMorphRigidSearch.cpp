#include "vpMorphRigidSearch.h"

#include <algorithm>
#include <limits>

#include "vpMorphRigidShapeData.h"

namespace
{
// Asks the cache for what alignOn() reads of \e d (its 16 KB distance grid the most), while the template before it is
// aligned: a thousand templates' data do not stay in the cache from one query to the next.
void prefetch(const vpMorphRigidShapeData &d)
{
#if defined(__GNUC__)
  auto lines = [](const void *p, std::size_t bytes) {
    for (std::size_t o = 0; o < bytes; o += 64)
      __builtin_prefetch(static_cast<const char *>(p) + o);
  };
  lines(d.grid.data(), d.grid.size() * sizeof(float));
  lines(d.x.data(), d.x.size() * sizeof(double));
  lines(d.y.data(), d.y.size() * sizeof(double));
  lines(d.voteX.data(), d.voteX.size() * sizeof(float));
  lines(d.voteY.data(), d.voteY.size() * sizeof(float));
  lines(d.bucketStart.data(), d.bucketStart.size() * sizeof(int));
  lines(d.hist.data(), sizeof(d.hist));
#else
  (void)d;
#endif
}
} // namespace

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
    if (v + 1 < views.size())
      prefetch(*views[v + 1].shape->m_data);
    const vpMorphRigidShape::Alignment a = query.alignOn(*views[v].shape, false);
    if (best.empty() || best.back().index != views[v].index)
      best.push_back(Coarse{a.cost, views[v].index, v, a});
    else if (a.cost < best.back().cost)
      best.back() = Coarse{a.cost, views[v].index, v, a};
  }
  std::stable_sort(best.begin(), best.end(), [](const Coarse &a, const Coarse &b) {
    return a.cost < b.cost || (a.cost == b.cost && a.index < b.index);
  });
  // A template's turns by its symmetries are compared exactly as templates are: those whose coarse cost is within
  // the shortlist's when it left templates out, all of them otherwise.
  double bar = std::numeric_limits<double>::infinity();
  if (shortlist > 0 && best.size() > shortlist) {
    best.resize(shortlist);
    bar = best.back().cost;
  }
  for (Coarse &c : best) {
    query.addSymmetric(*views[c.view].shape, c.alignment);
    std::vector<vpMorphRigidShape::Hypothesis> &h = c.alignment.symmetric;
    h.erase(std::remove_if(h.begin(), h.end(), [bar](const vpMorphRigidShape::Hypothesis &y) { return y.cost > bar; }),
            h.end());
  }
  // Exact stage on the shortlist.
  Outcome o;
  for (const Coarse &c : best) {
    // Once there is a runner-up, a template whose cost exceeds it is neither the best nor the runner-up: its
    // measurement stops there (the exhaustive search measures every one in full, as the reference).
    const double abandonAbove = shortlist > 0 && o.second != npos ? o.runnerUp.cost : -1.0;
    const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(query, *views[c.view].shape, c.alignment, abandonAbove);
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
