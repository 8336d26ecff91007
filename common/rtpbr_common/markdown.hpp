// rtpbr tools: generated sections of committed Markdown pages (the LUT reports in
// shaderlib/luts/*.md). A section runs from a line starting "<!-- TAG:begin" to the line
// "<!-- TAG:end -->"; the generator writes both marker lines itself.
#ifndef RTPBR_TOOLS_MARKDOWN_HPP
#define RTPBR_TOOLS_MARKDOWN_HPP

#include <string>

namespace rtpbr_tools {

// Replaces section TAG of the page at `path` with `section` (which must hold its own
// markers), or appends `section` after a blank line when the page has no such section yet
// (or does not exist). The rest of the page is kept byte for byte. On failure returns false
// and sets `error`.
bool replace_markdown_section(const std::string &path, const std::string &tag, const std::string &section,
                              std::string &error);

} // namespace rtpbr_tools

#endif
