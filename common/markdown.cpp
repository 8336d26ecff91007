// rtpbr common: generated Markdown sections (see rtpbr_common/markdown.hpp).
#include "rtpbr_common/markdown.hpp"

#include <fstream>
#include <sstream>

namespace rtpbr_tools {

bool replace_markdown_section(const std::string &path, const std::string &tag, const std::string &section,
                              std::string &error) {
    std::string text;
    {
        std::ifstream in(path);
        if (in) {
            std::stringstream ss;
            ss << in.rdbuf();
            text = ss.str();
        }
    }
    const std::string begin = "<!-- " + tag + ":begin", end = "<!-- " + tag + ":end -->\n";
    const size_t b = text.find(begin), e = text.find(end);
    if (b != std::string::npos && e != std::string::npos && e > b)
        text = text.substr(0, b) + section + text.substr(e + end.size());
    else
        text += (text.empty() ? "" : "\n") + section;
    std::ofstream out(path);
    out << text;
    out.close();
    if (!out) {
        error = "cannot write " + path;
        return false;
    }
    return true;
}

} // namespace rtpbr_tools
