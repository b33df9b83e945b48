// main.cpp -- the `rtb` executable; everything lives in cli/ (rtb_offline).
#include "cli/cli.h"

int main(int argc, char **argv) { return rtb::cli::main(argc, argv); }
