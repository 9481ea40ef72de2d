/*!
  \file vpMorphRecognition.h
  \brief The answer of vpMorphDatabase::recognize(): which template, how sure, and the correspondence.
*/
#ifndef VP_MORPH_RECOGNITION_H
#define VP_MORPH_RECOGNITION_H

#include <cmath>
#include <cstddef>
#include <limits>

#include <visp3/morph/vpMorphCorrespondence.h>

/*!
  \class vpMorphRecognition
  \ingroup group_morph
  \brief Result of a recognition (value type, public fields as it only carries data).

  The best template alone does not say whether the object is known: \e accepted compares its distance with
  the database's threshold (and, for a view the distance rejects, its \e support: an occluded view), and
  \e margin tells how clearly it beat the runner-up, so that a caller can ask for another view when two
  templates are nearly as good.

  \code
  vpMorphRecognition r = db.recognize(vpMorphContourExtractor().extract(I));
  if (r.accepted && r.margin > 0.1)
    std::cout << db[r.index].name() << " at distance " << r.distance << std::endl;
  \endcode
  \sa vpMorphDatabase, \ref page_design_recognition
*/
class vpMorphRecognition
{
public:
  //! No template (an index field that is not set).
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  std::size_t index = npos;                                        //!< the template (the nearest unless reranked)
  double distance = std::numeric_limits<double>::infinity();       //!< its distance (vpMorphShapeDistance)
  std::size_t secondIndex = npos;                                  //!< runner-up (npos with one template)
  double secondDistance = std::numeric_limits<double>::infinity(); //!< its distance
  //! Relative gap (secondDistance - distance) / secondDistance in [0, 1]; 1 with a single template, 0 if reranked.
  double margin = 0.0;
  double threshold = std::numeric_limits<double>::infinity(); //!< acceptance threshold used
  //! Share of the template's outline that the query shows (vpMorphDatabase::support()); NaN when the database's
  //! minimum support is off.
  double support = std::numeric_limits<double>::quiet_NaN();
  //! distance <= threshold and support >= vpMorphDatabase::supportFloor(), or else support >=
  //! vpMorphDatabase::minimumSupport()
  bool accepted = false;
  //! The distance's choice showed too little of its outline and was replaced by the template the query shows most
  //! (vpMorphDatabase, re-ranking); then secondIndex is the distance's choice and margin is 0.
  bool reranked = false;
  bool mirrored = false; //!< the template's mirror image matched best
  /*!
    RIGID: the best template would accept the view, but a runner-up would too and the view does not tell them apart
    (vpMorphDatabase::ambiguity()): rejected because what differs is not in the view, not because no template fits.
  */
  bool ambiguous = false;
  //! An articulated template's opening that matched best (radians, vpMorphArticulation; 0: the taught view).
  double articulation = 0.0;
  /*!
    Minimal-work correspondence from the query contour to the best template's contour (as stored, not
    resampled), ready for vpMorph(query, db[index].contour(), correspondence); for an articulated template seen at
    another opening, to db[index].articulation().pose(articulation).
  */
  vpMorphCorrespondence correspondence;
  std::size_t evaluated = 0; //!< templates whose distance is computed (the others pruned by the bound)

  /*!
    The distance over the threshold (the distance itself without a finite positive threshold): comparable across
    templates whose distances spread differently, so candidates of one image are ranked by it.
  */
  double relativeDistance() const
  {
    return std::isfinite(threshold) && threshold > 0.0 ? distance / threshold : distance;
  }
};

#endif
