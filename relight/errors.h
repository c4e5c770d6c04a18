// The errors relight reports, at the bottom of relight/: every layer above (io/,
// pipeline/, display/, dynamic/, the command) throws these, and none has to include a
// reader to do so. The commands (relight/main.cpp, viewer/main.cpp) exit with exitCode(),
// one code for each kind of failure whichever file it concerns:
//   InputError    2: the user's input is wrong; what() names the file and line or JSON key.
//   OutputError   3: an output cannot be written (an image, the prepared-state cache, a
//                    report, an edit, a debug-views folder: a missing or blocked folder, a
//                    full disk); what() names the file and why. Atomic writes
//                    (relight/io/atomic_write.h) leave the old file as it was.
//   anything else 1: a failure of the machine or of relight (out of memory, a solver that
//                    did not converge).
#pragma once

#include <exception>
#include <stdexcept>

namespace relight {

/// An error in the user's input; what() names the file and line or key.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// An output that cannot be written; what() names the file or folder and why.
struct OutputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The exit code of a command that failed with `e` (see above).
inline int exitCode(const std::exception& e) {
    if (dynamic_cast<const InputError*>(&e)) return 2;
    if (dynamic_cast<const OutputError*>(&e)) return 3;
    return 1;
}

}  // namespace relight
