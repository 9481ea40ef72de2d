#include <visp3/morph_bench/vpMorphBenchController.h>

#include <visp3/morph/vpMorphException.h>

#include "vpMorphBenchAdapter.h"

vpMorphBenchController::Command vpMorphBenchController::missingFrame()
{
  Command c;
  c.measured = false;
  return c;
}

std::vector<std::string> vpMorphBenchController::names()
{
  return {"morph",        "morph-planar", "morph-paper", "morph-vpservo", "ibvs-current",
          "ibvs-desired", "ibvs-mean",    "pbvs",        "moments",       "moments-planar"};
}

std::unique_ptr<vpMorphBenchController> vpMorphBenchController::create(const std::string &name)
{
  if (std::unique_ptr<vpMorphBenchController> c = vpMorphBenchAdapter::createMorph(name))
    return c;
  if (std::unique_ptr<vpMorphBenchController> c = vpMorphBenchAdapter::createStock(name))
    return c;
  throw vpMorphException(vpMorphException::notFoundError,
                         "vpMorphBenchController: unknown controller '" + name +
                             "' (morph, morph-planar, morph-paper, morph-vpservo, ibvs-current, "
                             "ibvs-desired, ibvs-mean, pbvs, moments, moments-planar)");
}
