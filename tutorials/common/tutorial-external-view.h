// Shared by the tutorials: an external view of a servo, the object's plane and the camera's path seen by a virtual
// camera placed above the plane and to the side, for a window or a picture. Header-only, tutorial code, not a library.
#ifndef TUTORIAL_EXTERNAL_VIEW_H
#define TUTORIAL_EXTERNAL_VIEW_H

#include <cmath>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpRotationMatrix.h>

namespace tutorial
{
/*!
  The scene from outside: the object's outline and the tag on their plane (object frame: x right, y down, z into the
  plane), the desired camera (green), and one or more camera paths, each with its camera where it is now. The view
  looks at the point \e height metres above the object (default: 0.6 of the way to the desired camera), from \e distance
  metres away, raised by \e elevation above the plane and turned by \e azimuth about its normal (radians).
*/
class ExternalView
{
public:
  ExternalView(const std::vector<vpPoint> &object, const std::vector<vpPoint> &tag, const vpHomogeneousMatrix &cdMo,
               double distance = 1.0, double elevation = 0.5, double azimuth = 0.7, double height = -1)
    : m_object(object), m_tag(tag), m_cdMo(cdMo), m_cam(700, 700, 320, 240), m_size(0.03 * distance)
  {
    const vpColVector zo = {0, 0, 1};
    // The cameras are on the plane's -z side.
    const vpColVector look = height < 0 ? 0.6 * centre(cdMo) : vpColVector({0, 0, -height});
    // The viewer's position: above the plane and to the side.
    const vpColVector eye =
        look + distance * vpColVector({std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                       -std::sin(elevation)});
    vpColVector z = look - eye;
    z.normalize();
    // The plane's normal towards the cameras (-z) points up in the picture (-y).
    vpColVector y = zo - vpColVector::dotProd(zo, z) * z;
    y.normalize();
    const vpColVector x = vpColVector::crossProd(y, z);
    vpRotationMatrix R;
    for (unsigned int i = 0; i < 3; ++i) {
      R[i][0] = x[i];
      R[i][1] = y[i];
      R[i][2] = z[i];
    }
    m_vMo = vpHomogeneousMatrix(vpTranslationVector(eye[0], eye[1], eye[2]), R).inverse();
  }

  //! The desired camera (cdMo), when it is known only once the servo has planned (an articulated target).
  void setDesiredPose(const vpHomogeneousMatrix &cdMo) { m_cdMo = cdMo; }
  //! Path \e k (0, 1, ...) in \e color gets the camera at cMo.
  void add(std::size_t k, const vpHomogeneousMatrix &cMo, const vpColor &color)
  {
    if (m_paths.size() <= k)
      m_paths.resize(k + 1);
    m_paths[k].color = color;
    m_paths[k].cMo.push_back(cMo);
  }

  //! Draws the view on the display attached to \e I (a white 480 x 640 image): each path with its first camera (thin)
  //! and its camera now (thick), then the desired camera on top.
  template <typename T> void display(const vpImage<T> &I) const
  {
    // The plane, 40 cm square about the object, the tag and the object on it.
    const std::vector<vpPoint> plane = {vpPoint(-0.2, -0.2, 0), vpPoint(0.2, -0.2, 0), vpPoint(0.2, 0.2, 0),
                                        vpPoint(-0.2, 0.2, 0)};
    polygon(I, plane, vpColor::lightGray, 1);
    polygon(I, m_tag, vpColor::darkGray, 1);
    polygon(I, m_object, vpColor::black, 2);
    vpDisplay::displayFrame(I, m_vMo, m_cam, 0.05, vpColor::none, 1);
    for (const Path &p : m_paths) {
      if (p.cMo.empty())
        continue;
      for (std::size_t i = 1; i < p.cMo.size(); ++i) {
        vpImagePoint a, b;
        if (project(centre(p.cMo[i - 1]), a) && project(centre(p.cMo[i]), b))
          vpDisplay::displayLine(I, a, b, p.color, 2);
      }
      camera(I, p.cMo.front(), p.color, 1);
      camera(I, p.cMo.back(), p.color, 3);
    }
    camera(I, m_cdMo, vpColor::green, 2);
  }

private:
  struct Path
  {
    vpColor color;
    std::vector<vpHomogeneousMatrix> cMo;
  };
  // The camera's centre in the object frame.
  static vpColVector centre(const vpHomogeneousMatrix &cMo)
  {
    const vpTranslationVector t = cMo.inverse().getTranslationVector();
    return vpColVector({t[0], t[1], t[2]});
  }
  // A camera at cMo, when it is in front of the viewer.
  template <typename T>
  void camera(const vpImage<T> &I, const vpHomogeneousMatrix &cMo, const vpColor &color, unsigned int t) const
  {
    vpImagePoint ip;
    if (project(centre(cMo), ip))
      vpDisplay::displayCamera(I, m_vMo * cMo.inverse(), m_cam, m_size, color, t);
  }
  bool project(const vpColVector &oP, vpImagePoint &ip) const
  {
    const vpColVector v = m_vMo * vpColVector({oP[0], oP[1], oP[2], 1});
    if (v[2] <= 1e-3)
      return false;
    vpMeterPixelConversion::convertPoint(m_cam, v[0] / v[2], v[1] / v[2], ip);
    return true;
  }
  template <typename T>
  void polygon(const vpImage<T> &I, const std::vector<vpPoint> &pts, const vpColor &color, unsigned int t) const
  {
    std::vector<vpImagePoint> ips;
    for (const vpPoint &p : pts) {
      vpImagePoint ip;
      if (project(vpColVector({p.get_oX(), p.get_oY(), p.get_oZ()}), ip))
        ips.push_back(ip);
    }
    if (ips.size() > 1)
      vpDisplay::displayPolygon(I, ips, color, t);
  }

  std::vector<vpPoint> m_object, m_tag;
  vpHomogeneousMatrix m_cdMo, m_vMo; // desired camera, and the viewer's pose (object frame in the viewer's frame)
  vpCameraParameters m_cam;
  double m_size; // the cameras' size (m): a fixed share of the view
  std::vector<Path> m_paths;
};
} // namespace tutorial

#endif
