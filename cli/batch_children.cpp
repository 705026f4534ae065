#include "cli/batch_children.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <fstream>

namespace geotex::cli {

namespace fs = std::filesystem;

pid_t spawn_child(const std::vector<std::string>& args, const std::string& log) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid != 0) return pid;
    // Child: only async-signal-safe calls until exec. The child dies with the batch (a kill
    // of the batch leaves no orphan writing into the output directory).
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);
    const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
    if (err < 0 || null < 0) ::_exit(126);
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::execv("/proc/self/exe", argv.data());
    ::_exit(127);
}

std::string failure_reason(const std::string& log, int wait_status) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.rfind("geotex: error: ", 0) == 0) last = line.substr(15);
    if (!last.empty()) return last;
    if (WIFSIGNALED(wait_status)) return std::string("crashed: ") + strsignal(WTERMSIG(wait_status));
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
