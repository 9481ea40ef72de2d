/*!
  \file vpMorphDatabase.h
  \brief Known objects (templates), their JSON file, and recognition by least morph work with rejection.
*/
#ifndef VP_MORPH_DATABASE_H
#define VP_MORPH_DATABASE_H

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRecognition.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphShapeDistance.h>
#include <visp3/morph/vpMorphTemplate.h>

struct vpMorphRigidView; // a template view of the RIGID search (internal)

/*!
  \class vpMorphDatabase
  \ingroup group_morph
  \brief Template database: which known part a view shows, or none. With a D_morph distance (default MULTISCALE) the
  template whose morph costs the least work (the paper's recognition); with RIGID the part whose template the view's
  outline coincides with through a homography, among look-alikes.

  \code
  vpMorphDatabase db = vpMorphDatabase::fromImages("data/objects");  // one template per image, calibrated
  db.save("objects.json");
  vpMorphContour c = vpMorphContourExtractor().extract(I);
  vpMorphRecognition r = db.recognize(c);
  if (r.accepted) vpMorph morph(c, db[r.index].contour(), r.correspondence); // then align with db[r.index].cdMo()
  \endcode

  <b>Distance</b> (vpMorphShapeDistance, saved with the database so that it is queried with the distance it was
  calibrated with): MULTISCALE by default, mirror images included (vpMorphRecognition::mirrored); RIGID names the
  exact rigid part among look-alikes (mirror images off by default).

  <b>Acceptance with a D_morph distance.</b> calibrate() gives each template t the threshold calibrationSlack() x
  within(t), within(t) the largest distance between t and perturbed copies of it (perturbations(): re-rendered
  views, another sampling start, a straight edge hiding 20 % of the outline); setThreshold() replaces them all. A view
  is accepted when its best distance is within its template's threshold and it shows at least supportFloor() of that
  template's outline (support()); or else, when the distance rejects it, when it shows at least minimumSupport()
  (an occluded view). When it shows less than minimumSupport() of its nearest template's outline by their
  correspondence, the rerankCandidates() nearest other templates, and as many on which its outline shape aligns at
  least cost (vpMorphRigidShape, voted by the parts that show: an occluder's notch can rank the view's own template far
  down the distance), are aligned on it (support()), the nearest by the outline shapes too, and the one it shows most
  replaces the distance's choice if it reaches the minimum (vpMorphRecognition::reranked).

  <b>Acceptance with RIGID.</b> The rigidShortlist() templates whose coarse alignment (vpMorphRigidShape) costs least
  are compared exactly (vpMorphRigidCheck); the least exact cost wins. When the view lies on none of them as far as it
  shows it, each is compared again from the one of its turns onto itself that the coarse cost ranked out, or of the
  whole view's start at its alignment's turn, that the fine outlines rank first, if they rank it before its alignment
  (vpMorphRigidCheck::startCost()): smoothed outlines cannot tell a toothed part's turns, nor a spring's coils, apart.
  The view is accepted when it shows at least minimumSupport() of the template's
  outline, sticks out of it by at most maximumOutside() of its own, leaves at most
  as much of the template's outline outside its region when nothing cuts its outline
  (vpMorphRigidCheck::Result::absentShare: such a view hides nothing, so what it lacks is absent, not hidden), has at
  most 1 - minimumSupport() of its outline on its own edge where the template has none
  (vpMorphRigidCheck::Result::unexplainedShare: the same majority both ways; an occluder only hides), and the
  runner-up, if acceptable too, is told from it by at least ambiguity() (vpMorphRigidCheck::evidence(): outline that
  one explains and the other not, on the view's side, and on the templates' side what the view says is absent rather
  than hidden; look-alikes that differ only where the view is hidden are not told apart: rejected).
  Before that, when the view lies on the best template as far as it shows it (a look-alike may lack what the view
  lacks of the best), its lookAlikes() are compared exactly too, each as a
  shortlisted template is and from the best's fitted start carried over by the two templates' own alignment (and so
  on, should one of them become the best): a view is accepted only against every template whose views could be taken
  for it, not only against those the coarse stage happened to rank (calibrate() finds the look-alikes; an
  uncalibrated database compares the shortlist only).

  <b>Search.</b> recognize() visits the templates by increasing lower bound of their distance and stops when the bound
  exceeds the runner-up's distance: the result is exactly that of recognize(c, false). An articulated template is also
  held at its poses every 4 deg over its range; a view the taught views leave unaccepted is searched again with them
  (vpMorphRecognition::articulation).

  <b>Files</b> (save(), load()): JSON, "format": "vispmorph-template-database", "version": 1, written atomically
  (temporary file, then rename); contours stored, image paths relative to the file. Errors: vpMorphException::ioError
  (unreadable, malformed, wrong version, missing image), badParameterError (duplicate names), notFoundError (unknown
  name or index).

  Not thread safe for modification; const methods may run concurrently.
  \sa vpMorphTemplate, vpMorphRecognition, \ref page_design_recognition
*/
class vpMorphDatabase
{
public:
  //! Progress callback (done, total) of the long operations.
  typedef vpMorphShapeDistance::Progress Progress;

