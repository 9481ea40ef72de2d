/*!
  \file vpMorphDatabase.h
  \brief Known objects (templates), their JSON file, and recognition by least morph work with rejection.
*/
#ifndef VP_MORPH_DATABASE_H
#define VP_MORPH_DATABASE_H

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
  if (r.accepted) vpMorph morph(c, db[r.index].contour(), r.correspondence); // then servo to db[r.index].cdMo()
  \endcode

  <b>Distance.</b> A vpMorphShapeDistance, saved with the database so that it is always queried with the
  distance it was calibrated with. Default MULTISCALE (mirrors included: a flat part turned over shows the
  mirror image of its outline; vpMorphRecognition::mirrored says so): D_morph between the raw polygons
  (POLYGON) confuses the tools as soon as 15 % of an outline is occluded, because a single polygon charges a
  spurious notch as much as a real limb. RIGID names the exact rigid part among look-alikes, whose differences a
  deformation-tolerant distance absorbs; mirror images off by default (a part lying on a table shows one side;
  vpMorphShapeDistance::setMirrors() tries the mirror image when the view itself is not accepted).

  <b>Recognition with RIGID</b> (recognize()), in two stages: every template's view is aligned coarsely on the view
  (vpMorphRigidShape::alignOn(), tens of microseconds each), and the rigidShortlist() templates whose coarse cost is
  least are compared exactly (vpMorphRigidCheck: the outlines laid on each other by a homography, both ways). The
  least exact cost wins (vpMorphRecognition::distance; ties to the lower index); recognize(c, false) compares every
  template exactly, and a test checks that the two stages give its answer. The view is accepted when
  - it shows at least minimumSupport() of the template's outline (vpMorphRecognition::support: the share of the
    template's outline within the check's tolerance of the view's; default 0.5, see below),
  - it does not stick out of the template (at most maximumOutside() of its outline beyond twice the tolerance outside
    the template's region: an occluder only takes away; not measured on a silhouette joined across an occluder), and
  - no other template of those compared is also acceptable at an exact cost within ambiguity() of it: two
    look-alikes that the visible part cannot tell apart (the card hides where they differ) give a rejection, not a
    coin toss.
  The three values are read off the distributions of the check on rendered views of the development classes of the
  MPEG-7 split (data/pools; vispmorph-reid, development seeds) under the documented nuisances: minimumSupport() lies
  above the most any absent shape showed of its best template, and below what the right template shows in all but a
  few of the views with a fifth of the outline hidden; maximumOutside() above the most any right template's view
  stuck out (a blurred notch fills in); ambiguity() above the gaps by which a look-alike that the visible part cannot
  tell apart beat the right template. Each template's threshold (calibrate()) is still computed, for accepts() with a
  slack and for the servo's checks.

  <b>Acceptance thresholds (calibrate()).</b> (What follows, to Fast querying, is the D_morph distances'
  recognition; with RIGID, calibrate() computes within(t) and the threshold the same way, and between(t) by the
  two-stage search.) Calibrated from the database itself, because the scale of
  D_morph depends on the objects and on the distance model. For each template t:
  - within(t): the largest distance between t and perturbed copies of its own contour (perturbations()):
    new views (the outline rotated and re-digitised, with and without grey-level noise), resampling from
    another start, and a straight edge of background colour hiding a contiguous 20 % of the outline at sixteen
    places (more than the 15 % the tests demand). Rotation and translation alone change nothing: D_morph is
    invariant; what they change is the digitisation, which the re-rendered views cover.
  - between(t): the distance from t to its nearest other template (+inf with one template).

  The threshold of template t is calibrationSlack() x within(t) = 1.25 within(t): a view is taken for t
  when it costs at most 25 % more work than the worst perturbation of t that the calibration tried (the
  slack covers perturbations it did not try). Per template, because the variability under occlusion differs
  widely between objects (D_morph of a hammer with its head partly hidden grows three times as much as that of
  a wedge), so one global threshold set by the most variable object would accept unknown objects near the
  least variable one. between(t) is kept for diagnosis: when threshold(t) >= between(t), a view of t's nearest
  neighbour could also be accepted as t, and the caller should look at vpMorphRecognition::margin.
  The query is accepted when its best distance is <= the threshold of its best template, or else when it shows
  at least minimumSupport() of that template's outline (support()). A view that shows less than that of its best
  template's outline is checked against the others (re-ranking, below); accepted by the distance alone, it is
  rejected if it shows almost nothing of it (supportFloor(), Unknown shapes).
  setThreshold() replaces every threshold by one value (e.g. chosen on a validation set).

  <b>Occluded views (support()).</b> An occluder that bites a notch into a side costs D_morph far more work than
  the straight edges of the calibration: a wedge with 14 % of its outline behind a square is 1.5 times its
  threshold away from its template, although nothing else matches it. Raising the thresholds to cover such views
  would accept most unknown shapes (tried while this was built, and dropped: with square occluders in the
  calibration too, the thresholds doubled and the six tools' database accepted the first image of 41 of the 60
  MPEG-7 classes instead of 11). Instead, a view the distance rejects is aligned on its best template (support())
  and the share of the template's outline that lies on the view's is measured: a view with part of it hidden still
  shows the rest exactly, where an unknown or a deformed object does not. The default minimum, 0.75, is the 80 %
  that an occlusion of up to 20 % leaves, less 5 % for the ends of the hidden stretch.

  <b>Re-ranking.</b> The same notch can also cost less work on another tool's outline than on its own: with a
  square card over 10-15 % of their outlines, 6 of 48 views of the six tools were accepted by the distance as the
  wrong tool (a key and a wedge as the wrench, screwdrivers as the pliers or the wedge), and a wedge under a card on
  the bench was nearest the screwdriver, rejected, while showing 0.90 of the wedge's outline. So whenever the view
  shows less than the minimum of its nearest template's outline, the rerankCandidates() nearest other templates are
  aligned on the view (whatever their distance: the notch put the wedge at 2.3 times its threshold); the one it shows
  most replaces the distance's choice if it reaches the minimum (vpMorphRecognition::reranked). A view none of them
  verifies keeps the distance's choice: a deformed view shows no template's outline whole. This costs every distance
  and up to 8 alignments more, only for such views (over the 1400 MPEG-7 images, mostly rejected: 14 ms an image
  instead of 9). Of those 6 wrong views, 4 are put right; the other 2 (a screwdriver taken for the wedge) show only
  0.62-0.64 of the screwdriver's outline and keep the wrong answer.

  <b>Unknown shapes.</b> The distance alone accepts many shapes that are none of the templates: the six tools'
  database took 281 of the 1400 MPEG-7 images for one of them. Those show little of the template's outline (median
  0.27), where the bench's views of the tools, tilted by up to 25 deg, deformed or occluded, show at least 0.63 of
  theirs. So a view the distance accepts is rejected when it shows less than supportFloor() = 0.5 of the template it
  is taken for and no template is re-ranked. 0.5 was chosen on the bench's first seed (its true views at least 0.63)
  and on MPEG-7 (250 of the 281 rejected), then checked on two other seeds (320 views: the true ones at least 0.64)
  and on Kimia-99 (16 of the 20 accepted rejected; the 4 left are Kimia's wrenches, taken for the wrench). It was
  0.35 while support() fitted the view onto the template only; fitting the template onto the view too raised the
  unknown shapes' support as well as the true views' (it accepted 94 MPEG-7 images at 0.35, against 76 before).

  <b>Fast querying.</b> recognize() visits the templates in increasing order of a cheap lower bound of their
  distance (vpMorphShapeDistance::lowerBound()) and stops as soon as the bound exceeds the second-best
  distance found: those templates can be neither the best nor the runner-up, so the result (best, runner-up,
  distances, ties broken by the lower index) is exactly that of the exhaustive search (recognize(c, false)).

  <b>Articulated templates.</b> A template given an articulation (vpMorphTemplate::setArticulation(): two parts
  about a pin, an opened pliers) is also held at its poses every 4 deg over its range (vpMorphArticulation::pose()).
  A view that the taught views leave unaccepted is searched again with the poses (the least distance over a
  template's poses counts, with the same pruning), its support taken on the pose it lies on best by overlap
  (overlapPose()); vpMorphRecognition::articulation gives that opening. A view that the taught views accept gets
  what it got without articulations, at the same cost. accepts() and support() try the poses too. The articulation
  is saved with its template.

  <b>Files (save(), load()).</b> JSON with "format": "vispmorph-template-database" and "version": 1; the
  contours are stored, so images are not needed to query, but a template whose image is named and missing
  is reported (the database no longer matches its source). save() writes a temporary file in the same
  directory and renames it over the target: a crash never leaves a half-written database.

  Not thread safe for modification; const methods may run concurrently.
*/
class vpMorphDatabase
{
public:
  typedef vpMorphShapeDistance::Progress Progress;

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

  std::size_t size() const { return m_templates.size(); }
  bool empty() const { return m_templates.empty(); }
  //! \throw vpMorphException::notFoundError if out of range.
  const vpMorphTemplate &operator[](std::size_t k) const;
  //! \throw vpMorphException::notFoundError if unknown.
  const vpMorphTemplate &operator[](const std::string &name) const;
  //! Index of template \e name, or vpMorphRecognition::npos.
  std::size_t find(const std::string &name) const;
  const std::vector<vpMorphTemplate> &templates() const { return m_templates; }

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
  bool isThresholdManual() const { return m_manual; }
  //! Factor between a template's threshold and the worst distance of its calibration perturbations.
  static double calibrationSlack() { return 1.25; }
  /*!
    How many of the nearest other templates recognize() aligns on a view when the distance's choice shows too
    little of its outline (re-ranking): 8, as each alignment costs about a millisecond.
  */
  static std::size_t rerankCandidates() { return 8; }
  bool isCalibrated() const { return m_calibrated; }

  /*!
    Share, in [0, 1], of template \e k's outline that contour \e c shows: \e c is aligned on the template by a
    similarity (the minimal-work correspondence, fitted robustly, then refined point to edge on the outlines, \e c
    onto the template and the template onto \e c, as an occluder's edge, which only \e c has, drags the first when it
    runs near a template edge; also from that fit turned half a turn, as a nearly symmetric outline can be matched end
    for end), and 512 points spread evenly along the template's outline are counted when they lie within 1/256 of its
    perimeter of the aligned \e c (2 px on a 500-px outline); the best of the four alignments counts. \e mirrored also
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
    servo): its distance (returned in \e distance if not null) is within \e slack x threshold(k), or else \e c
    shows at least minimumSupport() of its outline (its mirror image if that is what the distance matched). Without
    the supportFloor(): the template is already known, and the check should not cost an alignment on every view.
    \throw vpMorphException as support(), and badParameterError on a slack that is not finite and >= 1.
  */
  bool accepts(const vpMorphContour &c, std::size_t k, double slack = 1.0, double *distance = nullptr) const;
  //! within(t) and between(t) of the last calibration, per template (empty before).
  const std::vector<double> &withinDistances() const { return m_within; }
  const std::vector<double> &betweenDistances() const { return m_between; }

  /*!
    Recognises a contour (see the class description). \e prune = false runs the exhaustive reference search.
    \throw vpMorphException::notFoundError on an empty database, badContourError on an empty contour.
  */
  vpMorphRecognition recognize(const vpMorphContour &c, bool prune = true) const;
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
  //! RIGID: the largest share of a view's outline outside its template's region that accepts it (see the class).
  static double maximumOutside() { return 0.1; }
  //! RIGID: the least exact cost by which the best template must beat another acceptable one (see the class).
  static double ambiguity() { return 0.03; }

private:
  vpMorphRecognition search(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                            vpMorphMatcher &matcher) const;
  //! RIGID: search() in two stages (vpMorphRigidSearch), \e prune false comparing every template exactly.
  vpMorphRecognition rigidSearch(const vpMorphContour &c, const vpMorphShapeDistance::Shape &q, bool prune,
                                 vpMorphMatcher &matcher, bool poses) const;
  //! RIGID: the views of every template (with \e poses, the articulated ones' poses too), but template \e skip.
  std::vector<vpMorphRigidView> rigidViews(bool poses, std::size_t skip = vpMorphRecognition::npos) const;
  //! RIGID: the comparison of \e q with template k, its poses too (\e poses), its mirror image too (\e mirrored).
  vpMorphRigidCheck::Result rigidCheck(const vpMorphShapeDistance::Shape &q, std::size_t k, bool mirrored,
                                       bool poses) const;
  //! RIGID: whether a comparison accepts the view as that template (minimumSupport(), nothing outside it).
  bool rigidAccepted(const vpMorphRigidCheck::Result &r) const;
  //! support(), with an articulated template's poses or (\e poses false) its taught view only.
  double support(const vpMorphContour &c, std::size_t k, bool mirrored, bool poses) const;
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
    view). Why not the distance's: it picks an articulated template well but its opening poorly (on 21-vertex views
    of a 32 deg opening it was least at 38-40 deg, and the view showed half of that pose's outline).
  */
  std::size_t overlapPose(const vpMorphContour &c, std::size_t k, vpMorphMatcher &matcher) const;
  //! The contour of template k's view \e pose (npos: the taught one).
  const vpMorphContour &templateView(std::size_t k, std::size_t pose) const;
  void invalidate();
  std::string toJson(const std::string &relativeTo) const;

  vpMorphShapeDistance m_distance;
  std::vector<vpMorphTemplate> m_templates;
  std::vector<vpMorphShapeDistance::Shape> m_shapes;
  std::vector<std::vector<Pose>> m_poses; // per template: its articulated poses (none for a rigid one)
  double m_threshold;
  double m_minSupport = 0.75;
  double m_supportFloor = 0.5;
  bool m_calibrated = false, m_manual = false;
  std::vector<double> m_within, m_between;
};

#endif
