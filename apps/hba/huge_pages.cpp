// The tool's global operator new and delete: large blocks ask the kernel for
// transparent huge pages (2 MiB) before they are first touched.
//
// Why: a run fills hundreds of MB of fresh arrays at every association
// (world positions, cell numbers, point ids), freed and allocated again
// round after round. Each 4 KiB page of them costs a page fault, and on
// virtual machines a fault is expensive: the kernel took a quarter of the
// CPU time of a 1000-frame run (docs/cli.md, "Memory"). Most kernels offer huge pages only on request (THP
// mode "madvise"); with them a block faults once per 2 MiB. Blocks are still malloc's: only a hint is added,
// so `free`, malloc_trim and the results are unchanged. Lives in the executable (not the library), so that a
// program linking libhba keeps its own allocator.
#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

// Under AddressSanitizer the tool keeps the sanitizer's own operators, which
// check that new pairs with delete and new[] with delete[].
#if !defined(__SANITIZE_ADDRESS__)

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
// Smaller blocks are left alone: too few whole huge pages in them to matter.
constexpr std::size_t kAdviseFrom = std::size_t{8} << 20;

void adviseHugePages(void* block, std::size_t size) {
  if (size < kAdviseFrom) return;
  const auto start = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t first = (start + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (start + size) & ~(kHugePage - 1);
  // A refusal (no THP, an old kernel) leaves ordinary pages: nothing to do.
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

void* allocate(std::size_t size) {
  if (size == 0) size = 1;
  for (;;) {
    if (void* block = std::malloc(size)) {
      adviseHugePages(block, size);
      return block;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

// The nothrow forms call these. Every delete is replaced too, so that a
// checker that watches malloc and free (valgrind) sees each block freed as
// it was allocated; the aligned forms stay the library's (aligned_alloc and
// free).
void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* block) noexcept { std::free(block); }
void operator delete[](void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
void operator delete[](void* block, std::size_t) noexcept { std::free(block); }
void operator delete(void* block, const std::nothrow_t&) noexcept { std::free(block); }
void operator delete[](void* block, const std::nothrow_t&) noexcept { std::free(block); }
#endif
