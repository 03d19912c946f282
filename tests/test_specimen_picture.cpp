// The specimen picture: a real PNG of the right size, colours where the discs are, y up.
#include <gtest/gtest.h>

#include <cairo.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "mesogen/specimen_picture.hpp"

#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using cdem::Specimen;
using namespace cdem::mesogen;

namespace {

fs::path scratch_dir(const std::string& test) {
  return cdem::test::scratch_dir("specimen_picture", test);
}

// 100 x 200 mm: a mortar disc near the top, a bin-0 clump near the bottom (two pebbles, one of
// them dropped from contact detection), a bin-3 clump in the middle.
Specimen synthetic_specimen() {
  Specimen s;
  s.container = {cdem::ContainerShape::Rectangle, 0.1, 0.2};
  auto add = [&](double x, double y, double r, int clump, int active) {
    s.x.push_back(x);
    s.y.push_back(y);
    s.r.push_back(r);
    s.clump.push_back(clump);
    s.contact_active.push_back(static_cast<std::uint8_t>(active));
  };
  add(0.05, 0.18, 0.008, -1, 1);  // mortar, top
  add(0.03, 0.02, 0.008, 0, 1);   // bin 0, bottom
  add(0.07, 0.02, 0.008, 0, 0);   // bin 0, bottom, inactive
  add(0.05, 0.10, 0.008, 1, 1);   // bin 3, middle
  cdem::Clump bottom;
  bottom.vertices = {{0.015, 0.005}, {0.085, 0.005}, {0.085, 0.035}, {0.015, 0.035}};
  bottom.bin = 0;
  cdem::Clump middle;
  middle.vertices = {{0.04, 0.09}, {0.06, 0.09}, {0.05, 0.115}};
  middle.bin = 3;
  s.clumps = {bottom, middle};
  return s;
}

struct Png {
  cairo_surface_t* surface = nullptr;
  explicit Png(const fs::path& p) : surface(cairo_image_surface_create_from_png(p.c_str())) {}
  ~Png() { cairo_surface_destroy(surface); }
  bool ok() const { return cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(surface); }
  int height() const { return cairo_image_surface_get_height(surface); }
  // Mean row (0 = top) of the pixels within 2/255 of `rgb`, and their count.
  std::pair<double, int> rows_of(const std::array<double, 3>& rgb) const {
    cairo_surface_flush(surface);
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    double sum = 0;
    int count = 0;
    for (int row = 0; row < height(); ++row)
      for (int col = 0; col < width(); ++col) {
        // ARGB32/RGB24 in native-endian 32-bit words: B, G, R, A bytes on little endian.
        const auto word = *reinterpret_cast<const std::uint32_t*>(data + row * stride + 4 * col);
        const double r = ((word >> 16) & 0xff) / 255.0;
        const double g = ((word >> 8) & 0xff) / 255.0;
        const double b = (word & 0xff) / 255.0;
        if (std::abs(r - rgb[0]) <= 2.0 / 255 && std::abs(g - rgb[1]) <= 2.0 / 255 &&
            std::abs(b - rgb[2]) <= 2.0 / 255) {
          sum += row;
          ++count;
        }
      }
    return {count ? sum / count : -1, count};
  }
};

}  // namespace

TEST(SpecimenPicture, WritesAPngOfTheRequestedSize) {
  const fs::path file = scratch_dir("size") / "specimen.png";
  draw_specimen_png(synthetic_specimen(), file, 400);
  std::ifstream in(file, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const Png png(file);
  ASSERT_TRUE(png.ok());
  // A tall specimen: the height is the long side; the width holds the 1:2 specimen plus the
  // legend column, so it is more than half and less than the height.
  EXPECT_EQ(png.height(), 400);
  EXPECT_GT(png.width(), 200);
  EXPECT_LT(png.width(), 400);
  // No temporary file left beside it.
  EXPECT_EQ(std::distance(fs::directory_iterator(file.parent_path()), fs::directory_iterator()), 1);
}

TEST(SpecimenPicture, WideDiscContainer) {
  const fs::path file = scratch_dir("disc") / "brazilian.png";
  Specimen s = synthetic_specimen();
  s.container = {cdem::ContainerShape::Disc, 0.2, 0.2};
  draw_specimen_png(s, file, 600);
  const Png png(file);
  ASSERT_TRUE(png.ok());
  // Square container plus the legend: the width is the long side.
  EXPECT_EQ(png.width(), 600);
  EXPECT_LT(png.height(), 600);
}

TEST(SpecimenPicture, ColoursAndYAxisUp) {
  const fs::path file = scratch_dir("colours") / "specimen.png";
  draw_specimen_png(synthetic_specimen(), file, 800);
  const Png png(file);
  ASSERT_TRUE(png.ok());
  // A disc of radius 8 mm at ~3.6 px/mm covers ~2500 px; the legend swatch adds ~150.
  const auto [bin0_row, bin0_count] = png.rows_of(bin_colour(0));
  const auto [pale_row, pale_count] = png.rows_of(inactive_colour(0));
  const auto [bin3_row, bin3_count] = png.rows_of(bin_colour(3));
  const auto [mortar_row, mortar_count] = png.rows_of(kMortarColour);
  EXPECT_GT(bin0_count, 1500);
  EXPECT_GT(pale_count, 1500);
  EXPECT_GT(bin3_count, 1500);
  EXPECT_GT(mortar_count, 1500);
  // y up: the pebbles at y = 20 mm are near the bottom of the image, the mortar disc at
  // y = 180 mm near the top, the middle clump in between.
  EXPECT_GT(bin0_row, 0.75 * png.height());
  EXPECT_GT(pale_row, 0.75 * png.height());
  EXPECT_LT(mortar_row, 0.25 * png.height());
  EXPECT_GT(bin3_row, 0.35 * png.height());
  EXPECT_LT(bin3_row, 0.65 * png.height());
}

TEST(SpecimenPicture, DistinctBinColours) {
  for (int a = 0; a < 7; ++a)
    for (int b = a + 1; b < 7; ++b) {
      const auto ca = bin_colour(a);
      const auto cb = bin_colour(b);
      const double dist = std::hypot(ca[0] - cb[0], ca[1] - cb[1], ca[2] - cb[2]);
      EXPECT_GT(dist, 0.2) << a << " vs " << b;
    }
}

TEST(SpecimenPicture, RejectsBadInput) {
  const fs::path file = scratch_dir("bad") / "x.png";
  EXPECT_THROW(draw_specimen_png(synthetic_specimen(), file, 50), std::invalid_argument);
  Specimen s = synthetic_specimen();
  s.clump[0] = 9;
  EXPECT_THROW(draw_specimen_png(s, file, 400), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file));
}

TEST(SpecimenPicture, BinsLabelledBySieveSizesInMm) {
  const std::vector<double> edges{0.005, 0.0075, 0.010, 0.015};  // m
  EXPECT_EQ(bin_label(0, edges), "aggregate 5-7.5 mm");
  EXPECT_EQ(bin_label(2, edges), "aggregate 10-15 mm");
  // Beyond the edges (a specimen read from a file has none): the bin's number only.
  EXPECT_EQ(bin_label(3, edges), "aggregate bin 3");
  EXPECT_EQ(bin_label(0, {}), "aggregate bin 0");
}
