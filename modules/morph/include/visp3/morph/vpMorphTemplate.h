/*!
  \file vpMorphTemplate.h
  \brief One known object: its stored view (contour), where it came from, and the pose to align with it.
*/
#ifndef VP_MORPH_TEMPLATE_H
#define VP_MORPH_TEMPLATE_H

#include <map>
#include <string>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphTemplate
  \ingroup group_morph
  \brief A template of vpMorphDatabase (value type): name, contour, source image, desired pose, metadata.

  In the paper each known object is stored as the view taken from the pose at which the robot must align
  with it; recognizing the object therefore also tells where to go. The template keeps that pose as \e cdMo
  (object frame in the desired camera frame, identity when unknown), the contour of the view (PIXEL units, as
  extracted), the image it came from (so that a database can be rebuilt or audited), and free-form string
  metadata for the application (grasp point, part number, ...).

  \code
  vpMorphTemplate t("key", vpMorphContourExtractor().extract(I), "key.png");
  t.setPlanarPose(0.0, 0.0, 0.5, vpMath::rad(20));  // optical axis normal to the plane at 0.5 m, turned 20 deg
  t.setMetadata("part", "K-12");
  \endcode
  \sa vpMorphDatabase, vpMorphArticulation
*/
class vpMorphTemplate
{
public:
  //! An empty template (no name, no contour).
  vpMorphTemplate() = default;
  /*!
    A template named \e name for the view \e contour, taken from \e imagePath at the desired pose \e cdMo.
    \throw vpMorphException::badParameterError on an empty name or an empty contour.
  */
  vpMorphTemplate(const std::string &name, const vpMorphContour &contour, const std::string &imagePath = "",
                  const vpHomogeneousMatrix &cdMo = vpHomogeneousMatrix());

  //! The template's name (unique in a database).
  const std::string &name() const { return m_name; }
  //! The taught view's contour (PIXEL units).
  const vpMorphContour &contour() const { return m_contour; }
  //! Image the contour was extracted from (empty if none); relative paths are relative to the database file.
  const std::string &imagePath() const { return m_image; }
  //! Desired pose: the object frame in the camera frame at alignment.
  const vpHomogeneousMatrix &cdMo() const { return m_cdMo; }
  //! All metadata (key, value).
  const std::map<std::string, std::string> &metadata() const { return m_meta; }
  //! Value of metadata \e key, or \e fallback when absent.
  std::string metadata(const std::string &key, const std::string &fallback = "") const;

  //! Sets the source image's path.
  void setImagePath(const std::string &path) { m_image = path; }
  //! Sets the desired pose (object frame in the camera frame at alignment).
  void setCdMo(const vpHomogeneousMatrix &cdMo) { m_cdMo = cdMo; }
  /*!
    Desired pose from the in-plane pose of the paper's set-up: optical axis normal to the object plane at
    depth \e Z (metres), object frame rotated by \e theta (radians) about it and offset by (tx, ty) metres.
  */
  void setPlanarPose(double tx, double ty, double Z, double theta);
  /*!
    Makes the template articulated (two parts about a pin, in the view of contour()): recognition then also tries
    its view at other openings (vpMorphDatabase), and viewFor() poses it at the opening a view shows. An empty one
    makes it rigid again.
    \throw vpMorphException::badParameterError when the parts are not in the contour's units.
  */
  void setArticulation(const vpMorphArticulation &a);
  //! The articulation (empty for a rigid template).
  const vpMorphArticulation &articulation() const { return m_articulation; }
  /*!
    The view of this template to align \e view with: contour() for a rigid template, or for an articulated one seen
    at its taught opening; else its pose at the opening \e view shows (vpMorphArticulation::poseFor()). \e opening
    and \e fixedPart, if given, receive the opening (0 for contour()) and the part kept in place.
  */
  vpMorphContour viewFor(const vpMorphContour &view, double *opening = nullptr,
                         unsigned int *fixedPart = nullptr) const;
  //! True when the template has an articulation.
  bool isArticulated() const { return !m_articulation.empty(); }
  //! Sets metadata \e key to \e value.
  void setMetadata(const std::string &key, const std::string &value) { m_meta[key] = value; }
  //! Replaces all metadata.
  void setMetadata(const std::map<std::string, std::string> &meta) { m_meta = meta; }

private:
  std::string m_name;
  vpMorphContour m_contour;
  std::string m_image;
  vpHomogeneousMatrix m_cdMo;
  std::map<std::string, std::string> m_meta;
  vpMorphArticulation m_articulation;
};

#endif