  //! An empty database queried with \e distance.
  explicit vpMorphDatabase(
      const vpMorphShapeDistance &distance = vpMorphShapeDistance(vpMorphShapeDistance::MULTISCALE));

  /*!
    One template per image of \e dir (png, jpg, jpeg, pgm, ppm, bmp, tif, tiff), named after
    the file without its extension (sorted by that name); the largest object of each image (vpMorphContourExtractor) on
    all cores, then calibrate(). \e progress counts the images, then the calibration steps. \throw
    vpMorphException::ioError if \e dir is not a readable directory, holds no image or an image cannot be read;
    badImageError if an image has no object; badParameterError on two images with the same name.
  */
  static vpMorphDatabase
  fromImages(const std::string &dir,
             const vpMorphShapeDistance &distance = vpMorphShapeDistance(vpMorphShapeDistance::MULTISCALE),
             const Progress &progress = Progress());

  /*!
    Reads a database written by save().
    \throw vpMorphException::ioError on an unreadable, malformed, truncated or wrong-version file, or (if
    \e checkImages) a missing template image; badParameterError on duplicate names or invalid contours.
  */
  static vpMorphDatabase load(const std::string &path, bool checkImages = true);
  /*!
    Writes the database as JSON atomically (temporary file then rename). Image paths are written relative to
    the file's directory, so that a database moves with its images; load() resolves them back.
    \throw vpMorphException::ioError if the file cannot be written.
  */
  void save(const std::string &path) const;
  //! The JSON text of the database, image paths as they are in memory (save() makes them relative).
  std::string toJson() const;
  //! Parses the text of a database file; \e baseDir resolves relative image paths for \e checkImages.
  static vpMorphDatabase fromJson(const std::string &text, bool checkImages = false, const std::string &baseDir = "");

  /*!
    Adds a template; the threshold is no longer calibrated (call calibrate() again) unless it was set by hand.
    \throw vpMorphException::badParameterError on an empty contour or a name already used.
  */
  void add(const vpMorphTemplate &t);
  //! Removes template \e name. \throw vpMorphException::notFoundError if unknown.
  void remove(const std::string &name);
  /*!
    Gives template \e name the articulation \e a (an empty one makes it rigid) and draws its poses; the calibration
    stays, as it is made on the taught views only. \throw vpMorphException::notFoundError if unknown.
  */
  void setArticulation(const std::string &name, const vpMorphArticulation &a);

  //! Number of templates.
  std::size_t size() const { return m_templates.size(); }
  //! True without templates.
  bool empty() const { return m_templates.empty(); }
  //! \throw vpMorphException::notFoundError if out of range.
  const vpMorphTemplate &operator[](std::size_t k) const;
  //! \throw vpMorphException::notFoundError if unknown.
  const vpMorphTemplate &operator[](const std::string &name) const;
  //! Index of template \e name, or vpMorphRecognition::npos.
  std::size_t find(const std::string &name) const;
  //! All templates, in order.
  const std::vector<vpMorphTemplate> &templates() const { return m_templates; }

  //! The distance the database is queried with.
  const vpMorphShapeDistance &distance() const { return m_distance; }
  //! Changes the distance; the calibration is dropped (unless the threshold was set by hand) and minimumSupport()
  //! goes back to the model's default.
  void setDistance(const vpMorphShapeDistance &d);

