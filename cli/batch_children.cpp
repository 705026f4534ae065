#include "cli/batch_children.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "cli/commands.hpp"
#include "cli/output.hpp"

namespace geotex::cli {

namespace fs = std::filesystem;

pid_t spawn_child(const std::function<int()>& work, const std::string& log) {
    // The batch's own stop handlers must not run in the child: the signals wait, blocked,
    // until the child has installed its handlers (and the parent is past the fork).
    sigset_t stops, before;
    sigemptyset(&stops);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stops, sig);
    ::sigprocmask(SIG_BLOCK, &stops, &before);
    std::fflush(nullptr);  // nothing buffered is written twice
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid != 0) {
        const int fork_errno = errno;
        ::sigprocmask(SIG_SETMASK, &before, nullptr);
        errno = fork_errno;
        return pid;
    }
    // The child dies with the batch: a kill of the batch leaves no orphan writing into the
    // output directory.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);
    const int err =
        ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
    if (err < 0 || null < 0) ::_exit(126);
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::close(err);
    ::close(null);
    install_signal_cleanup();
    ::sigprocmask(SIG_SETMASK, &before, nullptr);
    const int code = run_command(work);
    // _exit, not exit: the batch's static objects belong to the parent, which destroys them.
    std::fflush(nullptr);
    ::_exit(code);
}

std::string failure_reason(const std::string& log, int wait_status) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.rfind("geotex: error: ", 0) == 0) last = line.substr(15);
    if (!last.empty()) return last;
    if (WIFSIGNALED(wait_status))
        return std::string("crashed: ") + strsignal(WTERMSIG(wait_status));
    return "exited with code " + std::to_string(WEXITSTATUS(wait_status));
}

void remove_child_temporaries(const fs::path& dir, pid_t pid) {
    const std::string mark = ".tmp." + std::to_string(pid) + ".";
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::error_code removed;
        if (name.size() > 1 && name[0] == '.' && name.find(mark) != std::string::npos)
            fs::remove(it->path(), removed);
    }
}

}  // namespace geotex::cli
