#include "radiosity/machine_memory.h"

#include <charconv>
#include <fstream>
#include <string>

#include <unistd.h>

namespace radiosity {

namespace {

size_t physicalMemory() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0) return 0;
    return static_cast<size_t>(pages) * static_cast<size_t>(pageSize);
}

size_t cgroupLimitFromFile(const char* path) {
    std::ifstream in(path);
    std::string text;
    if (!in || !std::getline(in, text)) return 0;
    return parseCgroupMemoryLimit(text);
}

}  // namespace

size_t parseCgroupMemoryLimit(std::string_view text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
    if (text.empty() || text == "max") return 0;
    unsigned long long bytes = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), bytes);
    if (ec != std::errc{} || end != text.data() + text.size()) return 0;
    return static_cast<size_t>(bytes);
}

size_t usableMemory() {
    const size_t physical = physicalMemory();
    size_t usable = physical;
    // The namespace's own cgroup is what a containerised process sees at these paths (v2,
    // then v1); v1 writes "no limit" as a number near 2^63, larger than any machine.
    for (const char* path :
         {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        const size_t limit = cgroupLimitFromFile(path);
        if (limit > 0 && (usable == 0 || limit < usable)) usable = limit;
    }
    return usable;
}

}  // namespace radiosity
