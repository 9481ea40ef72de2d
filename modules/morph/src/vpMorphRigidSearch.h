/*
  \file vpMorphRigidSearch.h
  \brief Internal to the morph module (not installed): vpMorphDatabase's two-stage search with the RIGID distance.
*/
#ifndef VP_MORPH_RIGID_SEARCH_H
#define VP_MORPH_RIGID_SEARCH_H

#include <cstddef>
#include <functional>
#include <vector>

#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphRigidShape.h>

//! A view of template \e index for vpMorphRigidSearch: its taught view (pose npos) or one of its poses.
struct vpMorphRigidView
{
  std::size_t index, pose;
  const vpMorphRigidShape *shape;
};

/*
  The template a view is, by the RIGID distance, in two stages: every template view is aligned coarsely
  (vpMorphRigidShape::alignOn(), tens of microseconds), and the \e shortlist templates whose coarse cost is least are
  compared exactly (vpMorphRigidCheck, a few hundred microseconds); the least exact cost wins, ties to the lower index.
  A shortlisted template is compared from its alignment, its alternative, and those of its symmetric hypotheses
  (vpMorphRigidShape::Alignment::symmetric) whose coarse cost is within the shortlist's: the rule that admits templates.
  When no answer is then \e acceptable, each shortlisted template gets a second look: of its turns onto itself beyond
  that cost and the whole view's start at its alignment's turn, the one whose fit objective at the start is least,
  when less than the alignment's, is compared too (vpMorphRigidCheck::startCost(), on the outlines: the coarse cost
  cannot rank a toothed part's alike turns, nor a spring's coils).
  Once two are compared, one whose cost is sure to exceed the runner-up's is measured no further (it can be neither).
  With shortlist 0 every template is compared exactly: the exhaustive search that the two stages stand for (a test
  checks they agree). With \e every, every template is compared exactly from its alignment and alternative, and the
  shortlist bounds only the symmetric hypotheses tried (a calibration's search for look-alikes).
  An articulated template has several views (its taught one and its poses): its coarsely best view is the one compared.
  Given \e lookAlikes (per template, vpMorphDatabase::lookAlikes()), the look-alikes of a best that is \e acceptable (a
  taught view) are then compared exactly too, as a shortlisted template is and from the best's fitted start carried
  over by the look-alike's transform (a start at a wrong turn of the best carries the same wrong turn over); and so
  on for a new best. An acceptable answer is then compared with every template a view of it could be taken
  for, whatever the coarse stage ranked.
*/
class vpMorphRigidSearch
{
public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  typedef vpMorphRigidView View;
  typedef std::vector<std::vector<vpMorphDatabase::LookAlike>> LookAlikes;
  typedef std::function<bool(const vpMorphRigidCheck::Result &)> Acceptable;
  //! A template compared exactly: its view and its least cost result.
  struct Exact
  {
    std::size_t index, pose;
    vpMorphRigidCheck::Result result;
  };
  struct Outcome
  {
    std::size_t index = npos, pose = npos;        // the best template and its view
    vpMorphRigidCheck::Result best;               // its exact comparison
    std::size_t second = npos, secondPose = npos; // the runner-up among those compared exactly, and its view
    vpMorphRigidCheck::Result runnerUp;           // its exact comparison
    std::size_t compared = 0;                     // exact comparisons made
    std::vector<Exact> exact;                     // every template compared exactly
  };

  /*!
    \param lookAlikes per template index, or null: none compared beyond the shortlist.
    \param acceptable whether the view lies on a result's template as far as it shows it: only such a best's
    look-alikes are compared, and a best that is not gets the second look (none without \e acceptable).
    \param abandon with a shortlist, measure no further a template that can be neither the best nor the runner-up
    (false: every result in Outcome::exact is measured in full).
    \param every compare every template exactly, the shortlist bounding only the symmetric hypotheses.
  */
  static Outcome run(const vpMorphRigidShape &query, const std::vector<View> &views, std::size_t shortlist,
                     const LookAlikes *lookAlikes = nullptr, const Acceptable &acceptable = Acceptable(),
                     bool abandon = true, bool every = false);
};

#endif
