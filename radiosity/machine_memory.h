// The memory this process may count on: the machine's physical memory, or its container's
// limit when that is smaller. A preparation run in a container (a CI runner, a render
// node) that reads only the host's memory would plan for memory it cannot have and be
// killed by the container's out-of-memory killer instead of ending with a message.
#pragma once

#include <cstddef>
#include <string_view>

namespace radiosity {

/// min(physical memory, the cgroup's memory limit), in bytes; 0 when the system says
/// neither.
size_t usableMemory();

/// A cgroup memory limit as its file holds it (v2 memory.max: bytes or "max"; v1
/// memory.limit_in_bytes: bytes, a huge number meaning none), in bytes; 0 for "max", an
/// empty or malformed text: no limit.
size_t parseCgroupMemoryLimit(std::string_view text);

}  // namespace radiosity
