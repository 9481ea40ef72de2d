/*!
  \file vpMorphShapeDistance.h
  \brief The dissimilarity used for recognition and retrieval: D_morph on a chosen representation of the contours.
*/
#ifndef VP_MORPH_SHAPE_DISTANCE_H
#define VP_MORPH_SHAPE_DISTANCE_H

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphHeightFunction.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphRigidShape.h>
#include <visp3/morph/vpMorphWorkModel.h>

/*!
  \class vpMorphShapeDistance
  \ingroup group_morph
  \brief Which contours D_morph is computed on, with or without mirror images, and the batch machinery
  (prepared shapes, a cheap lower bound for pruning, distance matrices on several cores).

  D_morph itself (vpMorphMatcher) depends on how the outline was turned into a polygon. Recognition needs
  that choice to be explicit, named and saved with a template database, so that a database is always
  queried with the distance it was calibrated with. Models:
  - POLYGON: the parameterless polygons themselves (vpMorphContourExtractor), no mirror image: the correspondence
    is between the very vertices a morph uses, and a planar object lying on a table is never seen mirrored.
  - PAPER: the paper's recognition set-up as used in the retrieval literature: both outlines resampled to
    points() vertices equally spaced by arc length (64), mirror images included (distance = the smaller of
    the two), vpMorphWorkModel with only the bending weight changed (kb = 0.1).
  - MULTISCALE (default of vpMorphDatabase): the sum of D_morph over several versions of the outline, smoothed
    by a circular Gaussian of width 1 %, 5 % and 10 % of the perimeter and resampled to 48 vertices (the same
    mirror choice at every scale), kb = 0.2. Fine scales see details, coarse ones the overall form, which a
    single polygon weighs badly: one spurious notch costs as much as a real limb at a single scale. The finest
    width is not 0 on purpose: 1 % is about half the sample spacing, so the samples do not alias small
    features. Widths and kb: \ref page_design_recognition.
  - RIGID: not D_morph. The view laid on the template by a plane homography (vpMorphRigidShape::alignOn(), then
    vpMorphRigidCheck), the two-way truncated quadratic cost of what does not coincide, in [0, 1]: a look-alike's
    differences stay uncovered, where D_morph absorbs them. Mirrors off (a part on a table shows one side; mirrors on
    try the mirror image when the direct one costs more). Not symmetric (the first shape is laid on the second).
  - HEIGHT: not D_morph. Height functions matched by a cyclic correspondence (vpMorphHeightFunction, settings through
    heightFunction()), mirrors included: the best of these models for shape retrieval.

  Every representation is computed once per contour (prepare()), so a matrix over N shapes costs N
  preparations and N(N-1)/2 distances. The distance is symmetric and invariant to translation, rotation and
  scale (the matcher normalises to unit perimeter).

  <b>Lower bound.</b> (D_morph models; 0 for RIGID and HEIGHT) lowerBound() is a cheap certificate that distance()
  cannot be smaller: every vertex of each polygon is entered by exactly one step of a correspondence, and every step
  costs at least as much as the cheapest step that could enter its vertex, so the sum over vertices of those minima (for
  either polygon, take the larger) bounds D_morph from below; mirror images have the same lengths and turning angles so
  the bound holds for them too. Used to skip templates that cannot win a recognition, without changing its result.

  \code
  const vpMorphShapeDistance d(vpMorphShapeDistance::MULTISCALE);
  std::vector<vpMorphShapeDistance::Shape> shapes = d.prepareAll(contours);
  std::vector<double> D = d.matrix(shapes);             // N x N, row-major, on all cores
  \endcode
  \sa vpMorphDatabase, vpMorphMatcher, \ref page_design_recognition
*/
class vpMorphShapeDistance
{
public:
  //! The contours D_morph is computed on (see the class description).
  enum Model {
    POLYGON,    //!< Parameterless polygons as extracted, no mirror.
    PAPER,      //!< 64 points by arc length, mirrors included.
    MULTISCALE, //!< Sum over Gaussian-smoothed scales, resampled, mirrors included.
    RIGID,      //!< The outlines laid on each other by a homography (vpMorphRigidCheck), no mirror.
    HEIGHT      //!< Height functions matched cyclically (vpMorphHeightFunction), mirrors included.
  };

  //! A contour in the representation(s) of a model, ready for distance() and lowerBound().
  struct Shape
  {
    std::vector<vpMorphContour> forms;        //!< per scale: the form, then its mirror image if mirrors are used
    std::vector<std::vector<double>> len;     //!< per scale: incoming edge lengths (positive traversal, unit perimeter)
    std::vector<std::vector<double>> phi;     //!< per scale: turning angles (positive traversal)
    std::vector<std::vector<double>> lenSort; //!< per scale: lengths sorted
    std::vector<std::vector<double>> phiSort; //!< per scale: angles sorted
    std::vector<vpMorphRigidShape> rigid;     //!< RIGID: the contour, then its mirror image (see rigidShape())
    vpMorphHeightFunction::Descriptor height; //!< HEIGHT: the descriptor (and its mirror image's)
  };

  //! Progress of a batch job: \e done of \e total units; called from the calling thread only.
  typedef std::function<void(std::size_t done, std::size_t total)> Progress;