  /*!
    Calibrates the acceptance threshold (see the class description) on \e threads threads (0: all cores).
    \throw vpMorphException::badParameterError on an empty database.
  */
  void calibrate(unsigned int threads = 0, const Progress &progress = Progress());
  /*!
    Acceptance threshold of template \e k: the value given to setThreshold() if any, otherwise
    calibrationSlack() x within(k) once calibrated, +inf before.
    \throw vpMorphException::notFoundError if out of range.
  */
  double threshold(std::size_t k) const;
  //! One threshold for every template, instead of the calibrated ones. \throw badParameterError unless finite and > 0.
  void setThreshold(double t);
  //! Back to the calibrated thresholds.
  void clearThreshold();
  //! True after setThreshold().
  bool isThresholdManual() const { return m_manual; }
  //! Factor between a template's threshold and the worst distance of its calibration perturbations.
  static double calibrationSlack() { return 1.25; }
  /*!
    How many of the nearest other templates recognize() aligns on a view when the distance's choice shows too
    little of its outline (re-ranking), by the distance and again by the outline shapes' alignment cost: 8 each, an
    alignment costing about a millisecond.
  */
  static std::size_t rerankCandidates() { return 8; }
  //! True once calibrate() has run since the last change.
  bool isCalibrated() const { return m_calibrated; }

  /*!
    Share, in [0, 1], of template \e k's outline that contour \e c shows: \e c is aligned on the template by a
    similarity (the minimal-work correspondence, fitted robustly, then refined point to edge on the outlines, \e c
    onto the template and the template onto \e c, as an occluder's edge, which only \e c has, drags the first when it
    runs near a template edge; also from that fit turned half a turn, as a nearly symmetric outline can be matched end
    for end), and 512 points spread evenly along the template's outline are counted when they lie within 1/256 of its
    perimeter of the aligned \e c (2 px on a 500-px outline); the best of the four alignments counts. When that is less
    than minimumSupport(), the outline shapes' alignment (vpMorphRigidShape::alignOn(), which an occluder's notch does
    not throw off as it can the correspondence) counts if it shows at least minimumSupport(). \e mirrored also
    aligns \e c's mirror image (a part turned over, vpMorphRecognition::mirrored; a nearly symmetric part may be matched
    either way), and the better counts. 0 when \e c cannot be aligned (a degenerate fit).
    \throw vpMorphException::notFoundError if \e k is out of range, badContourError on an empty contour or
    badParameterError on units that differ from the template's. For an articulated template, the better of its
    taught view's and of its pose that \e c lies on best (its opening).
  */
  double support(const vpMorphContour &c, std::size_t k, bool mirrored = false) const;
  /*!
    Least support() that accepts a view: with RIGID, the only way (default 0.5, see the class description); with a
    D_morph distance, a view its distance rejects (an occluded view; default 0.75; +inf: the distance alone decides).
  */
  double minimumSupport() const { return m_minSupport; }
  //! \throw vpMorphException::badParameterError unless in (0, 1] or +inf.
  void setMinimumSupport(double s);
  /*!
    Least support() of a view that the distance accepts (Unknown shapes, in the class description): below it, and
    with no template re-ranked, recognize() rejects the view. 0 turns it off; it needs the support on (a finite
    minimumSupport()). Not applied by accepts(), which checks a template already recognised.
  */
  double supportFloor() const { return m_supportFloor; }
  //! \throw vpMorphException::badParameterError unless in [0, 1].
  void setSupportFloor(double s);
  /*!
    Whether \e c is a view of template \e k, recognize()'s rule for a template given (the target check during a
    check of a known target): its distance (returned in \e distance if not null) is within \e slack x threshold(k), or
    else \e c shows at least minimumSupport() of its outline (its mirror image if that is what the distance matched).
    Without the supportFloor(): the template is already known, and the check should not cost an alignment on every view.
    \throw vpMorphException as support(), and badParameterError on a slack that is not finite and >= 1.
  */
  bool accepts(const vpMorphContour &c, std::size_t k, double slack = 1.0, double *distance = nullptr) const;
  //! within(t) of the last calibration, per template (empty before): the worst distance of its perturbations.
  const std::vector<double> &withinDistances() const { return m_within; }
  //! between(t) of the last calibration, per template: the distance to its nearest other template (diagnosis).
  const std::vector<double> &betweenDistances() const { return m_between; }
  //! A template whose views could be taken for another (lookAlikes()), and how to lay the other on it.
  struct LookAlike
  {
    std::size_t index;               //!< the look-alike template
    vpMorphRigidTransform transform; //!< the other template's pixels to this one's (a start for the exact check)
  };
  /*!
    RIGID, calibrated: the templates some view of which the search could accept as template \e k. A view of \e i is
    accepted as \e k only if it shows at least minimumSupport() of k's outline, and an occluder only hides: so \e i is
    a look-alike of \e k when i's whole outline, laid on k's (vpMorphRigidCheck), shows at least minimumSupport() of
    it. calibrate() compares every ordered pair of templates exactly, from the coarse alignment and its alternative
    (T (T - 1) comparisons; the other hypotheses, turns by a symmetry or the sweep, as a query's search bounds them):
    the coarse alignment ranks whole outlines, and may rank anywhere a template that shows enough of another's only in
    part.
    Empty for an uncalibrated database or another distance.
    \throw vpMorphException::notFoundError on an index out of range.
  */
  const std::vector<LookAlike> &lookAlikes(std::size_t k) const;

