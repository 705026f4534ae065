#include "geometry/detail/mapped_file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <new>

#include "common/errors.hpp"
#include "geometry/detail/read_window.hpp"

namespace geotex::detail {
namespace {

// The file mapped on this thread: its reader's, and the SIGBUS handler's (a SIGBUS is
// delivered to the thread whose access faulted).
struct ThreadMapping {
    char* begin = nullptr;
    char* end = nullptr;                  // past the last whole page of the mapping
    char* volatile unreadable = nullptr;  // the first page that could not be read
    const char* held = nullptr;           // the pages before it were given back (release_read)
    const char* scanned = nullptr;        // a scan ahead of the parse gave back the pages before it
};
thread_local ThreadMapping t_mapping;
thread_local std::size_t t_released = 0;

struct sigaction g_previous;  // SIGBUS's action before ours, for the faults that are not ours
std::size_t g_page = 4096;    // the page size, read before the handler can run
std::once_flag g_installed;

// A page of a mapped mesh file that cannot be read (past the file's end, or a disk error):
// that page and the rest of the mapping become zeros, so that the access, made again on return,
// reads a zero and the reader goes on. mmap is not on POSIX's list of async-signal-safe calls, but
// on Linux it is a system call that takes no lock of the C library's, and there is no other way to
// mend a mapping here.
extern "C" void on_sigbus(int sig, siginfo_t* info, void* context) {
    ThreadMapping& m = t_mapping;
    char* at = static_cast<char*>(info->si_addr);
    if (m.begin != nullptr && at >= m.begin && at < m.end) {
        char* from = m.begin + static_cast<std::size_t>(at - m.begin) / g_page * g_page;
        if (::mmap(from, static_cast<std::size_t>(m.end - from), PROT_READ,
                   MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) != MAP_FAILED) {
            if (m.unreadable == nullptr) m.unreadable = from;
            return;
        }
    }
    // Not ours: what SIGBUS did before. A fault that is ignored would come again at once, so
    // that and the default both end the process with the default action.
    if ((g_previous.sa_flags & SA_SIGINFO) != 0) {
        if (g_previous.sa_sigaction != nullptr) {
            g_previous.sa_sigaction(sig, info, context);
            return;
        }
    } else if (g_previous.sa_handler != SIG_DFL && g_previous.sa_handler != SIG_IGN) {
        g_previous.sa_handler(sig);
        return;
    }
    ::signal(SIGBUS, SIG_DFL);  // the access is made again, and ends the process
}

void install_handler() {
    g_page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    struct sigaction action {};
    action.sa_sigaction = on_sigbus;
    action.sa_flags = SA_SIGINFO;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGBUS, &action, &g_previous);
}

// The end of the last whole step of kReleaseStep bytes from the pages still held to `p`; null
// when `p` is not in the file mapped on this thread.
const char* step_before(const void* p) {
    const ThreadMapping& m = t_mapping;
    const char* at = static_cast<const char*>(p);
    if (m.held == nullptr || at < m.held || at > m.end) return nullptr;
    return m.held + static_cast<std::size_t>(at - m.held) / kReleaseStep * kReleaseStep;
}

// The pages [from, to) leave memory; the file's are read from it again if touched.
void give_back(const char* from, const char* to) {
#ifdef __linux__
    madvise(const_cast<char*>(from), static_cast<std::size_t>(to - from), MADV_DONTNEED);
#else
    (void)from;
    (void)to;
#endif
}

[[noreturn]] void fail(const char* what, int error, const std::string& path) {
    throw IoError(std::string(what) + std::strerror(error), path);
}

}  // namespace

const char* map_read_only(int fd, std::size_t size) {
    void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p != MAP_FAILED) return static_cast<const char*>(p);
    if (errno == ENOMEM) throw std::bad_alloc();
    return nullptr;
}

MappedFile::MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail("cannot open mesh file: ", errno, path);
    struct stat st {};
    if (::fstat(fd, &st) != 0 || st.st_size < 0) {
        const int error = errno;
        ::close(fd);
        fail("cannot read mesh file: ", error, path);
    }
    size_ = static_cast<std::size_t>(st.st_size);
    if (size_ == 0) {  // nothing to map (mmap refuses a length of 0)
        ::close(fd);
        return;
    }
    const char* p = nullptr;
    try {
        p = map_read_only(fd, size_);
    } catch (...) {
        ::close(fd);
        throw;
    }
    const int error = errno;
    if (p == nullptr) {
        ::close(fd);
        fail("cannot map mesh file into memory: ", error, path);
    }
    // Kept open to measure the file again: the mapping keeps the file, not its length.
    fd_ = fd;
    data_ = const_cast<char*>(p);
#ifdef __linux__
    // The readers go forward: read ahead, and the pages behind may go first.
    ::madvise(data_, size_, MADV_SEQUENTIAL);
#endif
    std::call_once(g_installed, install_handler);
    const std::size_t pages = (size_ + g_page - 1) / g_page;
    t_mapping.begin = data_;
    t_mapping.end = data_ + pages * g_page;
    t_mapping.unreadable = nullptr;
    t_mapping.held = t_mapping.scanned = data_;
}

MappedFile::~MappedFile() {
    if (data_ == nullptr) return;
    t_mapping.begin = t_mapping.end = nullptr;
    t_mapping.held = t_mapping.scanned = nullptr;
    ::munmap(data_, size_);
    ::close(fd_);
}

std::optional<std::size_t> MappedFile::unreadable_from() const {
    if (data_ == nullptr) return std::nullopt;
    if (t_mapping.unreadable != nullptr)
        return static_cast<std::size_t>(t_mapping.unreadable - data_);
    // Cut short within the last page the reader touched: the bytes past the new end read as
    // zeros without a signal.
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && st.st_size >= 0 && static_cast<std::size_t>(st.st_size) < size_)
        return static_cast<std::size_t>(st.st_size);
    return std::nullopt;
}

void release_read(const void* p) {
    const char* to = step_before(p);
    if (to == nullptr || to == t_mapping.held) return;
    give_back(t_mapping.held, to);  // the readers do not look back
    t_released += static_cast<std::size_t>(to - t_mapping.held);
    t_mapping.held = to;
}

void release_scanned(const void* p) {
    const char* to = step_before(p);
    if (to == nullptr) return;
    const char* from = std::max(t_mapping.held, t_mapping.scanned);
    if (to <= from) return;
    give_back(from, to);  // the window stays where the parse is
    t_mapping.scanned = to;
}

std::size_t released_read_bytes() { return t_released; }

}  // namespace geotex::detail
