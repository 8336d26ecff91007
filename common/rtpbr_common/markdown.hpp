// rtpbr tools: generated sections of committed Markdown pages (the LUT reports in
// shaderlib/luts/*.md). A section runs from a line starting "<!-- TAG:begin" to the line
// "<!-- TAG:end -->"; the generator writes both marker lines itself.
#ifndef RTPBR_TOOLS_MARKDOWN_HPP
#define RTPBR_TOOLS_MARKDOWN_HPP

#include <cstdio>
#include <string>
#include <vector>

namespace rtpbr_tools {

// Prints to stdout the rest of a Markdown table's head after its leading cells: a cell per
// value (cell_format: a printf format of one double, such as " %g deg |"), then the separator
// row, lead_columns cells for the leading columns and one per value.
inline void print_markdown_head(const std::vector<float> &values, const char *cell_format, int lead_columns) {
    for (float v : values)
        std::printf(cell_format, double(v));
    std::printf("\n|");
    for (int i = 0; i < lead_columns; i++)
        std::printf("---|");
    for (size_t i = 0; i < values.size(); i++)
        std::printf("---|");
    std::printf("\n");
}

// Replaces section TAG of the page at `path` with `section` (which must hold its own
// markers), or appends `section` after a blank line when the page has no such section yet
// (or does not exist). The rest of the page is kept byte for byte. On failure returns false
// and sets `error`.
bool replace_markdown_section(const std::string &path, const std::string &tag, const std::string &section,
                              std::string &error);

} // namespace rtpbr_tools

#endif
