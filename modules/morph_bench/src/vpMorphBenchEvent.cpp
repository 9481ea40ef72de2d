#include <visp3/morph_bench/vpMorphBenchEvent.h>

#include <cmath>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
const char *const kNames[] = {"dropped-frames", "no-object", "sudden-occluder", "pose-jump", "wrong-template"};
}

bool vpMorphBenchEvent::activeAt(unsigned int it) const
{
  switch (kind) {
  case DROPPED_FRAMES:
  case NO_OBJECT:
    return it >= iteration && it - iteration < frames;
  case SUDDEN_OCCLUDER:
    return it >= iteration;
  case POSE_JUMP:
  case WRONG_TEMPLATE:
    return it == iteration;
  }
  return false;
}

std::string vpMorphBenchEvent::kindName(Kind k) { return kNames[static_cast<int>(k)]; }

vpMorphBenchEvent::Kind vpMorphBenchEvent::kindFromName(const std::string &name)
{
  for (int k = 0; k < 5; ++k)
    if (name == kNames[k])
      return static_cast<Kind>(k);
  throw vpMorphException(vpMorphException::badParameterError,
                         "vpMorphBenchEvent: unknown fault '" + name +
                             "' (dropped-frames, no-object, sudden-occluder, pose-jump, wrong-template)");
}

std::string vpMorphBenchEvent::describe() const
{
  std::ostringstream os;
  os.precision(3);
  os << kindName(kind) << "@" << iteration;
  switch (kind) {
  case DROPPED_FRAMES:
  case NO_OBJECT:
    os << "x" << frames;
    break;
  case SUDDEN_OCCLUDER:
    os << " " << 100 * occludedShare << " %";
    break;
  case POSE_JUMP:
    os << " " << 1000 * cMcp.getTranslationVector().frobeniusNorm() << " mm "
       << vpMath::deg(vpThetaUVector(cMcp.getRotationMatrix()).getTheta()) << " deg";
    break;
  case WRONG_TEMPLATE:
    os << " " << wrongTemplate;
    break;
  }
  return os.str();
}
