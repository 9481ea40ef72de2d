// Tests of vpMorphDrawing: a headless strip of a morph sequence written as PNG.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>

#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
vpMorphContour arrowShape()
{
  const std::vector<double> x = {0, 100, 100, 140, 100, 100, 0};
  const std::vector<double> y = {0, 0, -20, 20, 60, 40, 40};
  std::vector<double> u, v;
  for (std::size_t k = 0; k < x.size(); ++k) {
    u.push_back(300 + x[k]);
    v.push_back(200 + y[k]);
  }
  return vpMorphContour(u, v);
}

// (ViSP 3.5's vpRGBa::operator== is not const.)
bool isBlack(const vpRGBa &p) { return p.R == 0 && p.G == 0 && p.B == 0; }

// Pixels of colour c in tile k of a one-row strip.
int countColour(const vpImage<vpRGBa> &I, unsigned int tile, unsigned int tileSize, const vpColor &c)
{
  int n = 0;
  for (unsigned int r = 0; r < I.getHeight(); ++r)
    for (unsigned int q = tile * tileSize; q < (tile + 1) * tileSize; ++q)
      n += I[r][q].R == c.R && I[r][q].G == c.G && I[r][q].B == c.B;
  return n;
}
} // namespace

TEST_CASE("vpMorphDrawing: sequence strip written as PNG", "[morph][drawing]")
{
  const vpMorphContour A = arrowShape().resampled(30);
  const vpMorphContour B = arrowShape().transformed(2.5, 60.0, 20.0, 0.8).resampled(24);
  const vpMorph m(A, B);
  const unsigned int tile = 120;
  const vpImage<vpRGBa> I = vpMorphDrawing::sequenceStrip(m, 7, tile); // input + 7 frames: 8 tiles, one row
  REQUIRE(I.getWidth() == 8 * tile);
  REQUIRE(I.getHeight() == tile);

  // Input outline in every tile (in tile 0 the frame is the input itself, drawn over it); n = 7 gives
  // nr = 7 - max(1, 7 / 2) = 4 rigid frames (tiles 1..4, blue) and 3 deformation frames (tiles 5..7, orange).
  REQUIRE(m.rigidFrameCount(7) == 4);
  for (unsigned int k = 1; k < 8; ++k)
    CHECK(countColour(I, k, tile, vpMorphDrawing::inputColor) > 0);
  for (unsigned int k = 0; k <= 4; ++k)
    CHECK(countColour(I, k, tile, vpMorphDrawing::rigidColor) > 20);
  for (unsigned int k = 5; k <= 7; ++k)
    CHECK(countColour(I, k, tile, vpMorphDrawing::deformationColor) > 20);
  // Black borders on the first and last tiles only.
  CHECK(isBlack(I[0][0]));
  CHECK(isBlack(I[tile - 1][8 * tile - 1]));
  CHECK(!isBlack(I[1][3 * tile + tile / 2]));

  const std::string path = "morph_test_output/strips/sequence_strip.png";
  std::filesystem::remove(path);
  vpMorphDrawing::write(I, path);
  REQUIRE(std::filesystem::exists(path));
  vpImage<vpRGBa> R;
  vpImageIo::read(R, path);
  CHECK(R.getWidth() == 8 * tile);
  CHECK(R.getHeight() == tile);

  // Explicit columns: two rows.
  const std::vector<vpMorphContour> frames = m.sequence(6);
  const vpImage<vpRGBa> J = vpMorphDrawing::sequenceStrip(A, frames, 100, 3, m.rigidFrameCount(6));
  CHECK(J.getWidth() == 300);
  CHECK(J.getHeight() == 200);
}

TEST_CASE("vpMorphDrawing: bad input", "[morph][drawing]")
{
  const vpMorphContour A = arrowShape();
  CHECK_THROWS_AS(vpMorphDrawing::sequenceStrip(A, {}), vpMorphException);
  CHECK_THROWS_AS(vpMorphDrawing::sequenceStrip(A, {A}, 8), vpMorphException);
  CHECK_THROWS_AS(vpMorphDrawing::sequenceStrip(vpMorphContour(), {A}), vpMorphException);
  // A directory where the file should be: the write fails with ioError.
  std::filesystem::create_directories("morph_test_output/is_a_dir.png");
  try {
    vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(A, {A}, 64), "morph_test_output/is_a_dir.png");
    FAIL("writing onto a directory succeeded");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::ioError);
  }
  // A parent "directory" that is a file: cannot be created.
  {
    std::ofstream("morph_test_output/a_file") << "x";
  }
  CHECK_THROWS_AS(vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(A, {A}, 64), "morph_test_output/a_file/x.png"),
                  vpMorphException);
}

