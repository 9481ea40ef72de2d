/*!
  \file vpMorphPlanarScene.h
  \brief The benchmark scene: a plane with one object silhouette and an AprilTag beside it, rendered headless.
*/
#ifndef VP_MORPH_PLANAR_SCENE_H
#define VP_MORPH_PLANAR_SCENE_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphJointFile.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

/*!
  \class vpMorphPlanarScene
  \ingroup group_morph_sim
  \brief A plane carrying one object silhouette (from a template image) and an AprilTag 36h11, rendered by
  vpImageSimulator for any camera pose, with optional seeded faults.

  <b>Object frame</b> (the frame of cMo): the plane is z = 0, x and y follow the template image axes (x right,
  y down), z points into the plane, so cMo = [I | (0, 0, 0.5)] views the object upright from 0.5 m, optical axis
  normal to the plane. The silhouette's area centroid is at (x, y) = setObjectPlacement() (default the origin),
  turned by theta about z; its longest bounding-box side in the template measures objectSize() metres.

  <b>Why a ground-truth contour from the template:</b> the object's outline is extracted once from the template
  (vpMorphContourExtractor, pixel centres) and mapped to metres with the same texel-to-plane mapping as
  vpImageSimulator (texel centres 0 .. W-1 span the texture rectangle), so projectedContour() is what a perfect
  extraction of a rendered image would give, whatever the pose.

  <b>Look:</b> light plane (grey 210), dark object (40), tag black 40 on 210. The light-grey occluder (170) is
  a square card lying on the plane over a chosen share of the contour; distractors are small dark rectangles
  away from the object and the tag, the large distractor one dark rectangle; beyond the plane's edge, a dark floor
  (70). Gain, offset and the illumination gradient act before the noise, and clip at 0 and 255 as a sensor does.
  Colour renders use a blue object on a beige plane (same geometry). Each pixel integrates the light over its area,
  as a camera's does: vpImageSimulator's bilinear sampling averages about two texels, so where a pixel spans more
  than two of the object texture's texels (a large texture, a far or low-resolution view) the view is drawn as K x K
  sub-pixels and averaged, K = ceil(texels a pixel / 2) (supersampling(), at most 4).

  <b>Determinism:</b> no clock and no global state: the same scene, faults, pose and frame index give the
  same image bit for bit. The noise generator is seeded with (seed, frame) so a sequence gets fresh noise.
  Distractors and the occluder depend only on the seed and the fault settings.

  \code
  vpMorphPlanarScene scene("data/objects/pliers.png");          // 15 cm pliers, an 8 cm tag beside them
  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 2; f.occludedShare = 0.1; f.seed = 7;
  scene.setFaults(f);
  vpImage<unsigned char> I;
  scene.render(vpHomogeneousMatrix(0, 0, 0.5, 0, 0, vpMath::rad(30)), I);   // cMo
  \endcode
  \sa vpMorphSimRobot, vpMorphTagPoseEstimator, \ref page_simulation
*/
class vpMorphPlanarScene
{
public:
  //! Image faults; everything off by default.
  struct Faults
  {
    double noiseSigma = 0.0;    //!< Std of additive Gaussian noise, grey levels.
    double blurSigma = 0.0;     //!< Std of a Gaussian blur, pixels.
    double gain = 1.0;          //!< Illumination change I' = gain I + offset (applied before the noise).
    double offset = 0.0;        //!< See gain, grey levels.
    double occludedShare = 0.0; //!< Share of the object's contour length hidden by the occluder, [0, 0.9].
    double occluderPosition =
        0.0;                      //!< Where the occluder sits: fraction of the perimeter from contour vertex 0, [0, 1).
    unsigned int distractors = 0; //!< Number of small distractor objects (at most 20).
    unsigned int seed = 0;        //!< Seed of the noise and of the distractor placement.
    //! The object is not drawn (a frame where it is absent: taken away, or hidden from the camera); the tag,
    //! occluder and distractors still are.
    bool objectHidden = false;
    //! Illumination gradient: the gain is multiplied by 1 + gradient r, r in [-1, 1] the position along
    //! gradientAngle (rad, image axes) over the image's half diagonal; [0, 0.9].
    double gradient = 0.0;
    double gradientAngle = 0.0; //!< See gradient.
    //! The plane ends: beyond the line through (planeEdgeX, planeEdgeY) of the object frame whose outward normal
    //! has angle planeEdgeAngle (rad, object frame), a dark floor (grey 70) is seen instead.
    bool planeEdge = false;
    double planeEdgeX = 0.0;     //!< See planeEdge (m).
    double planeEdgeY = 0.0;     //!< See planeEdge (m).
    double planeEdgeAngle = 0.0; //!< See planeEdge (rad).
    //! A dark distractor larger than the object: a rectangle of largeDistractorArea m^2 (0: none), aspect
    //! largeDistractorAspect (>= 1), centred at (largeDistractorX, largeDistractorY) of the object frame, its long
    //! side at largeDistractorAngle (rad).
    double largeDistractorArea = 0.0;
    double largeDistractorAspect = 1.5; //!< See largeDistractorArea.
    double largeDistractorX = 0.0;      //!< See largeDistractorArea (m).
    double largeDistractorY = 0.0;      //!< See largeDistractorArea (m).
    double largeDistractorAngle = 0.0;  //!< See largeDistractorArea (rad).
  };

