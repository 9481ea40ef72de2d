#include "vpMorphRigidSearch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vpMorphRigidShapeData.h"
#include "vpMorphSimilarityFit.h"

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

// The similarity that lays the whole of the input \e in on the target \e t turned by \e theta: centroid on centroid,
// size on size (exact for a view that hides nothing).
vpMorphRigidTransform wholeView(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, double theta)
{
  return vpMorphSimilarityFit::toPixels(in, t, vpMorphSimilarityFit::Sim{std::cos(theta), std::sin(theta), 0.0, 0.0});
}
} // namespace

vpMorphRigidSearch::Outcome vpMorphRigidSearch::run(const vpMorphRigidShape &query, const std::vector<View> &views,
                                                    std::size_t shortlist, const LookAlikes *lookAlikes,
                                                    const Acceptable &acceptable, bool abandon, bool every)
{
  // Coarse stage: each template's coarsely best view.
  struct Coarse
  {
    double cost;
    std::size_t index, view;
    vpMorphRigidShape::Alignment alignment;
    std::vector<vpMorphRigidShape::Hypothesis> beyond; // its turns onto itself beyond the shortlist's cost
  };
  std::vector<Coarse> best;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (v + 1 < views.size())
      prefetch(*views[v + 1].shape->m_data);
    const vpMorphRigidShape::Alignment a = query.alignOn(*views[v].shape, false);
    if (best.empty() || best.back().index != views[v].index)
      best.push_back(Coarse{a.cost, views[v].index, v, a, {}});
    else if (a.cost < best.back().cost)
      best.back() = Coarse{a.cost, views[v].index, v, a, {}};
  }
  std::stable_sort(best.begin(), best.end(), [](const Coarse &a, const Coarse &b) {
    return a.cost < b.cost || (a.cost == b.cost && a.index < b.index);
  });
  // A template's turns by its symmetries are compared exactly as templates are: those whose coarse cost is within
  // the shortlist's when it left templates out, all of them otherwise. Its turns onto itself beyond that are kept
  // aside for a second look.
  const std::size_t listed = shortlist > 0 && best.size() > shortlist ? shortlist : best.size();
  const double bar = listed < best.size() ? best[listed - 1].cost : std::numeric_limits<double>::infinity();
  if (!every)
    best.resize(listed);
  for (Coarse &c : best) {
    query.addSymmetric(*views[c.view].shape, c.alignment);
    std::vector<vpMorphRigidShape::Hypothesis> within;
    for (std::size_t k = 0; k < c.alignment.symmetric.size(); ++k) {
      const vpMorphRigidShape::Hypothesis &y = c.alignment.symmetric[k];
      if (y.cost <= bar)
        within.push_back(y);
      else if (k < c.alignment.selfTurns)
        c.beyond.push_back(y);
    }
    c.alignment.symmetric.swap(within);
  }
  // The exact results, the least per template; the best and the runner-up by cost, ties to the lower index.
  Outcome o;
  auto before = [](const Exact &a, const Exact &b) {
    return a.result.cost < b.result.cost || (a.result.cost == b.result.cost && a.index < b.index);
  };
  auto compare = [&](std::size_t view, const vpMorphRigidShape::Alignment &alignment) {
    // Once there is a runner-up, a template whose cost exceeds it is neither the best nor the runner-up: its
    // measurement stops there (the exhaustive search measures every one in full, as the reference).
    double abandonAbove = -1.0;
    if (abandon && shortlist > 0 && o.exact.size() > 1) {
      std::vector<Exact> two(2);
      std::partial_sort_copy(o.exact.begin(), o.exact.end(), two.begin(), two.end(), before);
      abandonAbove = two[1].result.cost;
    }
    const Exact e{views[view].index, views[view].pose,
                  vpMorphRigidCheck::check(query, *views[view].shape, alignment, abandonAbove)};
    ++o.compared;
    auto same = std::find_if(o.exact.begin(), o.exact.end(), [&e](const Exact &x) { return x.index == e.index; });
    if (same == o.exact.end())
      o.exact.push_back(e);
    else if (e.result.cost < same->result.cost)
      *same = e;
  };
  auto ranked = [&]() {
    std::vector<Exact> two(std::min<std::size_t>(2, o.exact.size()));
    std::partial_sort_copy(o.exact.begin(), o.exact.end(), two.begin(), two.end(), before);
    o.index = two.empty() ? npos : two[0].index;
    o.pose = two.empty() ? npos : two[0].pose;
    o.best = two.empty() ? vpMorphRigidCheck::Result() : two[0].result;
    o.second = two.size() < 2 ? npos : two[1].index;
    o.secondPose = two.size() < 2 ? npos : two[1].pose;
    o.runnerUp = two.size() < 2 ? vpMorphRigidCheck::Result() : two[1].result;
  };
  // Exact stage on the shortlist.
  for (const Coarse &c : best)
    compare(c.view, c.alignment);
  ranked();
  // A second look when no answer is acceptable: of each shortlisted template's starts that the coarse cost cannot
  // rank, the one whose fit objective is least (vpMorphRigidCheck::startCost(), on the outlines), compared when that
  // is less than the alignment's. They are the template's turns onto itself beyond the shortlist's cost (the coarse
  // cost, of outlines smoothed past a tooth's width, ranks a toothed part's alike turns by chance) and the whole
  // view's start at the alignment's turn (alignOn() keeps it or the votes' by their cost after two steps, and a
  // spring's voted start a coil off can cost less there). The sweep's turns are unlike ones, which the coarse cost
  // does rank.
  if (acceptable && !(o.index != npos && acceptable(o.best))) {
    for (const Coarse &c : best) {
      const vpMorphRigidShape &target = *views[c.view].shape;
      std::vector<vpMorphRigidTransform> starts;
      for (const vpMorphRigidShape::Hypothesis &y : c.beyond)
        starts.push_back(y.transform);
      starts.push_back(wholeView(*query.m_data, *target.m_data, c.alignment.transform.theta()));
      const vpMorphRigidTransform *least = nullptr;
      double objective = 0.0;
      for (const vpMorphRigidTransform &start : starts) {
        const double cost = vpMorphRigidCheck::startCost(query, target, start);
        if (!least || cost < objective) {
          least = &start;
          objective = cost;
        }
      }
      if (objective < vpMorphRigidCheck::startCost(query, target, c.alignment.transform)) {
        vpMorphRigidShape::Alignment other;
        other.transform = *least;
        compare(c.view, other);
      }
    }
    ranked();
  }
  // The best's look-alikes, from its fitted start carried over, while the best is acceptable and one whose
  // look-alikes were not compared yet.
  std::vector<std::size_t> visited;
  while (lookAlikes && o.index != npos && o.index < lookAlikes->size() && o.pose == npos && acceptable(o.best) &&
         std::find(visited.begin(), visited.end(), o.index) == visited.end()) {
    visited.push_back(o.index);
    const vpMorphRigidTransform fitted = o.best.start; // the query's pixels to the best's
    for (const vpMorphDatabase::LookAlike &l : (*lookAlikes)[o.index]) {
      const auto v = std::find_if(views.begin(), views.end(),
                                  [&l](const View &x) { return x.index == l.index && x.pose == npos; });
      if (v == views.end())
        continue; // not among the views searched
      // As a shortlisted template is compared, and from the best's fit carried over.
      vpMorphRigidShape::Alignment a = query.alignOn(*v->shape, true);
      const vpMorphRigidTransform carried = l.transform * fitted;
      a.symmetric.push_back(vpMorphRigidShape::Hypothesis{carried, query.cost(*v->shape, carried)});
      compare(static_cast<std::size_t>(v - views.begin()), a);
    }
    ranked();
  }
  return o;
}
