// render: the command-line front end of the renderer.
#include <string>
#include <vector>

#include "render_command.h"
#include "serve.h"

int main(int argc, char **argv) {
    if (argc == 2 && std::string(argv[1]) == "--serve") return mcval::serveRenderRequests();
    return mcval::runRenderCommand(std::vector<std::string>(argv + 1, argv + argc));
}
