// rtpbr_common/memory.hpp.
#include "rtpbr_common/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace rtpbr_tools {

uint64_t available_memory() {
    uint64_t avail = UINT64_MAX;
    if (FILE *f = std::fopen("/proc/meminfo", "r")) {
        char line[256];
        unsigned long long kb;
        while (std::fgets(line, sizeof line, f))
            if (std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1) {
                avail = uint64_t(kb) * 1024;
                break;
            }
        std::fclose(f);
    }
    struct rlimit lim;
    if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
        uint64_t mapped = 0;
        if (FILE *f = std::fopen("/proc/self/statm", "r")) {
            unsigned long long pages;
            if (std::fscanf(f, "%llu", &pages) == 1)
                mapped = uint64_t(pages) * uint64_t(sysconf(_SC_PAGESIZE));
            std::fclose(f);
        }
        const uint64_t room = uint64_t(lim.rlim_cur) > mapped ? uint64_t(lim.rlim_cur) - mapped : 0;
        avail = std::min(avail, room);
    }
    return avail;
}

namespace {

// GiB with two decimals from 1 GiB on, MiB below (a --memory-limit of a few MiB stays readable).
std::string amount(uint64_t bytes) {
    char buf[64];
    if (bytes >= (uint64_t(1) << 30))
        std::snprintf(buf, sizeof buf, "%.2f GiB", double(bytes) / 1073741824.0);
    else
        std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / 1048576.0);
    return buf;
}

}  // namespace

std::string memory_shortfall(uint64_t need, uint64_t limit, const std::string &what) {
    uint64_t avail = available_memory();
    if (limit) avail = std::min(avail, limit);
    if (need <= avail) return std::string();
    return what + " needs " + amount(need) + " of memory, " + amount(avail) + " are available";
}

}  // namespace rtpbr_tools
