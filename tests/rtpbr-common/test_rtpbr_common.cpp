// common/ against published values and round trips (suite 'rtpbr-common'): the two
// generators against their authors' reference outputs, the Markdown section writer on pages
// with and without the section, the image writer read back through OpenImageIO, the colour
// maps at their ends.
#include "rtpbr_common/colormap.hpp"
#include "rtpbr_common/energy.hpp"
#include "rtpbr_common/image.hpp"
#include "rtpbr_common/markdown.hpp"
#include "rtpbr_common/rng.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

int failures = 0;

void expect(bool ok, const std::string &what) {
    std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
    failures += ok ? 0 : 1;
}

std::string read_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

void write_file(const std::string &path, const std::string &text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

void test_splitmix64() {
    // Rosetta Code, "Pseudo-random numbers/Splitmix64": the first five outputs from 1234567.
    const uint64_t expected[5] = {6457827717110365317ull, 3203168211198807973ull, 9817491932198370423ull,
                                  4593380528125082431ull, 16408922859458223821ull};
    rtpbr_tools::SplitMix64 rng(1234567);
    bool ok = true;
    for (uint64_t e : expected)
        ok = ok && rng.next() == e;
    expect(ok, "SplitMix64(1234567) gives the published first five outputs");
    uint64_t state = 1234567;
    const float f = rtpbr_tools_splitmix64_float(&state);
    expect(f == float(expected[0] >> 40) / 16777216.0f, "SplitMix64 float = top 24 bits / 2^24");
    state = 1234567;
    const double d = rtpbr_tools_splitmix64_double(&state);
    expect(d == double(expected[0] >> 11) / 9007199254740992.0, "SplitMix64 double = top 53 bits / 2^53");
}

void test_pcg32() {
    // pcg-c-basic's pcg32-demo (O'Neill), seeded with initstate 42, stream 54.
    const uint32_t expected[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    rtpbr_tools::Pcg32 rng(42, 54);
    bool ok = true;
    for (uint32_t e : expected)
        ok = ok && rng.next() == e;
    expect(ok, "PCG32(42, 54) gives pcg32-demo's first six outputs");
}

void test_markdown(const std::string &dir) {
    const std::string page = dir + "/page.md";
    const std::string section = "<!-- gen:begin (generated) -->\nnew table\n<!-- gen:end -->\n";
    write_file(page, "# Title\n\ntext before\n<!-- gen:begin (generated) -->\nold\ntable\n<!-- gen:end -->\ntext after\n");
    std::string error;
    bool ok = rtpbr_tools::replace_markdown_section(page, "gen", section, error);
    expect(ok && read_file(page) == "# Title\n\ntext before\n" + section + "text after\n",
           "a section is replaced, the rest of the page kept byte for byte");
    write_file(page, "# Title\n<!-- other:begin -->\nx\n<!-- other:end -->\n");
    ok = rtpbr_tools::replace_markdown_section(page, "gen", section, error);
    expect(ok && read_file(page) == "# Title\n<!-- other:begin -->\nx\n<!-- other:end -->\n\n" + section,
           "a missing section is appended after a blank line, other sections untouched");
    const std::string fresh = dir + "/fresh.md";
    std::remove(fresh.c_str());
    ok = rtpbr_tools::replace_markdown_section(fresh, "gen", section, error);
    expect(ok && read_file(fresh) == section, "a missing page is created with the section");
    error.clear();
    ok = rtpbr_tools::replace_markdown_section(dir + "/no/such/dir/page.md", "gen", section, error);
    expect(!ok && error.find("no/such/dir") != std::string::npos, "an unwritable page is an error naming it");
}

bool read_back(const std::string &path, int &w, int &h, int &channels, std::vector<float> &pixels) {
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        return false;
    const OIIO::ImageSpec &spec = in->spec();
    w = spec.width, h = spec.height, channels = spec.nchannels;
    pixels.resize(size_t(w) * h * channels);
    const bool ok = in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data());
    in->close();
    return ok;
}

void test_image(const std::string &dir) {
    const uint8_t rgb[3 * 2 * 3] = {0, 1, 2, 50, 100, 150, 255, 254, 253, 7, 8, 9, 10, 20, 30, 128, 129, 130};
    std::string error;
    bool ok = rtpbr_tools::write_image_u8(dir + "/u8.png", 3, 2, 3, rgb, error);
    int w = 0, h = 0, c = 0;
    std::vector<float> back;
    ok = ok && read_back(dir + "/u8.png", w, h, c, back) && w == 3 && h == 2 && c == 3;
    for (int i = 0; ok && i < 18; i++)
        ok = std::lround(back[i] * 255.0f) == rgb[i];
    expect(ok, "an 8-bit PNG reads back pixel for pixel");

    const float values[4] = {0.0f, 0.5f, 1.0f / 3.0f, 1000.0f};
    rtpbr_tools::ImageWrite image;
    image.width = 2, image.height = 2, image.channels = 1, image.pixels = values;
    image.file_type = rtpbr_tools::PixelType::Half;
    image.attributes = {{"compression", "zip"}};
    ok = rtpbr_tools::write_image(dir + "/half.exr", image, error) && read_back(dir + "/half.exr", w, h, c, back) &&
         w == 2 && h == 2 && c == 1;
    for (int i = 0; ok && i < 4; i++)
        ok = std::fabs(back[i] - values[i]) <= values[i] * 0x1p-11f; // half: 11 significant bits
    expect(ok, "float pixels stored as half read back within half precision");

    image.width = 0;
    error.clear();
    expect(!rtpbr_tools::write_image(dir + "/bad.exr", image, error) && !error.empty(),
           "an image of width 0 is an error, not a crash");
    error.clear();
    expect(!rtpbr_tools::write_image_u8(dir + "/no/such/dir/x.png", 3, 2, 3, rgb, error) &&
               error.find("cannot write") != std::string::npos,
           "a file that cannot be created is an error");
    error.clear();
    expect(!rtpbr_tools::write_image_u8(dir + "/x.unknown-format", 3, 2, 3, rgb, error) && !error.empty(),
           "an unknown file format is an error");
}

void test_colormaps() {
    uint8_t a[3], b[3];
    // magma's first and last entries (matplotlib): (0.001462, 0.000466, 0.013866) and
    // (0.987053, 0.991438, 0.749504), times 255, rounded.
    rtpbr_tools::magma(0.0f, a);
    expect(a[0] == 0 && a[1] == 0 && a[2] == 4, "magma(0) is magma's first colour");
    rtpbr_tools::magma(1.0f, a);
    expect(a[0] == 252 && a[1] == 253 && a[2] == 191, "magma(1) is magma's last colour");
    rtpbr_tools::magma(-5.0f, b);
    rtpbr_tools::magma(0.0f, a);
    expect(a[0] == b[0] && a[1] == b[1] && a[2] == b[2], "magma clamps below 0");
    rtpbr_tools::magma(7.0f, b);
    rtpbr_tools::magma(1.0f, a);
    expect(a[0] == b[0] && a[1] == b[1] && a[2] == b[2], "magma clamps above 1");
    // The coarse map meets the table at both ends.
    rtpbr_tools::magma_coarse(0.0, b);
    rtpbr_tools::magma(0.0f, a);
    expect(a[0] == b[0] && a[1] == b[1] && a[2] == b[2], "magma_coarse(0) = magma(0)");
    rtpbr_tools::magma_coarse(1.0, b);
    rtpbr_tools::magma(1.0f, a);
    expect(a[0] == b[0] && a[1] == b[1] && a[2] == b[2], "magma_coarse(1) = magma(1)");
}

// The energy bound's figures on a 100 x 100 image whose values are known: 9,998 pixels of
// (0.1, 0.2, 0.3), one of (4, 1, 0) at (7, 3), one NaN; bound 2 -> largest ratio 2 at (7, 3),
// one pixel over 1.01; the brightest 0.01 % is one pixel: share 5 / (9998 x 0.6 + 5).
void test_energy() {
    const int w = 100, h = 100;
    std::vector<float> px(size_t(w) * h * 3);
    for (size_t p = 0; p < size_t(w) * h; ++p)
        px[3 * p] = 0.1f, px[3 * p + 1] = 0.2f, px[3 * p + 2] = 0.3f;
    px[3 * (3 * w + 7)] = 4.0f, px[3 * (3 * w + 7) + 1] = 1.0f, px[3 * (3 * w + 7) + 2] = 0.0f;
    px[3 * (50 * w + 50) + 1] = std::nanf("");
    rtpbr_tools::EnergyStats s = rtpbr_tools::energy_stats(px.data(), w, h, 3, 2.0);
    expect(s.max_ratio == 2.0 && s.max_x == 7 && s.max_y == 3, "energy: largest ratio and where");
    expect(s.over == 1 && s.non_finite == 1, "energy: pixels over 1.01 and not finite");
    const double share = 5.0 / (9998.0 * double(0.1f + 0.2f + 0.3f) + 5.0);
    expect(std::fabs(s.top_share - share) < 1e-6, "energy: share of the brightest 0.01 %");
    const double mean = (9998.0 * double(0.3f) + 4.0) / 9999.0 / 2.0;
    expect(std::fabs(s.mean_ratio - mean) < 1e-9, "energy: mean ratio over the finite pixels");
    rtpbr_tools::EnergyStats none = rtpbr_tools::energy_stats(px.data(), w, h, 3, 0.0);
    expect(none.max_ratio == 0.0 && none.over == 0, "energy: no bound, no ratios");
    expect(s.bounded && s.largest == 4.0, "energy: bounded, largest pixel value");
    expect(rtpbr_tools::energy_json(s).find("\"bounded\": true") != std::string::npos, "energy: JSON bounded");
    // A scene with punctual lights: no bound; the image's own figures, said so.
    rtpbr_tools::EnergyStats u = rtpbr_tools::energy_stats_unbounded(px.data(), w, h, 3);
    expect(!u.bounded && u.brightest_emitter == 0.0 && u.max_ratio == 0.0 && u.mean_ratio == 0.0 && u.over == 0,
           "energy: unbounded, no ratios");
    expect(u.largest == 4.0 && u.max_x == 7 && u.max_y == 3 && u.non_finite == 1 &&
               std::fabs(u.top_share - share) < 1e-6,
           "energy: unbounded, the image's own figures");
    expect(rtpbr_tools::energy_summary(u).rfind("no energy bound (punctual lights", 0) == 0 &&
               rtpbr_tools::energy_json(u).find("\"bounded\": false") != std::string::npos,
           "energy: unbounded, said so in the summary and the JSON");
}

} // namespace

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: test_rtpbr_common SCRATCH_DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    test_splitmix64();
    test_pcg32();
    test_markdown(dir);
    test_image(dir);
    test_colormaps();
    test_energy();
    std::printf("%d failure(s)\n", failures);
    return failures ? 1 : 0;
}