  /*!
    Recognises a contour (see the class description). \e prune = false runs the exhaustive reference search.
    \throw vpMorphException::notFoundError on an empty database, badContourError on an empty contour.
  */
  vpMorphRecognition recognize(const vpMorphContour &c, bool prune = true) const;
  /*!
    Which of several candidate outlines of one view shows a known part (vpMorphContourExtractor::extractCandidates()):
    each is recognised, and \e chosen receives the index of the accepted one whose distance is the smallest share of
    its template's threshold (the distance itself when the threshold is not finite), the first candidate when none is
    accepted. Why the share: thresholds differ between templates, and it says how well each candidate is explained.
    \throw vpMorphException::notFoundError on an empty database, badContourError on no candidate or an empty one.
  */
  vpMorphRecognition recognize(const std::vector<vpMorphContour> &candidates, std::size_t &chosen) const;
  //! recognize() for many contours on \e threads threads (0: all cores); \e progress counts the contours.
  std::vector<vpMorphRecognition> recognizeAll(const std::vector<vpMorphContour> &contours, unsigned int threads = 0,
                                               const Progress &progress = Progress()) const;

  /*!
    The perturbed copies of a contour used by calibrate() (noise, resampling, occlusions), deterministic.
    Public so that tests and tools can see what the threshold was calibrated on.
  */
  static std::vector<vpMorphContour> perturbations(const vpMorphContour &c);

