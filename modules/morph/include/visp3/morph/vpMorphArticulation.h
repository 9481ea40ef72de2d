/*!
  \file vpMorphArticulation.h
  \brief Two rigid parts of a template turning about one pin (pliers, scissors): the template's view at any opening.
*/
#ifndef VP_MORPH_ARTICULATION_H
#define VP_MORPH_ARTICULATION_H

#include <visp3/core/vpImagePoint.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphMatcher.h>

/*!
  \class vpMorphArticulation
  \ingroup group_morph
  \brief The two rigid parts of a template's view and the pin they turn about (value type, PIXEL units).

  An opened pliers is no rigid placement of its closed template. Knowing each arm's own outline in the taught view
  and the pin, the template can be posed at the opening the camera sees (pose()), and the view is then a similarity
  of that pose: recognition and rigid alignment apply unchanged.

  The opening is the turn of part 1 relative to part 0 from the taught view, in radians (counter-clockwise in the
  (x, y) axes), within [minAngle(), maxAngle()]. Which part stays where the template has it is the caller's choice
  (\e fixedPart): with the pin at the same place, the two choices lay the view on the template by one arm or the
  other, and for a symmetric tool no image tells which is meant.

  \code
  vpMorphArticulation a(arm0, arm1, vpImagePoint(240, 320), vpMath::rad(-8), vpMath::rad(60)); // each arm alone
  double opening = a.estimate(view);               // radians, within the range
  vpMorphContour goal = a.poseFor(view, opening);  // the template posed as the view shows it
  \endcode
  \sa vpMorphTemplate::setArticulation(), vpMorphJointFile, \ref page_design_recognition
*/
class vpMorphArticulation
{
public:
  vpMorphArticulation() = default;
  /*!
    \param part0, part1 the outlines of the two parts in the taught view (PIXEL units; their measured edge outlines
    are used when they have them), each whole, as if the other were not there.
    \param pivot the pin in the taught view (u, v).
    \param minAngle, maxAngle the range of the opening (radians, minAngle <= 0 <= maxAngle, less than a half turn
    either way).
    \throw vpMorphException::badParameterError on an empty part, a part not in pixels, a non-finite pivot or a bad
    range.
  */
  vpMorphArticulation(const vpMorphContour &part0, const vpMorphContour &part1, const vpImagePoint &pivot,
                      double minAngle, double maxAngle);

  //! True for a default-constructed articulation (a rigid template).
  bool empty() const { return m_parts[0].empty(); }
  //! Part \e k (0 or 1) as taught. \throw vpMorphException::badParameterError when k > 1.
  const vpMorphContour &part(unsigned int k) const;
  //! The pin in the taught view (u, v), pixels.
  const vpImagePoint &pivot() const { return m_pivot; }
  //! The least opening (radians, <= 0).
  double minAngle() const { return m_min; }
  //! The largest opening (radians, >= 0).
  double maxAngle() const { return m_max; }

  /*!
    The template's view at opening \e angle: part \e fixedPart where the taught view has it, the other turned about
    the pin, their union drawn (each pixel grey by the share of it covered, from 8 x 8 sub-pixels) and extracted by
    vpMorphContourExtractor, so that the result carries a measured region and edge outline as a camera's view does.
    \throw vpMorphException::badParameterError on an empty articulation, an angle out of the range or fixedPart > 1.
  */
  vpMorphContour pose(double angle, unsigned int fixedPart = 0) const;

  /*!
    The opening at which \e view lies best on the template: the largest fitOverlap() with a pose (polygons of the
    pixels the parts cover), every 4 deg over the range and at the peak of the parabola through the best three; then
    each part laid alone on the view's edges (trimmed ICP with scale, three rounds), the turn between the two fits
    correcting the opening. The taught opening (0) is kept unless the estimate lays the view better by more than 0.02
    of intersection over union: an occluded view of the closed tool lies on another opening about as well.
    \e overlap, if given, receives the intersection over union at the result. The overlap, not the morph distance,
    has one clear peak at the opening (\ref page_design_recognition).
    \throw vpMorphException on an empty articulation or view.
  */
  double estimate(const vpMorphContour &view, double *overlap = nullptr) const;
  /*!
    The goal for \e view, seen at \e opening (estimate()): pose() there, with the part that needs the smaller turn
    (of the view's best similarity onto either pose) where the taught view has it; \e fixedPart, if given, receives
    it. vpMorphTemplate::viewFor() estimates the opening and keeps the taught view itself at the taught opening.
    \throw vpMorphException as pose().
  */
  vpMorphContour poseFor(const vpMorphContour &view, double opening, unsigned int *fixedPart = nullptr) const;
  /*!
    How well \e view lies on \e pose up to a similarity: their regions' intersection over union once the view is
    laid on the pose by the robust (Tukey) least-squares similarity of their minimal-work correspondence; 0 when that
    fit collapses the view (an unrelated shape).
  */
  static double fitOverlap(const vpMorphContour &view, const vpMorphContour &pose, vpMorphMatcher &matcher);

private:
  //! pose(); without \e measured, only the polygon of the pixels it covers (a tenth of the cost).
  vpMorphContour draw(double angle, unsigned int fixedPart, bool measured) const;

  vpMorphContour m_parts[2];
  vpImagePoint m_pivot;
  double m_min = 0.0, m_max = 0.0;
};

#endif
