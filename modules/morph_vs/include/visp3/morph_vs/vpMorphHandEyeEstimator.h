/*!
  \file vpMorphHandEyeEstimator.h
  \brief Online estimate of the hand-eye transform eMc from commanded and observed moves (the paper's calibration).
*/
#ifndef VP_MORPH_HAND_EYE_ESTIMATOR_H
#define VP_MORPH_HAND_EYE_ESTIMATOR_H

#include <cmath>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>

/*!
  \class vpMorphHandEyeEstimator
  \ingroup group_morph_vs
  \brief Updates an estimate of eMc, and of the scale of the image projection, from each pair
  (commanded end-effector move eMe', camera move cMc' observed in the image), with averaging.

  <b>Model.</b> The true hand-eye transform is written eMc = eMc0 * Y, with eMc0 the initial estimate and Y the
  correction. If the robot executes eMe', the camera moves by cMc' = eMc^-1 eMe' eMc, so with
  A = eMc0^-1 eMe' eMc0 (the commanded move as the initial estimate sees it) and B = cMc' (observed):
  A Y = Y B, the classical hand-eye equation.

  <b>What is observable.</b> The paper's task moves the camera parallel to a planar object (translations and
  rotations about the optical axis) and observes a 2-D similarity of the image. Its moves only see the planar
  part of Y: the rotation psi about the optical axis and the in-plane offset (t1, t2). Tilt and offset along
  the axis are unobservable from such moves and are kept from eMc0. The image translation is also off by the
  error of the intrinsics (px/Z, py/Z): the observed translation is the true one divided by a scale k.

  <b>Estimator.</b> With the planar parts of A (angle phi, translation ta) and B (translation tb), A Y = Y B gives
  \f[ (R(\phi) - I)\, t - k R(\psi)\, t_b = -t_a, \f]
  two equations that are linear in \f$u = (t_1, t_2, k\cos\psi, k\sin\psi)\f$. The estimate is their least-squares
  solution over all moves so far (the averaging), with exponential forgetting so that it can follow a drift:
  each move multiplies the past normal equations by forgetting()^w, w = min(1, e / e_ref), e the squared norm of
  its equations and e_ref a tenth of the largest e so far (information-weighted: the tiny moves of the final
  convergence do not wash out the large moves that determined the estimate). The normal equations start
  from a ridge prior towards Y = I, k = 1 (weight priorWeight()), forgotten with the data, which only decides
  what the moves leave unobserved. Then \f$\psi = \mathrm{atan2}(u_4, u_3)\f$, \f$k = |(u_3, u_4)|\f$ and eMc = eMc0 *
  Y(psi, t1, t2). Rotations give t, translations give psi and k: a morph sequence (rigid frames then deformation) has
  both.

  <b>Outliers.</b> A move whose observation the current estimate explains worse than the error it could have (the
  residual of its equations beyond twice |ta| plus |phi| x 0.1 m) is not added (rejectedMoveCount()): one view
  measured wrong would otherwise pull k towards 0, after which the servo barely moves and never corrects it.

  \code
  vpMorphHandEyeEstimator estimator(eMc_guess);
  estimator.addMove(eMe_commanded, cMc_observed);  // after each move: commanded, and seen in the image
  vpHomogeneousMatrix eMc = estimator.get_eMc();   // the planar part corrected
  double k = estimator.translationScale();         // the projection's scale error
  \endcode
  \sa \ref page_design_servo
*/
class vpMorphHandEyeEstimator
{
public:
  //! Starts from the estimate \e eMc0.
  explicit vpMorphHandEyeEstimator(const vpHomogeneousMatrix &eMc0 = vpHomogeneousMatrix());

  //! Restarts from \e eMc0 (forgets all moves).
  void reset(const vpHomogeneousMatrix &eMc0);
  /*!
    Adds one move: eMe' commanded (executed) in the end-effector frame, cMc' observed from the image with the
    current projection estimate (translation before the scale correction).
  */
  void addMove(const vpHomogeneousMatrix &eMe, const vpHomogeneousMatrix &cMc);

  //! Current estimate of eMc.
  vpHomogeneousMatrix get_eMc() const { return m_eMc; }
  //! The initial estimate.
  vpHomogeneousMatrix get_eMc0() const { return m_eMc0; }
  /*!
    Estimated scale k: true camera translation in the image plane = k * observed one (1 if intrinsics are right).
    Kept in [1/2, 2]: intrinsics given for a calibrated camera are not off by more than a factor of 2, and a view the
    planar model does not fit (seen tilted) would otherwise pull k towards 0.
  */
  double translationScale() const { return std::hypot(m_u[2], m_u[3]); }
  //! Number of moves added.
  unsigned int moveCount() const { return m_moves; }
  //! Moves rejected as outliers: the current estimate left more of the observed camera translation unexplained than
  //! twice the commanded one plus what the move's rotation does to a 0.1 m offset (see addMove()).
  unsigned int rejectedMoveCount() const { return m_rejected; }

  //! The forgetting factor.
  double forgetting() const { return m_forget; }
  //! Forgetting factor in (0, 1] applied to the past moves at each new one (default 0.95).
  void setForgetting(double f);
  //! The ridge weight towards the initial estimate (m^2).
  double priorWeight() const { return m_prior; }
  //! Ridge weight towards the initial estimate, in m^2 (default 1e-6: one 1 mm move outweighs it). Only
  //! before the first move (it restarts the estimator).
  void setPriorWeight(double w);

private:
  void solve();

  static constexpr double kMaxTranslationScale = 2.0; // k is kept in [1/2, 2] (see translationScale())
  static constexpr double kOutlierMoves = 2.0;        // residual allowed per unit of commanded translation
  static constexpr double kOutlierOffset = 0.1;       // m: offset error the residual allows per radian of rotation

  vpHomogeneousMatrix m_eMc0, m_eMc; // m_eMc: eMc0 * Y(m_u), kept from solve()
  vpMatrix m_M;                      // 4x4 data normal matrix
  vpColVector m_r;                   // data right-hand side
  vpColVector m_u;                   // current solution (t1, t2, k cos psi, k sin psi)
  double m_forget = 0.95, m_prior = 1e-6, m_eRef = 0.0;
  unsigned int m_moves = 0, m_rejected = 0;
};

#endif
