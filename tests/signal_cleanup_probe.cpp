// A SIGINT taken by another thread than the one writing the outputs leaves no temporary
// file (cli/output.cpp). The writing thread keeps the signal off, so that a second thread's
// handler takes it; as soon as the handler has removed the first temporary file, the
// writer goes on to its next outputs, as geotex's main thread does while a TBB worker runs
// the handler. Before the handler waited for file creations and the writer looked for the
// signal, the writer created its next temporary file in the moment before the process ended,
// and it stayed.
//   signal_cleanup_probe ROUNDS
// Exits 0 when every round's process ended by SIGINT and left its directory (a new one in
// $TMPDIR or /tmp, removed at the end) empty.
//   signal_cleanup_probe --slots
// Checks that an output the handler could not remove is refused rather than written: the
// handler knows 16 temporary files at once, and a 17th output of one set is an error with
// kExitOutput that names it, leaves no file, and frees its slots with the set; an output
// whose temporary file could not be created holds no slot.
#include <dirent.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "cli/output.hpp"

namespace {

std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> names;
    DIR* d = ::opendir(dir.c_str());
    if (d == nullptr) return names;
    while (const dirent* e = ::readdir(d))
        if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0)
            names.emplace_back(e->d_name);
    ::closedir(d);
    return names;
}

// The child: writes a.out, tells the parent, and once the handler has removed a.out's
// temporary file writes b.out and c.out. It must never end but by the signal.
[[noreturn]] void write_outputs(const std::string& dir, int ready_fd) {
    sigset_t interrupt;
    sigemptyset(&interrupt);
    sigaddset(&interrupt, SIGINT);
    ::pthread_sigmask(SIG_BLOCK, &interrupt, nullptr);
    geotex::cli::install_signal_cleanup();
    std::atomic<bool> listening{false};
    std::thread handler_thread([&] {
        ::pthread_sigmask(SIG_UNBLOCK, &interrupt, nullptr);
        listening = true;
        for (;;) ::pause();
    });
    handler_thread.detach();
    while (!listening) std::this_thread::yield();

    geotex::cli::OutputSet outputs;
    const auto text = [](std::ostream& out) { out << "complete\n"; };
    outputs.add(dir + "/a.out", text);
    if (::write(ready_fd, "r", 1) != 1) std::_Exit(3);
    // The first temporary file of the process (cli/output.cpp's temporary_name).
    const std::string first = dir + "/.a.out.tmp." + std::to_string(::getpid()) + ".0";
    struct stat st {};
    while (::stat(first.c_str(), &st) == 0) {
    }
    try {
        outputs.add(dir + "/b.out", text);
        outputs.add(dir + "/c.out", text);
        outputs.commit();
    } catch (...) {
        std::_Exit(4);
    }
    std::_Exit(5);
}

// --slots: 16 outputs of one set are written, the 17th is refused; none is left behind.
int check_slots(const std::string& dir) {
    const auto text = [](std::ostream& out) { out << "complete\n"; };
    const auto name = [&](int k) { return dir + "/out-" + std::to_string(k); };
    int failures = 0;
    {
        geotex::cli::OutputSet outputs;
        // Outputs whose temporary file cannot be created (no such directory) hold no slot.
        for (int k = 0; k < 20; ++k) {
            try {
                outputs.add(dir + "/missing/out-" + std::to_string(k), text);
                ++failures;
            } catch (const geotex::cli::CliError&) {
            }
        }
        for (int k = 0; k < 16; ++k) outputs.add(name(k), text);
        try {
            outputs.add(name(16), text);
            std::printf("a 17th output of one set was written, unknown to the signal's handler\n");
            ++failures;
        } catch (const geotex::cli::CliError& e) {
            const std::string what = e.what();
            if (e.code() != geotex::cli::kExitOutput || what.find(name(16)) != 0 ||
                what.find("16 output files are being written already") == std::string::npos) {
                std::printf("the 17th output's error is not the one meant: %s\n", what.c_str());
                ++failures;
            }
        }
    }  // the set is dropped uncommitted: its temporary files are removed
    if (!entries(dir).empty()) {
        std::printf("a dropped set left files\n");
        ++failures;
    }
    // The dropped set's slots are free again.
    geotex::cli::OutputSet again;
    for (int k = 0; k < 16; ++k) again.add(name(k), text);
    again.commit();
    if (entries(dir).size() != 16) {
        std::printf("a set after a dropped one did not write its 16 outputs\n");
        ++failures;
    }
    for (const std::string& file : entries(dir)) ::unlink((dir + "/" + file).c_str());
    return failures;
}

}  // namespace

int main(int argc, char** argv) {
    const bool slots = argc == 2 && std::strcmp(argv[1], "--slots") == 0;
    if (argc != 2) {
        std::fprintf(stderr, "usage: signal_cleanup_probe ROUNDS | --slots\n");
        return 2;
    }
    const char* tmpdir = std::getenv("TMPDIR");
    std::string pattern = std::string(tmpdir != nullptr ? tmpdir : "/tmp") + "/signal-probe.XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) {
        std::perror("signal_cleanup_probe: mkdtemp");
        return 2;
    }
    const std::string dir = pattern;
    if (slots) {
        int failures = 0;
        try {
            failures = check_slots(dir);
        } catch (const std::exception& e) {
            std::printf("an output that should have been written was refused: %s\n", e.what());
            failures = 1;
        }
        ::rmdir(dir.c_str());
        std::printf("%s\n", failures == 0 ? "the 17th output was refused" : "failed");
        return failures == 0 ? 0 : 1;
    }
    const int rounds = std::atoi(argv[1]);
    int failures = 0;
    for (int round = 0; round < rounds; ++round) {
        int ready[2];
        if (::pipe(ready) != 0) return 2;
        const pid_t child = ::fork();
        if (child < 0) return 2;
        if (child == 0) {
            ::close(ready[0]);
            write_outputs(dir, ready[1]);
        }
        ::close(ready[1]);
        char byte = 0;
        const bool got_ready = ::read(ready[0], &byte, 1) == 1;
        ::close(ready[0]);
        if (got_ready) ::kill(child, SIGINT);
        int status = 0;
        ::waitpid(child, &status, 0);
        const std::vector<std::string> left = entries(dir);
        const bool by_signal = WIFSIGNALED(status) && WTERMSIG(status) == SIGINT;
        if (!got_ready || !by_signal || !left.empty()) {
            ++failures;
            std::printf("round %d: %s", round,
                        !got_ready  ? "the writer never reached its first output"
                        : by_signal ? "ended by SIGINT"
                                    : "not ended by SIGINT");
            if (WIFEXITED(status)) std::printf(" (exit %d)", WEXITSTATUS(status));
            if (!left.empty()) std::printf(", files left:");
            for (const std::string& name : left) {
                std::printf(" %s", name.c_str());
                ::unlink((dir + "/" + name).c_str());
            }
            std::printf("\n");
        }
    }
    ::rmdir(dir.c_str());
    std::printf("%d of %d rounds failed\n", failures, rounds);
    return failures == 0 ? 0 : 1;
}
