#include "mpm3d.hpp"

int main(int argc, char** argv) { return mpm3d::run_main(argc, argv); }
