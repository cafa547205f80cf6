#pragma once
// The exit codes of every subcommand, in one table (README.md and `grainshock --help` show it).
// Subcommands do not call std::exit: they throw, and main() maps what they throw to a code after
// the stack has unwound, so files being written are finished or removed first.
#include <stdexcept>
#include <string>

namespace gs::app {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitUserError = 1,      // UserError: a file, a folder or physics that cannot work
  kExitUsageError = 2,     // the command line itself: unknown word, missing or malformed value,
                           // a value outside its flag's range (CLI11's or gs::UsageError)
  kExitInterrupted = 130,  // SIGINT or SIGTERM; what was written is complete and readable
};

// `compare` answers "not alike" with 1 and its bad input with 2, as cmp and diff do.
inline constexpr int kExitNotAlike = 1;
inline constexpr int kExitCompareTrouble = 2;

// Ends the program with `code`, after a subcommand has said all it had to say.
struct Exit {
  int code;
};

// A UserError that ends with its own code rather than 1 (compare's bad input).
class CodedError : public std::runtime_error {
 public:
  CodedError(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

// The table as `grainshock --help` ends with it; README.md has the same.
inline constexpr const char* kExitCodeHelp =
    "Exit codes:\n"
    "  0    success (compare: the pictures are alike)\n"
    "  1    user error: a file, folder or setting that cannot work (compare: not alike)\n"
    "  2    usage error: unknown subcommand or flag, missing or malformed value,\n"
    "       a value outside the flag's range, flags that exclude each other\n"
    "       (compare: missing file, different sizes, not a PNG or movie)\n"
    "  130  interrupted by SIGINT or SIGTERM; the files written so far are complete";

}  // namespace gs::app