  /*!
    \param objectImage : template image (dark object on light background, e.g. data/objects/pliers.png).
    \param objectSize : longest side of the object's bounding box, metres (> 0).
    \param tagId : AprilTag 36h11 id.
    \param tagSize : black-border side of the tag, metres (> 0). 8 cm by default: the tag measures the truth, and
    a smaller tag's tilt is poorly observable at 0.5 m from 0.1 px corner errors.
    \throw vpMorphException notFoundError for a missing file, badImageError for an image without object,
    badParameterError for non-positive or NaN sizes.
  */
  explicit vpMorphPlanarScene(const std::string &objectImage, double objectSize = 0.15, int tagId = 0,
                              double tagSize = 0.08);

  //! Where setReferenceImage() puts the object's texture against the reference's.
  enum ReferencePlacement {
    SHARED_FRAME, //!< As drawn: one texture frame for both (a deformed variant's undeformed part on the template's).
    BEST_OVERLAP  //!< Moved (turned and shifted in the image) to where its silhouette overlaps the reference's most.
  };

  /*!
    Takes the object frame (origin at the outline centroid, axes of the image) and the scale (objectSize over the
    longest side) from another image of the same size, instead of from the object image itself, so that a deformed
    variant is placed against its template rather than by its own centroid and size (which move with the bend).
    - SHARED_FRAME: the object's texture keeps its place in the shared texture frame, so the pose that aligns the
      part drawn undeformed (a bent key's bow) with the template's is the
      template's pose. Which part stayed still is a choice of the drawing, not visible in an image: bending the
      blade about the bow or the bow about the blade gives the same shape.
    - BEST_OVERLAP: the object's texture is moved by the rigid motion under which its silhouette covers the most
      of the reference's (referenceAlignment(); exact overlap of the two measured edge outlines, best of starts
      +-20 deg apart by 2.5 deg): the pose that lays the deformed object on its template as well as a rigid
      placement can, which depends on the shapes only. A shape with two equally good placements (pliers opened
      symmetrically: either arm) gets the first one found; give such a shape its placements with
      setReferenceAlignment().
    \throw vpMorphException notFoundError or ioError for a missing or unreadable image, badImageError for an image
    without object, badParameterError for an image of another size.
  */
  void setReferenceImage(const std::string &referenceImage, ReferencePlacement placement = SHARED_FRAME);
  //! The motion of the object's texture (template pixels) set by setReferenceImage(): identity unless BEST_OVERLAP.
  const vpMorphRigidTransform &referenceAlignment() const { return m_texAlign; }
  /*!
    Places the object's texture by \e align (template pixels, after setReferenceImage(), whose frame it keeps), and
    records \e alternatives, equally good placements. Why: an articulated object has no best rigid placement on its
    template, but one per part: an opened pliers laid by either arm on the closed one's (the turns its drawing
    gave them). Its largest overlap lies tenths of a degree off either, where no part is where it was taught.
  */
  void setReferenceAlignment(const vpMorphRigidTransform &align,
                             const std::vector<vpMorphRigidTransform> &alternatives = {});
  /*!
    The alternatives of setReferenceAlignment(), each as the in-plane motion W of the object frame that takes the
    object as placed to it: for a desired pose cdMo, cdMo * W is an equally good one. Empty by default.
  */
  std::vector<vpHomogeneousMatrix> alternativePlacements() const;
  /*!
    The in-plane motion W of the object frame that takes the object as placed to the object placed by \e align
    (template pixels, as setReferenceAlignment()): for a desired pose cdMo, cdMo * W sees the object placed so.
  */
  vpHomogeneousMatrix placementOf(const vpMorphRigidTransform &align) const;
  //! Places the object frame origin (the outline centroid, of the reference image if set) at (x, y), turned by theta
  //! (rad) about z.
  void setObjectPlacement(double x, double y, double theta);
  /*!
    Places the tag centre at (x, y) of the object frame (tag axes = object axes). By default it sits on the
    side of the object where it stays closest to the object's centroid, 1 cm clear of the silhouette, so it
    remains in view at the desired pose whatever the in-plane rotation.
  */
  void setTagPlacement(double x, double y);
  /*!
    Places the tag where it fits in the view from \e cMo: for each size of \e tagSizes in turn (black-border sides,
    m, largest first), every direction around the object 15 deg apart, the nearest centre 1 cm clear of the
    silhouette (as by default); the nearest to the object's centroid whose whole texture (quiet zone included) is in
    view \e margin pixels from the border. Returns false, the tag left as it was, when no size fits.
    \throw vpMorphException::badParameterError for a size that is not finite and > 0, or an invalid cMo.
  */
  bool placeTagInView(const vpHomogeneousMatrix &cMo, const std::vector<double> &tagSizes, double margin = 10.0);
  //! Changes the tag's black-border side (m, > 0); its placement is kept (automatic placement is redone).
  void setTagSize(double tagSize);
  //! Tag centre's x in the object frame, m.
  double tagX() const { return m_tagX; }
  //! Tag centre's y in the object frame, m.
  double tagY() const { return m_tagY; }
  //! The corners of the tag's whole texture (quiet zone included) in the object frame.
  std::vector<vpPoint> tagTextureCorners3D() const;
  //! Sets the image faults (see Faults).
  void setFaults(const Faults &faults);
  //! The image faults.
  const Faults &faults() const { return m_faults; }
  //! Camera intrinsics and image size used by render() (default: defaultCamera(), 640 x 480).
  void setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height);
  //! Camera intrinsics of render().
  const vpCameraParameters &camera() const { return m_cam; }
  //! Image width of render() (px).
  unsigned int imageWidth() const { return m_width; }
  //! Image height of render() (px).
  unsigned int imageHeight() const { return m_height; }
  //! The benchmark camera: px = py = 800, u0 = 320, v0 = 240, no distortion.
  static vpCameraParameters defaultCamera() { return vpCameraParameters(800.0, 800.0, 320.0, 240.0); }

  /*!
    Sub-pixels a side render() draws each pixel with from cMo (see the description): 1 unless a pixel spans more than
    two texels of the object's texture somewhere on it.
  */
  unsigned int supersampling(const vpHomogeneousMatrix &cMo) const;
  //! Largest supersampling(): 16 draws a pixel bound a render's cost (beyond 8 texels a pixel, some aliasing stays).
  static unsigned int maxSupersampling() { return 4; }
  //! Renders the view from cMo (grey levels), with the faults; \e frame selects the noise realisation.
  void render(const vpHomogeneousMatrix &cMo, vpImage<unsigned char> &I, unsigned int frame = 0) const;
  //! Same in colour.
  void render(const vpHomogeneousMatrix &cMo, vpImage<vpRGBa> &I, unsigned int frame = 0) const;

  //! The object's outline in the object frame (metres, z = 0), polygon vertices.
  std::vector<vpPoint> objectContour3D() const;
  //! The object's outline projected in the image for cMo (pixels): the ground truth of contour extraction.
  vpMorphContour projectedContour(const vpHomogeneousMatrix &cMo) const;
  /*!
    True when the whole object outline projects inside the image, at least \e margin pixels from the border
    (and in front of the camera): the benchmark's "target never out of view" criterion, from the truth.
  */
  bool objectInView(const vpHomogeneousMatrix &cMo, double margin = 0.0) const;
  //! Same for the four tag corners.
  bool tagInView(const vpHomogeneousMatrix &cMo, double margin = 0.0) const;
  //! The four corners of the tag's black border in the object frame, in vpDetectorAprilTag's 3-D point order.
  std::vector<vpPoint> tagCorners3D() const;
  //! A point of the object's texture (template pixels, as in the object image) projected in the image for cMo.
  vpImagePoint projectedTexel(double tx, double ty, const vpHomogeneousMatrix &cMo) const;
  //! The four tag corners projected in the image for cMo (pixels).
  std::vector<vpImagePoint> projectedTagCorners(const vpHomogeneousMatrix &cMo) const;
  //! Pose of the tag frame in the object frame (a pure translation).
  vpHomogeneousMatrix oMt() const;
  //! The tag's 36h11 id.
  int tagId() const { return m_tagId; }
  //! The tag's black-border side (m).
  double tagSize() const { return m_tagSize; }
  //! Longest side of the object's bounding box (m).
  double objectSize() const { return m_objectSize; }
  //! Metres per template pixel.
  double metresPerTexel() const { return m_metresPerTexel; }
  //! An estimator of cMo from the tag in images of this scene; keep it for a whole run (its detector is built once).
  vpMorphTagPoseEstimator tagPoseEstimator() const;

  /*!
    The object's silhouette as the camera at \e cMo sees it, to teach a template: rendered (with the faults), the tag
    found by the detector and masked when it is in view (vpMorphTagPoseEstimator::silhouette()), extracted.
    \throw vpMorphException::badImageError when the tag is in view but not found, or no object is seen.
  */
  vpMorphContour silhouette(const vpHomogeneousMatrix &cMo) const;
  /*!
    The articulation of the object of this scene (the template image that \e joint's parts are drawn over, see
    vpMorphJointFile) as the camera at \e cMo sees it: each part alone in this scene's layout (object size and
    placement, tag, camera; no faults) and silhouette() of it, the pin projected, and the range mirrored when the
    camera sees the texture's axes mirrored. With the template's silhouette() at the same pose it makes an articulated
    template (vpMorphTemplate::setArticulation()).
    \throw vpMorphException as silhouette() and vpMorphJointFile::articulation(); badParameterError when a part's
    image is not of the object image's size.
  */
  vpMorphArticulation articulation(const vpMorphJointFile &joint, const vpHomogeneousMatrix &cMo) const;

  /*!
    Share of the object's contour length actually hidden by the occluder (measured on the outline densely
    sampled every 0.5 mm); 0 without occluder. Close to, but not exactly, Faults::occludedShare.
  */
  double occludedShare() const;
  //! Corners of the occluder square in the object frame (empty without occluder).
  std::vector<vpPoint> occluderCorners3D() const;
  //! Corners of each distractor rectangle in the object frame (the large distractor last, when there is one).
  std::vector<std::vector<vpPoint>> distractorCorners3D() const;
  //! Area of the object's outline on the plane, m^2.
  double objectArea() const;
  //! Largest Faults::largeDistractorArea, m^2: about all the default camera sees of the plane at 0.5 m.
  static double maxDistractorArea() { return 0.1; }

