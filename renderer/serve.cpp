#include "serve.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

#include "render_command.h"

namespace mcval {

namespace {

/// Longest argument and most arguments a request may hold: far above any real command line.
constexpr size_t kMaxArgumentBytes = 1 << 20;
constexpr size_t kMaxArguments = 4096;
/// How long a worker thread spins after a render that used every core, as the Python module's renders do: the
/// caller reads the image (a few ms at 128², tens at 768²) and asks for the next one, and waking a sleeping
/// thread pool costs a small render a third of its time. With 30 ms, Mitsuba over ours in the worker fell
/// from 1.07 to 0.88 on cornell simple 128² and from 1.70 to 1.53 on highpoly ao 768².
constexpr int kKeepWarmMilliseconds = 100;

/// A decimal number on a line of its own; false at the end of the input or on anything else.
bool readCount(size_t limit, size_t &value) {
    char line[32];
    if (!std::fgets(line, sizeof line, stdin)) return false;
    if (!std::isdigit(static_cast<unsigned char>(line[0]))) return false;
    char *end = nullptr;
    const unsigned long long n = std::strtoull(line, &end, 10);
    if (end == line || *end != '\n' || n > limit) return false;
    value = static_cast<size_t>(n);
    return true;
}

}  // namespace

int serveRenderRequests() {
    // Answers go to the original stdout; from here on fd 1 is stderr, so that whatever a render prints
    // (a --help, a library's message) lands in the log and never among the answers.
    const int answerFd = dup(STDOUT_FILENO);
    if (answerFd < 0 || dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
        std::perror("render --serve: cannot set up its output");
        return 3;
    }
    FILE *answers = fdopen(answerFd, "w");
    if (!answers) {
        std::perror("render --serve: cannot set up its output");
        return 3;
    }
    // The greeting tells the caller that this binary speaks the framing (an older one would not).
    std::fprintf(answers, "mcval-serve 1\n");
    std::fflush(answers);
    size_t count = 0;
    while (readCount(kMaxArguments, count)) {
        std::vector<std::string> args(count);
        for (std::string &arg : args) {
            size_t length = 0;
            if (!readCount(kMaxArgumentBytes, length)) {
                std::fprintf(stderr, "render --serve: expected an argument's length on a line of its own\n");
                return 3;
            }
            arg.resize(length);
            if (length > 0 && std::fread(arg.data(), 1, length, stdin) != length) {
                std::fprintf(stderr, "render --serve: the input ended inside an argument\n");
                return 3;
            }
        }
        const int status = runRenderCommand(args, kKeepWarmMilliseconds);
        std::fflush(stdout);
        std::fflush(stderr);
        std::fprintf(answers, "%d\n", status);
        std::fflush(answers);
    }
    if (!std::feof(stdin)) {
        std::fprintf(stderr, "render --serve: expected a request's argument count on a line of its own\n");
        return 3;
    }
    return 0;
}

}  // namespace mcval
