// freeform: the command-line tool. See `freeform --help` and docs/cli.md; the commands are the
// freeform_cli library (cli/command.h).

#include <iostream>

#include "cli/command.h"

int main(int argc, char** argv)
{
    return freeform::cli::run(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
