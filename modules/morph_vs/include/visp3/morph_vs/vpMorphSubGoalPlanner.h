/*!
  \file vpMorphSubGoalPlanner.h
  \brief The sub-goals of the morph servo: the sequence from the current view to the target, its camera path and
  its joints.
*/
#ifndef VP_MORPH_SUBGOAL_PLANNER_H
#define VP_MORPH_SUBGOAL_PLANNER_H

#include <cstddef>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>
#include <visp3/morph/vpMorphRigidTransform.h>

/*!
  \class vpMorphSubGoalPlanner
  \ingroup group_morph_vs
  \brief Plans the successive goals (sub-goals) of the morph servo from one view of the object to the target.

  plan() takes the current view, the target and the similarity that lays the view on the target (normalised
  coordinates, from vpMorphViewAligner), and makes the sequence:
  - <b>rigid frames</b>: the current view as seen from evenly spaced camera poses on the way to the rectified one,
    then the target. With CAMERA_STRAIGHT_LINE (default) the poses lie on the straight line from the current camera
    to the one the similarity rectifies it to (the rotation about the optical axis shared evenly): the shortest
    camera path. With ABOUT_OBJECT_CENTROID (the paper's image-space interpolation) the view turns about its
    centroid and moves on a straight line in the image: the camera travels on an arc about the object.
  - <b>deformation frames</b> (the paper's Eq. 1, setDeformationFrames(true)): after the rigid frames, the rectified
    view interpolated vertex by vertex to the target over a correspondence. Off by default: no camera motion
    produces them (a bent or hidden part changes the outline, not the pose), so the rigid frames end on the target.

  Each sub-goal carries the depth of the plane at which it is seen (the current depth at the first, the target's
  at the last), and the similarity from the planned view to it, so that the fit to one sub-goal starts the fit to the
  next (getStep()).

  <b>Joints.</b> The turn about the optical axis can be planned either way round: the short way unless the joints'
  end, predicted to first order from setJointState() (q + eJe^+ eVc times the planned camera displacement), comes
  within getJointMargin() of a limit where the long way's does not. Near half a turn the two ways differ by less than
  the rotation's estimate, and an arm's wrist may allow only one of them.

  \code
  vpMorphSubGoalPlanner planner;
  planner.setSubGoalCount(10);
  planner.plan(current, target, currentToTarget, cam, Zd, eMc);   // currentToTarget: vpMorphViewAligner's
  for (std::size_t k = 0; k < planner.size(); ++k) { const vpMorphContour &g = planner.getSubGoal(k); }
  \endcode
  \sa vpServoMorph, \ref page_method, \ref page_design_servo
*/
class vpMorphSubGoalPlanner
{
public:
  //! The camera path of the rigid frames.
  enum RigidPath {
    CAMERA_STRAIGHT_LINE, //!< the camera on a straight line, turning evenly (default)
    ABOUT_OBJECT_CENTROID //!< the paper's image-space interpolation about the view's centroid
  };

  //! 10 sub-goals on the straight camera path, no deformation frames, no joints.
  vpMorphSubGoalPlanner() = default;