  /*!
    Templates the RIGID search compares exactly (vpMorphRigidCheck), those whose coarse alignment costs least: 5, as
    each comparison costs a few hundred microseconds and a query against 100 templates should stay within 5 ms.
  */
  static std::size_t rigidShortlist() { return 5; }
  //! RIGID: the largest share of a view's outline outside its template's region, and of the template's outside a
  //! view that hides nothing, that accepts it (see the class).
  static double maximumOutside() { return 0.1; }
  /*!
    RIGID: the least evidence (vpMorphRigidCheck::evidence()) that tells the best template from another acceptable
    one: 2.88 standard deviations (one-sided 0.2 %, the wrong answers aimed at) of the evidence between two templates
    that the view fits alike, under the measured outline's edge noise (sigma a fifth of the check's tolerance: a
    sample's term has variance 2 / 625, each side's mean over 256 samples, the two sides averaged).
  */
  static double ambiguity() { return 2.88 * std::sqrt(2.0 / 625.0 / 256.0); }

private:
  vpMorphRecognition search(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                            vpMorphMatcher &matcher) const;
  //! RIGID: search() in two stages (vpMorphRigidSearch), \e prune false comparing every template exactly.
  vpMorphRecognition rigidSearch(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                                 vpMorphMatcher &matcher, bool poses) const;
  //! RIGID: the views of every template (with \e poses, the articulated ones' poses too), but template \e skip.
  std::vector<vpMorphRigidView> rigidViews(bool poses, std::size_t skip = vpMorphRecognition::npos) const;
  //! RIGID: template k's prepared view \e pose (npos: the taught one).
  const vpMorphRigidShape &rigidView(std::size_t k, std::size_t pose) const;
  //! RIGID: the comparison of \e q with template k, its poses too (\e poses), its mirror image too (\e mirrored).
  vpMorphRigidCheck::Result rigidCheck(const vpMorphShapeDistance::Shape &q, std::size_t k, bool mirrored,
                                       bool poses) const;
  //! A look-alike found by calibration: \e lookAlike belongs to template \e of's list (lookAlikes()).
  struct Found
  {
    std::size_t of;
    LookAlike lookAlike;
  };
  /*!
    RIGID: template \e i compared exactly with every other (vpMorphRigidSearch::run()'s \e every), each in full;
    appends to \e found the templates it is a look-alike of, sets \e nearest (npos: none) and returns its cost.
  */
  double rigidRow(std::size_t i, std::vector<Found> &found, std::size_t &nearest) const;
  //! The per-template look-alike lists from the rows' findings.
  std::vector<std::vector<LookAlike>> gathered(const std::vector<std::vector<Found>> &found) const;
  //! RIGID: lookAlikes() found anew (a calibrated file written without them), on \e threads threads (0: all cores).
  void findLookAlikes(unsigned int threads);
  //! RIGID: whether the view lies on that template as far as it shows it (minimumSupport(), nothing outside it).
  bool rigidFits(const vpMorphRigidCheck::Result &r) const;
  //! RIGID: whether a comparison accepts the view as that template (rigidFits(), it lacks none of it in sight, and
  //! its own edge is mostly the template's).
  bool rigidAccepted(const vpMorphRigidCheck::Result &r) const;
  //! support(), with an articulated template's poses or (\e poses false) its taught view only.
  double support(const vpMorphContour &c, std::size_t k, bool mirrored, bool poses) const;
  //! The same with \e view, c's outline shape (vpMorphRigidShape), built on first use: once for all templates.
  double support(const vpMorphContour &c, std::size_t k, bool mirrored, bool poses, vpMorphRigidShape &view) const;
  //! Appends a template contour's prepared shape and its outline shape (m_shapes and m_outlineShapes in step).
  void pushShapes(const vpMorphContour &c);
  //! Template k's outline shape (vpMorphRigidShape): RIGID's own, else one built for support() and re-ranking.
  const vpMorphRigidShape &outlineShape(std::size_t k) const
  {
    return m_shapes[k].rigid.empty() ? m_outlineShapes[k] : m_shapes[k].rigid[0];
  }
  //! One search over the taught views, or (\e poses) over the articulated templates' poses too.
  vpMorphRecognition search(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                            vpMorphMatcher &matcher, bool poses) const;
  //! One view of an articulated template at an opening other than the taught one (the taught one is m_shapes).
  struct Pose
  {
    double angle;
    vpMorphContour contour;
    vpMorphShapeDistance::Shape shape;
  };
  //! The views of template k besides the taught one: its articulation every kPoseStep over its range.
  std::vector<Pose> poses(const vpMorphTemplate &t) const;
  //! Distance of \e q to template k: to its taught view, and with \e poses the least over its poses too.
  double templateDistance(const vpMorphShapeDistance::Shape &q, std::size_t k, vpMorphMatcher &matcher,
                          double abandonAbove, bool *mirrored, bool poses) const;
  //! The least of \e best (the distance to the taught view, \e mirrored its side) and the distances of \e q to
  //! template k's poses, each abandoned above the best so far (or \e abandonAbove, when given and smaller).
  double poseDistance(const vpMorphShapeDistance::Shape &q, std::size_t k, vpMorphMatcher &matcher, double best,
                      double abandonAbove, bool &mirrored) const;
  double templateLowerBound(const vpMorphShapeDistance::Shape &q, std::size_t k, bool poses) const;
  /*!
    The pose of articulated template k that \e c lies on best (vpMorphArticulation::fitOverlap(); npos: the taught
    view). Why not the distance's: it picks an articulated template well but its opening poorly.
  */
  std::size_t overlapPose(const vpMorphContour &c, std::size_t k, vpMorphMatcher &matcher) const;
  //! The contour of template k's view \e pose (npos: the taught one).
  const vpMorphContour &templateView(std::size_t k, std::size_t pose) const;
  void invalidate();
  std::string toJson(const std::string &relativeTo) const;

  vpMorphShapeDistance m_distance;
  std::vector<vpMorphTemplate> m_templates;
  std::vector<vpMorphShapeDistance::Shape> m_shapes;
  std::vector<vpMorphRigidShape> m_outlineShapes; // per template, when m_shapes holds none (see outlineShape())
  std::vector<std::vector<Pose>> m_poses;         // per template: its articulated poses (none for a rigid one)
  double m_threshold;
  double m_minSupport = 0.75;
  double m_supportFloor = 0.5;
  bool m_calibrated = false, m_manual = false;
  std::vector<double> m_within, m_between;
  std::vector<std::vector<LookAlike>> m_lookAlikes; // RIGID, calibrated: per template (lookAlikes())
};

#endif
