// Shared by the servo tutorials: the vpPlot window of a vpServoMorph run (residuals to the sub-goal chased and the
// commanded camera velocity, per period), what the display test checks in the camera window and in the plot, and the
// three windows of a run on a rendered scene (camera, plot, external view). Header-only, tutorial code, not a library.
#ifndef TUTORIAL_SERVO_WINDOWS_H
#define TUTORIAL_SERVO_WINDOWS_H

#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpRect.h>
#include <visp3/gui/vpPlot.h>
#include <visp3/morph_vs/vpServoMorph.h>

#include "tutorial-display.h"
#include "tutorial-external-view.h"

namespace tutorial
{
class ServoPlot
{
public:
  //! A plot window at (x, y), when the viewer has a window open (else nothing is plotted).
  ServoPlot(Viewer &viewer, int x, int y, const std::string &tag = "plot") : m_tag(tag)
  {
    m_plot = viewer.plot(3, 700, 560, x, y, "vpServoMorph: residuals to the sub-goal, camera velocity", tag);
    if (!m_plot)
      return;
    m_plot->initGraph(0, 1);
    m_plot->setTitle(0, "rotation residual (rad)");
    m_plot->initGraph(1, 2);
    m_plot->setTitle(1, "translation, scale residuals (px)");
    m_plot->setLegend(1, 0, "translation");
    m_plot->setLegend(1, 1, "scale");
    m_plot->initGraph(2, 6);
    m_plot->setTitle(2, "camera velocity (m/s, rad/s)");
    const char *v[] = {"vx", "vy", "vz", "wx", "wy", "wz"};
    for (unsigned int k = 0; k < 6; ++k)
      m_plot->setLegend(2, k, v[k]);
  }
  //! The servo's state after computeControlLaw() at period \e k.
  void add(unsigned int k, const vpServoMorph &servo)
  {
    if (!m_plot)
      return;
    m_plot->plot(0, 0, k, servo.getRotationResidual());
    m_plot->plot(1, 0, k, servo.getTranslationResidual());
    m_plot->plot(1, 1, k, servo.getScaleResidual());
    m_plot->plot(2, k, servo.getCameraVelocity());
  }
  /*!
    What the display test checks: the target drawn in green in the camera window \e cameraTag (of \e width x
    \e height), the status written in yellow in its top-left quarter, and curves in the plot (vpPlot's first colours).
  */
  void expect(Viewer &viewer, const std::string &cameraTag, const vpServoMorph &servo, unsigned int width,
              unsigned int height) const
  {
    viewer.expectContour(cameraTag, "target", servo.getTargetContour().points(), vpColor::green);
    viewer.expectText(cameraTag, "status", vpRect(0, 0, 0.75 * width, 0.25 * height), vpColor::yellow,
                      servo.statusText());
    viewer.expectCurves(m_tag, "residuals and velocity", {vpColor::blue, vpColor::green, vpColor::red});
  }

private:
  vpPlot *m_plot = nullptr;
  std::string m_tag;
};
/*!
  The windows of a vpServoMorph run on a rendered scene, when a display is available: the camera image with
  vpServoMorph::display(), the residuals and the velocity (ServoPlot), and the camera's path seen from outside
  (ExternalView of the object's outline and the tag on their plane, \e cdMo the desired pose).
*/
class ServoWindows
{
public:
  ServoWindows(Viewer &viewer, unsigned int width, unsigned int height, const std::vector<vpPoint> &object,
               const std::vector<vpPoint> &tag, const vpHomogeneousMatrix &cdMo, const std::string &camera)
    : m_viewer(viewer), m_I(height, width, 255), m_Iext(480, 640, 255), m_external(object, tag, cdMo)
  {
    viewer.open(m_I, 0, 0, camera + ": contour (red), sub-goal (orange), target (green)", "camera");
    m_plot.reset(new ServoPlot(viewer, 660, 0));
    viewer.open(m_Iext, 0, 540, "External view: the camera's path (red), desired camera (green)", "external");
  }
  //! The camera image \e I seen at period \e k, the servo's state after it, and the camera's pose (truth).
  void show(const vpImage<unsigned char> &I, const vpServoMorph &servo, unsigned int k, const vpHomogeneousMatrix &cMo)
  {
    if (!m_viewer.on())
      return;
    m_I = I; // vpImage's assignment keeps the window attached
    vpDisplay::display(m_I);
    servo.display(m_I, vpColor::red, vpColor::orange, vpColor::green, 2);
    vpDisplay::flush(m_I);
    m_plot->add(k, servo);
    m_external.add(0, cMo, vpColor::red);
    vpDisplay::display(m_Iext);
    m_external.display(m_Iext);
    vpDisplay::flush(m_Iext);
    m_viewer.pace(40);
  }
  //! The desired pose drawn in the external view, when the servo decides it (an articulated target's placement).
  void setDesiredPose(const vpHomogeneousMatrix &cdMo) { m_external.setDesiredPose(cdMo); }
  //! A click in the camera window: stop.
  bool stopped() const { return m_viewer.clicked(m_I); }
  //! The end: what the display test checks, --save-display, and a click unless -c.
  void end(const vpServoMorph &servo)
  {
    m_plot->expect(m_viewer, "camera", servo, m_I.getWidth(), m_I.getHeight());
    m_viewer.save();
    m_viewer.waitClick(m_I);
  }

private:
  Viewer &m_viewer;
  vpImage<unsigned char> m_I, m_Iext;
  ExternalView m_external;
  std::unique_ptr<ServoPlot> m_plot;
};
} // namespace tutorial

#endif