private:
  struct Patch
  {
    std::vector<vpPoint> corners; // top-left, top-right, bottom-right, bottom-left (object frame)
    int kind;                     // 0 object, 1 tag, 2 occluder, 3 distractor, 4 floor beyond the plane's edge
  };
  void updateLayout();
  static void textureFrame(const vpMorphContour &c, double objectSize, double &cx, double &cy, double &metresPerTexel);
  std::vector<Patch> patches() const;
  // A texture point (template pixels) on the plane: referenceAlignment(), the texture frame, the placement.
  vpPoint texelOnPlane(double tx, double ty) const;
  vpPoint texelOnPlane(double tx, double ty, const vpMorphRigidTransform &align) const;
  template <typename T> void renderT(const vpHomogeneousMatrix &cMo, vpImage<T> &I, unsigned int frame) const;

  std::string m_path;
  double m_objectSize, m_tagSize;
  int m_tagId;
  vpImage<unsigned char> m_texture, m_tag;
  vpMorphContour m_texContour;     // the object's outline in template pixels (with its edge outline)
  double m_texCx = 0, m_texCy = 0; // outline centroid in template pixels
  double m_metresPerTexel = 0;
  vpMorphRigidTransform m_texAlign;                     // texture motion of setReferenceImage(BEST_OVERLAP)
  std::vector<vpMorphRigidTransform> m_texAlternatives; // equally good others (setReferenceAlignment())
  double m_objX = 0, m_objY = 0, m_objTheta = 0;
  bool m_tagAuto = true;
  double m_tagX = 0, m_tagY = 0;
  Faults m_faults;
  vpCameraParameters m_cam;
  unsigned int m_width = 640, m_height = 480;
  // Derived from the faults and placement.
  std::vector<vpPoint> m_occluder;
  std::vector<std::vector<vpPoint>> m_distractors;
  double m_occludedShare = 0.0;
};

#endif
