#pragma once
// Hands the heap's free pages back to the system. A refinement block builds
// and drops hundreds of MB of small allocations (plane features, clusters);
// the allocator keeps those pages, so the next block's peak would stack on
// top of them. Where the allocator cannot (not glibc), it does nothing.
namespace hba {

void releaseFreedMemory();

}  // namespace hba
