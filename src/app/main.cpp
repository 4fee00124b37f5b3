// caustica: entry point.
#include "app/cli.h"

int main(int argc, char** argv) { return caustica::run_cli(argc, argv); }
