#include "apps/commands/commands.hpp"

int main(int argc, char** argv) { return egg::app::runCli(argc, argv); }
