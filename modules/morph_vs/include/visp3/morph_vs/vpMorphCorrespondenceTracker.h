/*!
  \file vpMorphCorrespondenceTracker.h
  \brief Minimal-work correspondence kept from one control iteration to the next.
*/
#ifndef VP_MORPH_CORRESPONDENCE_TRACKER_H
#define VP_MORPH_CORRESPONDENCE_TRACKER_H

#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>
#include <visp3/morph/vpMorphMatcher.h>

/*!
  \class vpMorphCorrespondenceTracker
  \ingroup group_morph_vs
  \brief Runs the correspondence between the current contour and a target once per control iteration,
  tracked from the previous iteration when that is reliable (vpMorphMatcher::matchWindow), with a full
  cyclic search (vpMorphMatcher::match) otherwise.

  Why tracking: between two iterations the best starting pair moves by a vertex or two, and a window of starts
  around the previous one is exact in that window and much cheaper than the full search.

  <b>Start of the window.</b> The previous starting input vertex is carried to the new contour as the vertex
  nearest to its previous position moved by the centroid displacement (the contour's numbering may change
  from frame to frame); the window is centred on the previous starting target vertex.

  <b>Reliability test</b> (a tracked result is kept only if all hold; otherwise match() runs):
  - the target has the same vertices as at the previous call (a new sub-goal always gets a full search);
  - the best start is strictly inside the window (on its edge the optimum may lie outside it);
  - no distance jump: work <= jumpFactor() * previous work + workFloor().

  A window that fails the jump test only (its best start inside it) is confirmed by the least work over all starts
  (vpMorphMatcher::match) when that is no lower: a real contour that gains or loses a vertex from one image to the
  next changes its work many times over while the window still holds the best start. Then the region check is not
  repeated: the tracked correspondence passed it (unless the last region check replaced the least work, after which
  every rejected window gets the full search with the check).

  <b>Region check</b> (on by default): a full search is vpMorphMatcher::matchOnRegions(), so a deformed view
  whose minimal work lies half a turn round (a sagging wedge) is matched the way its region lies on the target's.
  The margin of such a correspondence is the intersection over union it won by.

  After each full search the <b>margin</b> is measured: the relative gap (D_alt - D) / D_alt in [0, 1] between
  the best work D and the best work D_alt of the starts more than n/8 target vertices away from the best
  one (n the target size). A margin near 0 means two different alignments of the contour are almost equally
  good (a symmetric object): the correspondence, hence the rotation, is ambiguous.

  \code
  vpMorphCorrespondenceTracker tracker;
  for (;;) {                                              // one call per control iteration
    const vpMorphCorrespondence &c = tracker.update(vpMorphContourExtractor().extract(I), target);
    if (tracker.margin() < 0.05) { }                      // ambiguous (a symmetric object)
  }
  \endcode
  \sa vpMorphMatcher::matchWindow(), \ref page_design_servo
*/
class vpMorphCorrespondenceTracker
{
public:
  //! Where the last correspondence came from.
  enum Source {
    NONE,   //!< No correspondence yet.
    FULL,   //!< Full cyclic search (first frame, new target, or the tracked one was unreliable).
    TRACKED //!< Windowed search around the previous start.
  };

  //! A tracker running \e matcher (copied).
  explicit vpMorphCorrespondenceTracker(const vpMorphMatcher &matcher = vpMorphMatcher());

  /*!
    Correspondence from \e current (input) to \e target, tracked when reliable (see the class description).
    \throw vpMorphException on empty contours or different units.
  */
  const vpMorphCorrespondence &update(const vpMorphContour &current, const vpMorphContour &target);
  //! Forgets the previous correspondence: the next update() runs a full search.
  void reset();

  //! The last correspondence.
  const vpMorphCorrespondence &correspondence() const { return m_corr; }
  //! Where the last correspondence came from.
  Source lastSource() const { return m_source; }
  //! Work of the last correspondence.
  double work() const { return m_corr.work(); }
  //! Work of the correspondence before the last one (0 if none).
  double previousWork() const { return m_prevWork; }
  //! Margin measured at the last full search (1 if never measured; see the class description).
  double margin() const { return m_margin; }
  //! Number of full searches run.
  unsigned int fullMatchCount() const { return m_fullCount; }
  //! Number of tracked results kept.
  unsigned int trackedMatchCount() const { return m_trackedCount; }
  //! Number of tracked results rejected by the reliability test.
  unsigned int rejectedTrackCount() const { return m_rejectedCount; }
  //! Number of rejected windows (a jump only) that the least work over all starts confirmed (see the class
  //! description); they are counted as full searches too.
  unsigned int confirmedJumpCount() const { return m_confirmedJumps; }

  //! The jump test's factor.
  double jumpFactor() const { return m_jumpFactor; }
  //! Tracked work above jumpFactor * previous work + workFloor is a jump (default 1.5, >= 1).
  void setJumpFactor(double f);
  //! The jump test's absolute slack.
  double workFloor() const { return m_workFloor; }
  //! Absolute slack of the jump test (default 1e-3, >= 0), so that near-zero works do not trigger it.
  void setWorkFloor(double w);
  //! Whether full searches are checked against the regions.
  bool regionCheck() const { return m_regionCheck; }
  //! Full searches checked against the regions' overlap (default true, see the class description).
  void setRegionCheck(bool on) { m_regionCheck = on; }
  //! Number of full searches whose minimal-work correspondence the region check replaced.
  unsigned int regionOverrideCount() const { return m_regionOverrides; }
  //! Half width of the tracking window in target vertices (0: automatic, max(2, n / 8)).
  void setWindowHalfWidth(std::size_t h) { m_halfWidth = h; }
  //! The matcher, to configure it.
  vpMorphMatcher &matcher() { return m_matcher; }

private:
  std::size_t carriedStart(const vpMorphContour &current) const;
  void measureMargin(const vpMorphContour &current, const vpMorphContour &target);

  vpMorphMatcher m_matcher;
  vpMorphCorrespondence m_corr;
  vpMorphContour m_prevInput;
  std::vector<double> m_prevTargetX, m_prevTargetY;
  Source m_source = NONE;
  double m_prevWork = 0.0, m_margin = 1.0;
  double m_jumpFactor = 1.5, m_workFloor = 1e-3;
  std::size_t m_halfWidth = 0;
  bool m_regionCheck = true;
  unsigned int m_regionOverrides = 0;
  bool m_lastOverride = false; // the last full search's region check replaced the least-work correspondence
  unsigned int m_confirmedJumps = 0;
  unsigned int m_fullCount = 0, m_trackedCount = 0, m_rejectedCount = 0;
};

#endif
