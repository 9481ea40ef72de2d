/*!
  \file vpMorphTagPoseEstimator.h
  \brief Object pose measured from an image through an AprilTag: the second, independent ground truth.
*/
#ifndef VP_MORPH_TAG_POSE_ESTIMATOR_H
#define VP_MORPH_TAG_POSE_ESTIMATOR_H

#include <memory>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphTagPoseEstimator
  \ingroup group_morph_sim
  \brief Estimates the object pose cMo from the AprilTag 36h11 lying in the object plane, with vpDetectorAprilTag.

  Why: the simulator knows the exact pose, but a real bench only has what a camera sees. Reporting both, and
  checking that they agree, shows that the truth used to score controllers is also measurable. The detector is
  set with setZAlignedWithCameraAxis(true) so that the tag frame has z along the viewing direction, like the
  object frame of the scenes (x right, y down, z into the plane); the object pose is cMo = cMt * oMt^-1.

  \code
  vpMorphTagPoseEstimator tag(scene.tagId(), scene.tagSize(), scene.oMt(), scene.camera());
  vpHomogeneousMatrix cMo;
  std::vector<vpImagePoint> corners;
  if (tag.estimate(I, cMo, &corners)) {
    vpMorphContour c = vpMorphTagPoseEstimator::silhouette(I, corners);   // the object, tag masked
  }
  \endcode
  \sa vpMorphPlanarScene, \ref page_simulation
*/
class vpMorphTagPoseEstimator
{
public:
  /*!
    \param tagId : the 36h11 id to look for (other tags are ignored).
    \param tagSize : side of the black border square, metres.
    \param oMt : pose of the tag frame (centre of the tag) in the object frame.
    \param cam : camera intrinsics (no distortion).
  */
  vpMorphTagPoseEstimator(int tagId, double tagSize, const vpHomogeneousMatrix &oMt, const vpCameraParameters &cam);

  /*!
    The detector is built once per estimator and shared by its copies (calls on copies are serialised):
    give each thread its own estimator to detect in parallel.

    Detects the tag and returns true with the object pose \e cMo (and optionally the four tag corners in
    pixels, in the detector's order) when the tag is found; false otherwise (cMo untouched).
  */
  bool estimate(const vpImage<unsigned char> &I, vpHomogeneousMatrix &cMo,
                std::vector<vpImagePoint> *corners = nullptr) const;

  /*!
    Paints the detected tag's black square (its \e corners, grown by \e margin pixels) with the grey level of
    its white quiet zone, which is left as it is: the quiet zone may touch the object, and painting it would eat
    into the silhouette. Why: an 8 cm tag is a larger dark
    region than most objects, so an automatic silhouette extraction (largest region) would take the tag; a real bench
    removes it the same way, from the detector's corners, never from the simulator's truth. Throws vpMorphException
    unless there are 4 corners.
  */
  static void maskTag(vpImage<unsigned char> &I, const std::vector<vpImagePoint> &corners, double margin = 2.0);
  /*!
    The object's silhouette in a scene image, as every controller of a scene gets it: the tag masked with
    maskTag() when its 4 detected \e corners are given (none: nothing is masked), then the largest object's
    polygon by vpMorphContourExtractor::extractJoined(): the pieces an occluder cut from it are joined back (a
    single piece keeps its measured region): the largest piece alone may look like another object. Empty when the
    image shows no object (the
    extractor's bad-image errors), so that a control loop can hold or stop instead of unwinding. \e extractionMs,
    when given, receives the CPU time of the extraction alone (vpMorphThreadCpuClock): masking the tag is an artefact
    of the scene.
  */
  static vpMorphContour silhouette(const vpImage<unsigned char> &I, const std::vector<vpImagePoint> &corners,
                                   double *extractionMs = nullptr);
  /*!
    silhouette() of the object that continues \e previous, its silhouette in the last image
    (vpMorphContourExtractor::extractJoined(I, previous)): a larger region elsewhere is not taken for it. Empty when
    no object region lies where \e previous was. An empty \e previous gives silhouette(I, corners).
  */
  static vpMorphContour silhouette(const vpImage<unsigned char> &I, const std::vector<vpImagePoint> &corners,
                                   const vpMorphContour &previous, double *extractionMs = nullptr);
  /*!
    The outlines the object may have in a first image (vpMorphContourExtractor::extractCandidates()), the tag masked
    as by silhouette(); empty when the image shows no object. For vpMorphDatabase::recognize() on a list.
  */
  static std::vector<vpMorphContour> silhouetteCandidates(const vpImage<unsigned char> &I,
                                                          const std::vector<vpImagePoint> &corners,
                                                          double *extractionMs = nullptr);

  /*!
    Difference between two poses of the object seen from a camera: distance between the object origins (metres,
    in the camera frame) and angle of the relative rotation (radians, norm of theta-u). Measured at the object
    (not as a camera displacement) so that a rotation error is not amplified by the viewing distance.
  */
  static void poseDifference(const vpHomogeneousMatrix &aMo, const vpHomogeneousMatrix &bMo, double &translation,
                             double &rotation);

  //! The 36h11 id looked for.
  int tagId() const { return m_tagId; }
  //! Side of the tag's black border square (m).
  double tagSize() const { return m_tagSize; }
  //! Pose of the tag in the object frame.
  const vpHomogeneousMatrix &oMt() const { return m_oMt; }

private:
  struct Detector; // vpDetectorAprilTag built once (building the 36h11 decoder costs ~20 ms), behind a mutex
  std::shared_ptr<Detector> m_detector;
  int m_tagId;
  double m_tagSize;
  vpHomogeneousMatrix m_oMt;
  vpCameraParameters m_cam;
};

#endif
