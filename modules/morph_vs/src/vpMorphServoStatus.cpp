#include <visp3/morph_vs/vpMorphServoStatus.h>

const char *vpMorphServoStatus::statusName(Status s)
{
  switch (s) {
  case NOT_STARTED:
    return "not started";
  case MOVING:
    return "moving";
  case SUBGOAL_REACHED:
    return "sub-goal reached";
  case CONVERGED:
    return "converged";
  case UNVERIFIED:
    return "unverified";
  case TARGET_LOST:
    return "target lost";
  case DEGENERATE_CONTOUR:
    return "degenerate contour";
  case UNEXPLAINED_VIEW:
    return "unexplained view";
  case REPLANNED:
    return "replanned";
  case LOST_TOO_LONG:
    return "lost too long";
  case TOO_MANY_REPLANS:
    return "too many replans";
  case TARGET_MISMATCH:
    return "target mismatch";
  }
  return "?";
}

bool vpMorphServoStatus::isStop(Status s)
{
  return s == CONVERGED || s == UNVERIFIED || s == LOST_TOO_LONG || s == TOO_MANY_REPLANS || s == TARGET_MISMATCH;
}
