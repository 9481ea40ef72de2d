/*!
  \file vpMorphViewAlignment.h
  \brief What vpMorphViewAligner measured: the similarity from the current view to its goal, how sure it is, and
  which model of the view explains it.
*/
#ifndef VP_MORPH_VIEW_ALIGNMENT_H
#define VP_MORPH_VIEW_ALIGNMENT_H

#include <limits>
#include <utility>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>

/*!
  \class vpMorphViewAlignment
  \ingroup group_morph_vs
  \brief Result of vpMorphViewAligner::align() (value type, public fields as it only carries data).

  The transform maps the current view onto the goal in normalised image coordinates (x = X/Z, y = Y/Z), about the
  current view's centroid. Its uncertainty is the covariance of \f$(\theta, t_x, t_y, \ln s)\f$ (radians, normalised
  units, log-scale) at the residuals' robust scale.

  <b>Models</b> (vpMorphViewAligner, the test on the fit's residuals):
  - RIGID: every sample of the view lies on the goal's edges within the noise (no run of outliers beyond what the
    noise makes), up to a similarity, or up to a homography (perspective: the goal seen tilted);
  - PART_HIDDEN: samples beyond the cut lie inside the goal's region and outnumber those outside (an occluder only
    hides: its edge crosses the object);
  - PART_BENT: samples beyond the cut lie outside the goal's region and outnumber those inside (a part turned away);
  - UNEXPLAINED: less than half of the view's region lies on the goal's, or less than half of the goal's outline on
    the view's, or the residuals' robust scale is beyond what edge noise makes: the part laid on the goal is not the
    larger part of the object (another shape, a deformation no rigid placement explains, a fit run off to a point).

  \code
  vpMorphViewAlignment a = aligner.align(current);
  if (a.explained() && a.rotationDeviation() < 1e-3)
    std::cout << vpMorphViewAlignment::modelName(a.model) << ": theta " << a.transform.theta() << std::endl;
  \endcode
  \sa vpMorphViewAligner, \ref page_servo_measurement
*/
class vpMorphViewAlignment
{
public:
  //! How the view relates to the goal (see the class description).
  enum Model {
    RIGID,       //!< the view is the goal seen again, within the noise
    PART_HIDDEN, //!< part of the goal is hidden
    PART_BENT,   //!< part of the view lies out of the goal
    UNEXPLAINED  //!< fewer than half of the view lies on the goal
  };
  //! A short name ("rigid", "part hidden"...).
  static const char *modelName(Model m);

  vpMorphRigidTransform transform; //!< current -> goal, normalised coordinates
  //! Covariance of (theta, tx, ty, ln s), 4 x 4; infinite diagonal when the inliers do not determine them.
  vpMatrix covariance = vpMatrix(4, 4, 0.0);
  Model model = UNEXPLAINED; //!< which model explains the residuals
  double sigmaPx = 0.0;      //!< robust scale of the residuals, pixels
  double edgeOffsetPx = 0.0; //!< the goal's edges moved outwards by this to lie on the view's (pixels)
  double inlierShare = 0.0;  //!< share of the view's samples on the goal's edges, [0, 1]
  double overlapShare = 0.0; //!< share of the view's region inside the goal's once laid by the transform, [0, 1]
  double goalCoverage = 0.0; //!< share of the goal's outline on the view's edges, [0, 1]
  double outsideShare = 0.0; //!< share beyond the cut outside the goal's region
  double insideShare = 0.0;  //!< share beyond the cut inside the goal's region
  //! The view is the goal seen tilted: a homography explained it (the model is the test's under it), no similarity
  //! did as well (the transform is the homography's own).
  bool perspective = false;
  bool fromCorrespondence = false; //!< the fit started from the correspondence (no usable warm start)
  double work = std::numeric_limits<double>::quiet_NaN();   //!< work of the correspondence, when it was run
  double margin = std::numeric_limits<double>::quiet_NaN(); //!< its margin after a full search (NaN: tracked)

  //! Standard deviation of the rotation (rad).
  double rotationDeviation() const;
  //! Standard deviation of the translation along its worse axis (normalized units).
  double translationDeviation() const;
  //! Standard deviation of the relative scale.
  double scaleDeviation() const;
  //! The view is explained: the larger part of it lies on the goal within the noise.
  bool explained() const { return model != UNEXPLAINED; }
  /*!
    What a display draws of the alignment: from about \e count vertices of \e view (the aligned view, normalised
    coordinates) to where the transform lays them, both in pixels of \e cam. None when the view is unexplained.
  */
  std::vector<std::pair<vpImagePoint, vpImagePoint>> lines(const vpMorphContour &view, const vpCameraParameters &cam,
                                                           std::size_t count = 24) const;
};

#endif
