// The memory a process may count on: the machine's, or its container's limit when smaller
// (radiosity/machine_memory.h).
#include <gtest/gtest.h>

#include <unistd.h>

#include "radiosity/machine_memory.h"

using namespace radiosity;

TEST(MachineMemory, ACgroupLimitIsReadAsTheKernelWritesIt) {
    EXPECT_EQ(parseCgroupMemoryLimit("8589934592\n"), size_t{8589934592});  // v2: bytes
    EXPECT_EQ(parseCgroupMemoryLimit("max\n"), 0u);                         // v2: no limit
    EXPECT_EQ(parseCgroupMemoryLimit(""), 0u);
    EXPECT_EQ(parseCgroupMemoryLimit("12x"), 0u);  // malformed: not a limit
    EXPECT_EQ(parseCgroupMemoryLimit("-1"), 0u);
    // v1's "no limit" is a number near 2^63, larger than any machine: min() keeps the machine.
    EXPECT_EQ(parseCgroupMemoryLimit("9223372036854771712"), size_t{9223372036854771712u});
}

TEST(MachineMemory, IsAtMostThePhysicalMemoryAndEnoughToRunTheSuite) {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    ASSERT_GT(pages, 0);
    ASSERT_GT(pageSize, 0);
    const size_t physical = static_cast<size_t>(pages) * static_cast<size_t>(pageSize);
    EXPECT_LE(usableMemory(), physical);
    EXPECT_GT(usableMemory(), size_t{1} << 28);  // any machine (or container) that runs the suite
}
