// rrf: command-line front end of RRF Workbench. Subcommands are registered in cli_*.cpp.
#include <cstdio>
#include <cstring>
#include <string>

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::printf("usage: rrf <command> [options]\n");
        return argc < 2 ? 2 : 0;
    }
    std::fprintf(stderr, "rrf: unknown command '%s'\n", argv[1]);
    return 2;
}
