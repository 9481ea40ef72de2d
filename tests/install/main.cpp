// Outside-project check of an installed VISPMorph: construct contours, measure them, catch a bad one.
#include <cmath>
#include <iostream>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphException.h>

static bool check(const char *name, double value, double expected)
{
  const bool ok = std::fabs(value - expected) < 1e-9;
  std::cout << name << " area = " << value;
  if (!ok)
    std::cout << " (expected " << expected << ")";
  std::cout << std::endl;
  return ok;
}

int main()
{
  try {
    const vpMorphContour triangle(std::vector<double>{0, 4, 0}, std::vector<double>{0, 0, 3});
    const vpMorphContour square(std::vector<double>{10, 20, 20, 10}, std::vector<double>{10, 10, 20, 20});
    bool ok = check("triangle", triangle.area(), 6.0);
    ok = check("square", square.area(), 100.0) && ok;

    // Bad input must raise the suite's exception, catchable as a vpException (ViSP's own library links).
    bool thrown = false;
    try {
      vpMorphContour segment(std::vector<double>{0, 1}, std::vector<double>{0, 1});
    } catch (const vpException &e) {
      thrown = true;
      std::cout << "two vertices rejected: " << e.getMessage() << std::endl;
    }
    if (!thrown)
      std::cout << "a two-vertex contour was accepted" << std::endl;
    ok = ok && thrown;

    std::cout << (ok ? "installed VISPMorph OK" : "installed VISPMorph FAILED") << std::endl;
    return ok ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "unexpected exception: " << e.getMessage() << std::endl;
    return 1;
  }
}
