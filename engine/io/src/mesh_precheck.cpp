#include "mesh_precheck.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace tumble::io {

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

// A PLY header is text lines from "ply" to "end_header", also in binary files. assimp 5.2's
// PLY reader loops for ever at the end of a header that has no "end_header" line.
std::optional<std::string> plyHeaderWithoutEnd(std::ifstream& in) {
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string first;
        words >> first;
        if (first == "end_header") return std::nullopt;
    }
    return std::string("is a PLY file whose header has no end_header line");
}

}  // namespace

std::optional<std::string> meshFileAssimpWouldHangOn(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;  // importMesh says why
    char magic[3] = {};
    in.read(magic, 3);
    const bool plyMagic = in.gcount() == 3 && lower(std::string(magic, 3)) == "ply";
    if (plyMagic || lower(file.extension().string()) == ".ply") {
        in.clear();
        in.seekg(0);
        return plyHeaderWithoutEnd(in);
    }
    return std::nullopt;
}

}  // namespace tumble::io
