// Large blocks of the geotex program in transparent huge pages.
//
// A 20-million-face mesh lives in a few dozen arrays of 80 to 500 MB (positions, depths,
// adjacency, the triangle tree), and each stage allocates and fills new ones. glibc serves
// every block above its mmap threshold (at most 32 MB) with a fresh mapping, so every 4 KiB
// page of it faults on first touch: at sphere-1 level 10 a quarter of the run's cycles went to
// page faults and zeroing, and each stage cost more per face than at level 8, whose arrays are
// below the threshold and reuse the heap's pages. Linux hands out 2 MiB pages where a range
// asks for them (MADV_HUGEPAGE; the usual "madvise" setting of
// /sys/kernel/mm/transparent_hugepage/enabled): 512 times fewer faults for the same bytes.
//
// glibc has this as a switch (the tunable glibc.malloc.hugetlb=1), but it is read from the
// environment at start-up only, so the program would have to run itself again. Replacing the
// global operator new is the in-process way: the block still comes from malloc (operator
// delete's default, free, releases it), and only whole 2 MiB pages inside it are advised.
// The program only: a library must not replace its host's allocator. Not under
// AddressSanitizer, whose own operator new checks that new and delete pair up.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

// GCC says it builds under AddressSanitizer with __SANITIZE_ADDRESS__; clang 14 (the fuzz
// build's) only through __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define GEOTEX_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GEOTEX_UNDER_ASAN 1
#endif
#endif

#if !defined(GEOTEX_UNDER_ASAN) && defined(__linux__)
#include <sys/mman.h>

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
// Smaller blocks come from the heap, whose pages are reused; from here up a block spans
// whole huge pages worth advising.
constexpr std::size_t kAdviseFrom = std::size_t{4} << 20;

// What the standard asks of operator new: call the new-handler until malloc succeeds, and
// throw std::bad_alloc when there is none.
void* allocate(std::size_t size) {
    void* p = nullptr;
    while ((p = std::malloc(size > 0 ? size : 1)) == nullptr) {
        const std::new_handler handler = std::get_new_handler();
        if (handler == nullptr) throw std::bad_alloc();
        handler();
    }
    if (size >= kAdviseFrom) {
        const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(p);
        const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
        const std::uintptr_t last = (begin + size) & ~(kHugePage - 1);
        // Advice only: where the kernel has no huge pages (or THP is "never") it is refused
        // or ignored, and the block works as before.
        if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
    }
    return p;
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }

#endif