  //! Sub-goals per plan (0: the target only). \throw nothing.
  void setSubGoalCount(std::size_t n) { m_n = n; }
  //! Sub-goals per plan.
  std::size_t getSubGoalCount() const { return m_n; }
  //! The camera path of the rigid frames (default CAMERA_STRAIGHT_LINE).
  void setRigidPath(RigidPath p) { m_path = p; }
  //! The camera path of the rigid frames.
  RigidPath getRigidPath() const { return m_path; }
  //! The paper's deformation frames after the rigid ones (default false).
  void setDeformationFrames(bool on) { m_deformation = on; }
  //! Whether the deformation frames follow the rigid ones.
  bool getDeformationFrames() const { return m_deformation; }
  /*!
    The robot's joints: \e eJe at the joint positions \e q, and their limits (infinite: none). Read by plan().
    \throw vpMorphException::badParameterError if eJe is not 6 x n for n positions and limits, or a position is NaN
    or outside its limits.
  */
  void setJointState(const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin, const vpColVector &qMax);
  //! True after setJointState().
  bool hasJointState() const { return m_q.size() > 0; }
  //! eJe as last set.
  const vpMatrix &getJointJacobian() const { return m_eJe; }
  //! q as last set.
  const vpColVector &getJointPositions() const { return m_q; }
  //! The joints' lower limits.
  const vpColVector &getJointMin() const { return m_qMin; }
  //! The joints' upper limits.
  const vpColVector &getJointMax() const { return m_qMax; }
  //! Share of a joint's range kept clear of its limits at a plan's predicted end (3 %: 21.6 deg of a +-360 deg wrist).
  static double getJointMargin() { return 0.03; }

  /*!
    Plans from \e current to \e target (pixels) given the similarity \e currentToTarget (normalised coordinates),
    the camera intrinsics, the target's depth \e Zd and the hand-eye estimate (to predict the joints).
    \e correspondence is needed only with deformation frames.
    \throw vpMorphException on contours the morph cannot use.
  */
  void plan(const vpMorphContour &current, const vpMorphContour &target, const vpMorphRigidTransform &currentToTarget,
            const vpCameraParameters &cam, double Zd, const vpHomogeneousMatrix &eMc,
            const vpMorphCorrespondence &correspondence = vpMorphCorrespondence());
  //! Forgets the plan.
  void clear();

  //! Number of sub-goals of the plan.
  std::size_t size() const { return m_goals.size(); }
  //! True without a plan.
  bool empty() const { return m_goals.empty(); }
  //! Sub-goal k, in pixels (the last is the target).
  const vpMorphContour &getSubGoal(std::size_t k) const { return m_goals[k]; }
  //! All sub-goals, in pixels.
  const std::vector<vpMorphContour> &getSubGoals() const { return m_goals; }
  //! The depth of the object's plane (its centroid) at which sub-goal k is seen.
  double getDepth(std::size_t k) const { return m_depths[k]; }
  //! The similarity from the planned view to sub-goal k (normalised coordinates; the target's: currentToTarget).
  const vpMorphRigidTransform &getPlannedMap(std::size_t k) const { return m_maps[k]; }
  //! The similarity from sub-goal k to sub-goal k + 1 (normalised), to start the fit to the next from the last one.
  vpMorphRigidTransform getStep(std::size_t k) const;
  //! The number of rigid frames of the plan (the target excluded).
  std::size_t getRigidFrameCount() const { return m_rigid; }
  //! True when the plan turns about the optical axis the long way round (its joints could not go the short way).
  bool isLongWay() const { return m_longWay; }
  //! The joints' predicted end of the plan (empty without setJointState()).
  const vpColVector &getJointEnd() const { return m_qEnd; }
  //! The camera displacement the plan's similarity stands for, at depth Z, with projection scale k (Eq. 5-10).
  static vpHomogeneousMatrix cameraDisplacement(const vpMorphRigidTransform &T, double Z, double k = 1.0);

private:
  vpColVector jointEnd(const vpMatrix &eJeInv, const vpHomogeneousMatrix &eMc, const vpHomogeneousMatrix &cMcp,
                       double turn) const;
  bool nearJointLimit(const vpColVector &q) const;

  std::size_t m_n = 10;
  RigidPath m_path = CAMERA_STRAIGHT_LINE;
  bool m_deformation = false;
  vpMatrix m_eJe;
  vpColVector m_q, m_qMin, m_qMax, m_qEnd;
  std::vector<vpMorphContour> m_goals;
  std::vector<double> m_depths;
  std::vector<vpMorphRigidTransform> m_maps;
  std::size_t m_rigid = 0;
  bool m_longWay = false;
};

#endif
