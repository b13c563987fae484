// geokiosk-import: the importer, linked separately from the kiosk runtime so that GDAL, netCDF
// and their dependencies never load into a playing kiosk. Users normally run it through
// `geokiosk import ...`, which execs this binary with the words after "import".
#include "runtime/app/ImportCli.h"

#include <string>
#include <vector>

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    return kiosk::app::runImportCli(args);
}