namespace
{
bool is(const vpRGBa &p, const vpColor &c) { return p.R == c.R && p.G == c.G && p.B == c.B; }
} // namespace

TEST_CASE("vpMorphDrawing::drawLine clips segments to the image", "[morph][drawing]")
{
  // Random segments across and around a small image, of every thickness drawn: vpImageDraw alone wrote outside it.
  vpImage<vpRGBa> I(48, 64, vpRGBa(255, 255, 255));
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(-300, 400);
  for (int k = 0; k < 20000; ++k)
    vpMorphDrawing::drawLine(I, vpImagePoint(u(g), u(g)), vpImagePoint(u(g), u(g)), vpColor::red, 1 + k % 3);
  // A segment across the image draws the whole row inside; one outside draws nothing; a NaN end draws nothing.
  vpImage<vpRGBa> J(48, 64, vpRGBa(255, 255, 255));
  vpMorphDrawing::drawLine(J, vpImagePoint(10, -100), vpImagePoint(10, 200), vpColor::blue);
  for (unsigned int c = 0; c < 64; ++c)
    CHECK(is(J[10][c], vpColor::blue));
  vpImage<vpRGBa> K(48, 64, vpRGBa(255, 255, 255));
  vpMorphDrawing::drawLine(K, vpImagePoint(-5, -100), vpImagePoint(-20, 200), vpColor::blue);
  vpMorphDrawing::drawLine(K, vpImagePoint(10, std::nan("")), vpImagePoint(10, 20), vpColor::blue);
  vpMorphDrawing::drawPolygon(K, {vpImagePoint(100, 100), vpImagePoint(100, 200), vpImagePoint(200, 150)},
                              vpColor::blue);
  std::size_t painted = 0;
  for (unsigned int k = 0; k < K.getSize(); ++k)
    painted += !is(K.bitmap[k], vpColor::white);
  CHECK(painted == 0);
  // A polygon crossing the border: its edges inside are drawn.
  vpMorphDrawing::drawPolygon(K, {vpImagePoint(5, 5), vpImagePoint(5, 100), vpImagePoint(40, 5)}, vpColor::green);
  CHECK(is(K[5][60], vpColor::green));
  CHECK(is(K[20][5], vpColor::green));
}

TEST_CASE("vpMorphDrawing::drawTextBand writes its lines on a black band, clipped to the image", "[morph][drawing]")
{
  vpImage<vpRGBa> I(120, 200, vpRGBa(255, 255, 255));
  const std::vector<std::string> lines = {"converged", "residual 0.001 rad"};
  const vpRect band = vpMorphDrawing::drawTextBand(I, lines, vpImagePoint(4, 4), vpColor::yellow);
  CHECK(band.getWidth() == Approx(8.0 * (18 + 2)));
  CHECK(band.getHeight() == Approx(16.0 * 3));
  std::size_t inside = 0, outside = 0, black = 0;
  for (unsigned int v = 0; v < I.getHeight(); ++v)
    for (unsigned int u = 0; u < I.getWidth(); ++u) {
      const bool in = band.isInside(vpImagePoint(v, u));
      (in ? inside : outside) += is(I[v][u], vpColor::yellow);
      black += in && is(I[v][u], vpColor::black);
    }
  CHECK(inside > 4 * 24); // glyphs: a few pixels a character at least
  CHECK(outside == 0);
  CHECK(black > inside);
  // A band that does not fit: what fits is drawn, nothing beyond the image.
  CHECK_NOTHROW(vpMorphDrawing::drawTextBand(I, lines, vpImagePoint(110, 150), vpColor::yellow));
  CHECK(is(I[119][199], vpColor::black));
}
