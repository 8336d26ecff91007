// Memory a program may still take, and the check the oracle, rtpbr-render and rtpbr-diff make
// before their large allocations (docs/limits.md states each program's need).
#pragma once

#include <cstdint>
#include <string>

namespace rtpbr_tools {

// Bytes the process can still allocate: the smaller of the system's MemAvailable and the
// address-space limit (ulimit -v) less what is mapped already. UINT64_MAX if unknown.
uint64_t available_memory();

// Empty when `need` bytes (for `what`) fit in available_memory() and in `limit` (0: no limit
// of its own); otherwise the sentence "WHAT needs X of memory, Y are available".
std::string memory_shortfall(uint64_t need, uint64_t limit, const std::string &what);

}  // namespace rtpbr_tools