  //! The model with its default settings (POLYGON: default work model).
  explicit vpMorphShapeDistance(Model model = POLYGON);
  //! Named models: "polygon", "paper", "multiscale", "rigid", "height". \throw vpMorphException::badParameterError if
  //! unknown.
  static vpMorphShapeDistance fromName(const std::string &name);
  //! Name of the model, as accepted by fromName().
  std::string name() const;
  //! The settings as a JSON object: model, points, mirrors, scales, the work model's ks, kb, cs, and the height
  //! model's segments, skip and starts (what a database file and a benchmark summary record).
  std::string settingsJson() const;

  //! The model.
  Model model() const { return m_model; }
  //! The work model of the D_morph models.
  const vpMorphWorkModel &workModel() const { return m_work; }
  //! Sets the work model.
  void setWorkModel(const vpMorphWorkModel &w) { m_work = w; }
  //! Vertices per resampled outline (0 for POLYGON: the polygon as it is).
  std::size_t points() const { return m_points; }
  /*!
    \throw vpMorphException::badParameterError if n < 8 for a resampling model, or (HEIGHT) if its segments do not
    divide n.
  */
  void setPoints(std::size_t n);
  //! Whether mirror images are tried.
  bool mirrors() const { return m_mirrors; }
  //! Tries mirror images too (or not).
  void setMirrors(bool on)
  {
    m_mirrors = on;
    m_height.setMirrors(on);
  }
  //! Gaussian widths (fractions of the perimeter) of the scales; {0} for a single unsmoothed scale.
  const std::vector<double> &scales() const { return m_scales; }
  //! \throw vpMorphException::badParameterError on an empty list or a negative or non-finite width.
  void setScales(const std::vector<double> &sigmas);

  /*!
    The representations of \e c used by this distance.
    \throw vpMorphException::badContourError on an empty contour (HEIGHT: also on fewer than 3 vertices or no area).
  */
  Shape prepare(const vpMorphContour &c) const { return prepare(c, true); }
  /*!
    As prepare(c), but with \e rigidMirror false RIGID leaves the mirror image's shape unmade (Shape::rigid holds the
    contour's only; Shape::forms both): a template is never laid on a view turned over, and a view accepted as it is
    never needs its mirror image's. rigidShape() makes it where it is needed.
  */
  Shape prepare(const vpMorphContour &c, bool rigidMirror) const;
  /*!
    RIGID: the shape of \e s.forms[m] (0: the contour, 1: its mirror image), \e s.rigid[m] when prepared, made
    otherwise.
    \throw vpMorphException::badParameterError when \e s has no such form or was not prepared for RIGID.
  */
  static vpMorphRigidShape rigidShape(const Shape &s, std::size_t m);
  /*!
    Distance between two prepared shapes (symmetric for the D_morph models, nearly for HEIGHT); \e abandonAbove: once
    the partial sum over the scales exceeds it the computation stops and returns a value > abandonAbove (exact
    otherwise). \e mirrored (if not null) tells whether b's mirror image gave the distance. RIGID: a laid on b (b's
    mirror image: a's mirror image laid on b), and \e check (if not null) receives the comparison that gave it.
  */
  double distance(const Shape &a, const Shape &b, vpMorphMatcher &matcher, double abandonAbove = -1.0,
                  bool *mirrored = nullptr, vpMorphRigidCheck::Result *check = nullptr) const;
  //! Convenience: distance between two contours.
  double distance(const vpMorphContour &a, const vpMorphContour &b) const;
  /*!
    Valid lower bound of distance(a, b) (see the class description): an O(mn) pass per scale, a fraction of the
    cost of distance().
  */
  double lowerBound(const Shape &a, const Shape &b) const;
  //! HEIGHT's descriptor and matching settings.
  const vpMorphHeightFunction &heightFunction() const { return m_height; }
  //! Sets HEIGHT's settings (its mirror setting follows setMirrors()).
  void setHeightFunction(const vpMorphHeightFunction &h);
  //! A matcher configured with this work model (scale normalisation on).
  vpMorphMatcher matcher() const { return vpMorphMatcher(m_work, true); }

  /*!
    prepare() for many contours on \e threads threads (0: all cores).
  */
  std::vector<Shape> prepareAll(const std::vector<vpMorphContour> &contours, unsigned int threads = 0,
                                const Progress &progress = Progress()) const;
  /*!
    Full symmetric N x N distance matrix (row-major, zero diagonal), on \e threads threads (0: all cores),
    one matcher per thread. \e progress receives the number of pairs done.
  */
  std::vector<double> matrix(const std::vector<Shape> &shapes, unsigned int threads = 0,
                             const Progress &progress = Progress()) const;

  /*!
    Runs job(k, matcher) for k = 0 .. count-1 on \e threads threads (0: all cores), each thread with its own
    matcher, and reports progress (units done) from the calling thread about ten times a second.
    The first exception thrown by a job is rethrown after all threads stop.
  */
  void
  parallelFor(std::size_t count, unsigned int threads, const std::function<void(std::size_t, vpMorphMatcher &)> &job,
              const Progress &progress = Progress(),
              const std::function<std::size_t(std::size_t)> &weight = std::function<std::size_t(std::size_t)>()) const;

private:
  Model m_model;
  vpMorphWorkModel m_work;
  std::size_t m_points;
  bool m_mirrors;
  std::vector<double> m_scales;
  vpMorphHeightFunction m_height;
};

#endif
