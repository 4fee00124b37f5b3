// The caustica command line.
#pragma once

namespace caustica {

// Runs the command line; returns the process exit code (0 success, 1 bad input, 2 internal error).
int run_cli(int argc, char** argv);

}  // namespace caustica
