#include <string>
#include <vector>

#include "runtime/app/Cli.h"

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    return kiosk::app::runCli(args);
}
