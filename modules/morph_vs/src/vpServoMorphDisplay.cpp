// vpServoMorph: what display() and draw() show, from the servo's public state only, on a display or into an image.
#include <visp3/morph_vs/vpServoMorph.h>

#include <algorithm>
#include <cstdio>

#include <visp3/core/vpMath.h>

#include "vpMorphOverlay.h"

namespace
{
// The correspondence drawn between the current contour and its sub-goal, and the status text.
const vpColor kCorrespondenceColor = vpColor::cyan;
const vpColor kStatusColor = vpColor::yellow;

// Whether the last alignment is the one from the current contour to the current sub-goal: only when the servo aligned
// it (moving, reached, converged; not on a hold, a stop, a re-plan or the exploration turn).
bool alignmentShown(const vpServoMorph &servo)
{
  const vpServoMorph::Status st = servo.getStatus();
  return !servo.getHandEyeExploration().isActive() && servo.getAlignment().explained() &&
         (st == vpServoMorph::MOVING || st == vpServoMorph::SUBGOAL_REACHED || st == vpServoMorph::CONVERGED);
}

void drawServo(const vpServoMorph &servo, vpMorphOverlay &o, const vpColor &currentColor, const vpColor &subGoalColor,
               const vpColor &targetColor, unsigned int thickness)
{
  const vpMorphContour &target = servo.getTargetContour(), &current = servo.getCurrentContour();
  const std::vector<vpMorphContour> &goals = servo.getSubGoals();
  const std::size_t k = servo.getSubGoalIndex();
  if (!target.empty())
    o.polygon(target.points(), targetColor, thickness + 2);
  if (k + 1 < goals.size())
    o.polygon(goals[k].points(), subGoalColor, thickness);
  if (!current.empty() && k < goals.size() && alignmentShown(servo))
    for (const auto &l : servo.alignmentLines())
      o.line(l.first, l.second, kCorrespondenceColor, 1);
  if (!current.empty())
    o.polygon(current.points(), currentColor, thickness);
  o.text(servo.statusText(), kStatusColor);
}
} // namespace

std::vector<std::pair<vpImagePoint, vpImagePoint>> vpServoMorph::alignmentLines() const
{
  return m_alignment.lines(m_current.toNormalized(m_camIso), m_camIso);
}

std::vector<std::string> vpServoMorph::statusText() const
{
  char line[160];
  std::vector<std::string> lines;
  const std::size_t n = getSubGoals().size();
  const bool exploring = getHandEyeExploration().isActive();
  // An UNVERIFIED stop says which test of the verification it failed.
  std::string status = statusName(getStatus());
  if (getStatus() == UNVERIFIED)
    status += std::string(" (") + vpMorphServoGuard::verificationName(getGuard().getVerification()) + ")";
  if (n > 0)
    std::snprintf(line, sizeof line, "%s  sub-goal %zu/%zu  (%s)", status.c_str(), getSubGoalIndex() + 1, n,
                  exploring ? "exploration turn" : vpMorphViewAlignment::modelName(getAlignment().model));
  else
    std::snprintf(line, sizeof line, "%s%s", status.c_str(), exploring ? "  (exploration turn)" : "");
  lines.emplace_back(line);
  if (n > 0 && !exploring) { // the turn measures no residual
    std::snprintf(line, sizeof line, "residual %.3f rad  %.2f px", getRotationResidual(), getTranslationResidual());
    std::string l = line;
    if (getTiltEstimator().isEstimated()) {
      const double deviation = getTiltEstimator().getDeviation();
      if (std::isfinite(deviation))
        std::snprintf(line, sizeof line, "  tilt %.2f +- %.2f deg", vpMath::deg(getTiltEstimator().getResidual()),
                      vpMath::deg(deviation));
      else
        std::snprintf(line, sizeof line, "  tilt %.2f deg", vpMath::deg(getTiltEstimator().getResidual()));
      l += line;
    }
    lines.push_back(l);
  }
  return lines;
}

void vpServoMorph::display(const vpImage<unsigned char> &I, const vpColor &currentColor, const vpColor &subGoalColor,
                           const vpColor &targetColor, unsigned int thickness) const
{
  vpMorphDisplayOverlay<unsigned char> o(I);
  drawServo(*this, o, currentColor, subGoalColor, targetColor, thickness);
}

void vpServoMorph::display(const vpImage<vpRGBa> &I, const vpColor &currentColor, const vpColor &subGoalColor,
                           const vpColor &targetColor, unsigned int thickness) const
{
  vpMorphDisplayOverlay<vpRGBa> o(I);
  drawServo(*this, o, currentColor, subGoalColor, targetColor, thickness);
}

void vpServoMorph::draw(vpImage<vpRGBa> &I, const vpColor &currentColor, const vpColor &subGoalColor,
                        const vpColor &targetColor, unsigned int thickness) const
{
  vpMorphImageOverlay o(I);
  drawServo(*this, o, currentColor, subGoalColor, targetColor, thickness);
}
