// Whether a run fits in this machine's memory, asked before the run allocates (issue 46): a size
// flag (a mesh edge of 1e-6 c, an image a million pixels wide) must be refused at once with its
// estimate, not end in std::bad_alloc after minutes or be killed by the kernel.
#pragma once

#include <cstdint>
#include <string>

namespace finverse {

// Physical memory of the machine [bytes] (sysconf); 0 when unknown.
std::uint64_t physical_memory_bytes();

// Throws finverse::Error "<what>: needs about X GiB, more than the Y GiB of this machine" when the
// estimate exceeds 80 % of the physical memory (or is not finite). `what` names the flag or key
// and the size it asks for.
void require_memory(double bytes, const std::string& what);

}  // namespace finverse
