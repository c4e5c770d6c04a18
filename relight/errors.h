// The errors relight reports, at the bottom of relight/: every layer above (io/,
// pipeline/, display/, dynamic/, the command) throws these, and none has to include a
// reader to do so. The command maps them to exit codes (relight/main.cpp):
//   InputError   2: the user's input is wrong; what() names the file and line or JSON key.
//   anything else 1: a failure of the machine or of relight (out of memory, a file that
//                    cannot be written, a solver that did not converge).
#pragma once

#include <stdexcept>

namespace relight {

/// An error in the user's input; what() names the file and line or key.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace relight
