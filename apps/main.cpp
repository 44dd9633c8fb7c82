#include "apps/egg/commands.hpp"

#include <malloc.h>

int main(int argc, char** argv) {
  // Every stage allocates and frees blocks of megabytes (mesh tables, window arrays, maps). By
  // default glibc hands blocks above 128 kB back to the OS on free, and the next stage pays a page
  // fault per fresh page: the geodesic tables of the 5k-vertex bench surface took 7.5 ms to build
  // the first time and 1.5 ms once the memory was the process's own. Keep such blocks in the heap
  // (up to 64 MB each, and up to 256 MB of free heap before trimming).
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  return egg::app::runCli(argc, argv);
}
