// tumble: the editor, or the headless command line when a command-line flag is given.
#include "cli.h"

#include <iostream>
#include <string>
#include <vector>

#ifdef TUMBLE_HAVE_UI
#include "editor_main.h"
#endif

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
#ifdef TUMBLE_HAVE_UI
    tumble::cli::setImageRenderer(&tumble::ui::renderImages);
#endif
    if (tumble::cli::wantsCommandLine(args)) return tumble::cli::run(args, std::cout, std::cerr);
#ifdef TUMBLE_HAVE_UI
    return tumble::ui::runEditor(argc, argv);
#else
    std::cerr << "tumble: this build has no editor (configured with TUMBLE_BUILD_UI=OFF); "
                 "use --headless SCENE (see --help)\n";
    return 1;
#endif
}
