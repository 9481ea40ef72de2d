// vpServoMorph: what display() and draw() show, from the servo's public state only, on a display or into an image.
#include <visp3/morph_vs/vpServoMorph.h>

#include <cstdio>

#include <visp3/core/vpMath.h>

#include "vpMorphOverlay.h"

namespace
{
// The correspondence drawn between the current contour and its sub-goal, and the status text.
const vpColor kCorrespondenceColor = vpColor::cyan;
const vpColor kStatusColor = vpColor::yellow;

// Whether the tracker's correspondence is the one from \e current to sub-goal \e goal fitted at the last period: only
// when the servo fitted it (moving, reached, converged; not on a stop, a re-plan or the exploration turn), and never
// beyond the two contours' vertices.
bool correspondenceShown(const vpServoMorph &servo, const vpMorphContour &current, const vpMorphContour &goal)
{
  const vpServoMorph::Status st = servo.status();
  if (servo.exploring() ||
      (st != vpServoMorph::MOVING && st != vpServoMorph::SUBGOAL_REACHED && st != vpServoMorph::CONVERGED))
    return false;
  const vpMorphCorrespondence &corr = servo.tracker().correspondence();
  return !corr.empty() && corr.inputSize() == current.size() && corr.targetSize() == goal.size();
}

void drawServo(const vpServoMorph &servo, vpMorphOverlay &o, const vpColor &currentColor, const vpColor &subGoalColor,
               const vpColor &targetColor, unsigned int thickness)
{
  const vpMorphContour &target = servo.getTargetContour(), &current = servo.getCurrentContour();
  const std::vector<vpMorphContour> &goals = servo.subGoals();
  const std::size_t k = servo.subGoalIndex();
  if (!target.empty())
    o.polygon(target.points(), targetColor, thickness + 2);
  if (k + 1 < goals.size())
    o.polygon(goals[k].points(), subGoalColor, thickness);
  if (!current.empty() && k < goals.size() && correspondenceShown(servo, current, goals[k])) {
    const std::vector<vpImagePoint> a = current.points(), b = goals[k].points();
    for (const auto &p : servo.tracker().correspondence().pairs())
      o.line(a[p.first], b[p.second], kCorrespondenceColor, 1);
  }
  if (!current.empty())
    o.polygon(current.points(), currentColor, thickness);
  o.text(servo.statusText(), kStatusColor);
}
} // namespace

std::vector<std::string> vpServoMorph::statusText() const
{
  char line[160];
  std::vector<std::string> lines;
  const std::size_t n = subGoals().size();
  if (n > 0)
    std::snprintf(line, sizeof line, "%s  sub-goal %zu/%zu%s", statusName(status()), subGoalIndex() + 1, n,
                  exploring() ? "  (exploration turn)" : "");
  else
    std::snprintf(line, sizeof line, "%s", statusName(status()));
  lines.emplace_back(line);
  if (n > 0 && !exploring()) { // the turn measures no residual
    std::snprintf(line, sizeof line, "residual %.3f rad  %.2f px", rotationResidual(), translationResidual());
    std::string l = line;
    if (tiltEstimated()) {
      std::snprintf(line, sizeof line, "  tilt %.2f deg", vpMath::deg(tiltResidual()));
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
