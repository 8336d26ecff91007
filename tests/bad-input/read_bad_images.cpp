// Regression inputs for rtpbr-diff's image reading (tests/bad-input/images/):
//   read_bad_images DIR
// reads DIR/expected.txt, lines "FILE error [WORDS]" or "FILE ok" ('#' starts a comment), reads
// each FILE with rtpbr::read_image (common/rtpbr_common/image_read.hpp) and checks the outcome:
// an error must come with a message (containing WORDS, the rest of the line, when given: the
// reason, not just any failure), a success with width x height x 3 finite values.
#include "rtpbr_common/image_read.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: read_bad_images DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::ifstream list(dir + "/expected.txt");
    if (!list) {
        std::fprintf(stderr, "read_bad_images: cannot open %s/expected.txt\n", dir.c_str());
        return 2;
    }
    std::string line;
    int failures = 0, cases = 0;
    while (std::getline(list, line)) {
        std::istringstream fields(line);
        std::string file, want, word;
        if (line.empty() || line[0] == '#' || !(fields >> file >> want)) continue;
        std::getline(fields >> std::ws, word);  // the rest of the line
        ++cases;
        rtpbr::Image image;
        std::string error;
        const bool read = rtpbr::read_image(dir + "/" + file, image, error);
        bool ok = read == (want == "ok");
        if (read) {
            ok = ok && image.width > 0 && image.height > 0 &&
                 image.rgb.size() == static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3;
            for (float v : image.rgb) ok = ok && std::isfinite(v);
        } else {
            ok = ok && !error.empty() && error.find(word) != std::string::npos;
        }
        std::printf("%s %s: %s\n", ok ? "ok  " : "FAIL", file.c_str(),
                    read ? ("read " + std::to_string(image.width) + "x" + std::to_string(image.height)).c_str()
                         : error.c_str());
        failures += !ok;
    }
    std::printf("%d cases, %d failures\n", cases, failures);
    return failures || cases == 0 ? 1 : 0;
}
