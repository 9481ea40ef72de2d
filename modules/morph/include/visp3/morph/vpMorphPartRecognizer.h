/*!
  \file vpMorphPartRecognizer.h
  \brief Which part a view shows: the exact rigid part first, the database's own distance where no part fits rigidly.
*/
#ifndef VP_MORPH_PART_RECOGNIZER_H
#define VP_MORPH_PART_RECOGNIZER_H

#include <cstddef>
#include <memory>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphRecognition.h>

/*!
  \class vpMorphPartRecognizer
  \ingroup group_morph
  \brief Recognition for a robot's first view: a rigid part named by the RIGID distance, a bent object by the
  database's deformation-tolerant one.

  Why two: a D_morph or height distance lets the correspondence slide and bend, so it names a bent object, but it also
  absorbs what tells look-alikes apart and an occluder's edge (a view under a card rejected, look-alikes confused). The
  RIGID distance lays the view on each template by the homography a camera's view of a flat part is (vpMorphRigidCheck):
  it names the exact part, or says that the view does not show what tells two acceptable parts apart
  (vpMorphRecognition::ambiguous); a bent view fits no template rigidly. The answer, per view:
  - the RIGID twin of the database accepts the view: its template;
  - it finds the view ambiguous: rejected (no distance that tolerates more can tell the two apart);
  - no template explains the view rigidly (bent, or no part of the database): the database's own distance decides,
    as vpMorphDatabase::recognize() alone does.

  The twin holds the same templates in the same order: every answer indexes the database given. A RIGID database is
  its own twin (one stage): give one when every part is rigid, since a view of an unknown part that fits no template
  rigidly is otherwise judged by the distance, which accepts more of them. Copies share the two databases (neither
  changes after construction).

  \code
  vpMorphDatabase db = vpMorphDatabase::load("objects.json");   // MULTISCALE, calibrated
  vpMorphPartRecognizer recognizer(db);                          // its RIGID twin calibrated here
  std::size_t chosen = 0;
  vpMorphRecognition r = recognizer.recognize(vpMorphContourExtractor().extractCandidates(I), chosen);
  if (r.accepted) std::cout << db[r.index].name() << std::endl;
  \endcode
  \sa vpMorphDatabase, vpMorphRigidCheck, \ref page_design_recognition
*/
class vpMorphPartRecognizer
{
public:
  //! The stage that answered.
  enum Stage {
    RIGID_STAGE,   //!< the RIGID twin: accepted, or rejected as ambiguous
    DISTANCE_STAGE //!< the database's own distance: no template fits the view rigidly
  };
  //! What the RIGID stage says of a view and one template (namedAs()).
  enum Naming {
    NAMED_TEMPLATE, //!< the view is that template's part
    NAMED_OTHER,    //!< the view is another template's part
    UNDECIDED       //!< ambiguous, or no template fits the view rigidly: for the database's own distance to say
  };

  /*!
    Over a copy of \e db, with its RIGID twin prepared and calibrated (look-alikes among every pair of templates) on
    \e threads (0: all cores).
    \throw vpMorphException::notFoundError for an empty database.
  */
  explicit vpMorphPartRecognizer(const vpMorphDatabase &db, unsigned int threads = 0);

  /*!
    The part \e c shows, or a rejection; \e stage (when given) says which stage answered.
    \throw vpMorphException::badContourError for an empty contour.
  */
  vpMorphRecognition recognize(const vpMorphContour &c, Stage *stage = nullptr) const;
  /*!
    The part shown by the likeliest of \e candidates (regions of one image), its index in \e chosen: a candidate the
    RIGID stage accepts before one the distance accepts, each compared as vpMorphDatabase::recognize() compares
    candidates; the first candidate's answer when none is accepted.
    \throw vpMorphException::badContourError for an empty list or an empty contour.
  */
  vpMorphRecognition recognize(const std::vector<vpMorphContour> &candidates, std::size_t &chosen,
                               Stage *stage = nullptr) const;

  /*!
    Whether \e c is template \e k's part by the RIGID stage alone: a target check (vpMorphServoGuard) that agrees with
    recognize() where the rigid check answers, and leaves the rest to the database's distance.
    \throw vpMorphException::badContourError for an empty contour, badParameterError for \e k out of range.
  */
  Naming namedAs(const vpMorphContour &c, std::size_t k) const;

  //! The database given (its own distance, and the indices of every answer).
  const vpMorphDatabase &getDatabase() const { return *m_db; }
  //! The RIGID twin (the database itself when its distance is RIGID).
  const vpMorphDatabase &getRigidDatabase() const { return m_rigid ? *m_rigid : *m_db; }

private:
  std::shared_ptr<const vpMorphDatabase> m_db;
  std::shared_ptr<const vpMorphDatabase> m_rigid; // null when m_db is RIGID
};

#endif
