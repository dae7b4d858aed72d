// tumble-mesh-reader: reads one mesh file with assimp for Tumble, in a process of its own
// (engine/io/src/mesh_reader.cpp). Not meant to be run by hand.
#include <tumble/io/mesh_import.h>

int main(int argc, char** argv) { return tumble::io::meshReaderMain(argc, argv); }
