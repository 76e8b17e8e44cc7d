// The splinecal command-line tool. Everything lives in the front end (src/cli/front_end.cc).
#include "splinecal/cli/command.h"

int main(int argc, char** argv) { return splinecal::cli::Main(argc, argv); }
