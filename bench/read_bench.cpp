// Reading speed of every mesh format on one mesh: the mesh (a PLY) is written as binary and
// ASCII PLY, OBJ, OFF, ASCII and binary STL into a directory, each file is read back with
// read_mesh_file (best of --repeat runs) and checked against the PLY, corner by corner. Not a
// test: prints a Markdown table. bench/read_bench.sh runs it beside the previous reader.
//
//   geotex_read_bench MESH.ply [--dir DIR] [--repeat 3] [--reuse] [--only OBJ]
//
// --reuse keeps the files of an earlier run in DIR; --only times one format (for a profiler).

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/mesh_io.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Coordinates as the ASCII PLY writer puts floats: the shortest text that reads back to the
// same float, so that every text format holds the same numbers.
void append_coord(std::string& out, double v) {
    char tmp[64];
    const auto res = std::to_chars(tmp, tmp + sizeof tmp, static_cast<float>(v));
    out.append(tmp, res.ptr);
}

void append_int(std::string& out, long v) {
    char tmp[32];
    const auto res = std::to_chars(tmp, tmp + sizeof tmp, v);
    out.append(tmp, res.ptr);
}

void append_point(std::string& out, const Eigen::Vector3d& p) {
    for (int k = 0; k < 3; ++k) {
        out += ' ';
        append_coord(out, p[k]);
    }
}

std::string to_obj(const geotex::PolygonSoup& s) {
    std::string out = "# written by geotex_read_bench\n";
    for (const Eigen::Vector3d& p : s.positions) {
        out += 'v';
        append_point(out, p);
        out += '\n';
    }
    for (int f = 0; f < s.num_polygons(); ++f) {
        out += 'f';
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            out += ' ';
            append_int(out, s.face_indices[j] + 1);
        }
        out += '\n';
    }
    return out;
}

std::string to_off(const geotex::PolygonSoup& s) {
    std::string out = "OFF\n" + std::to_string(s.positions.size()) + " " +
                      std::to_string(s.num_polygons()) + " 0\n";
    for (const Eigen::Vector3d& p : s.positions) {
        append_point(out, p);
        out += '\n';
    }
    for (int f = 0; f < s.num_polygons(); ++f) {
        append_int(out, s.face_offsets[f + 1] - s.face_offsets[f]);
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            out += ' ';
            append_int(out, s.face_indices[j]);
        }
        out += '\n';
    }
    return out;
}

// Triangles only (the synthetic spheres are triangle meshes); normals written as 0 0 0.
std::string to_stl_ascii(const geotex::PolygonSoup& s) {
    std::string out = "solid bench\n";
    for (int f = 0; f < s.num_polygons(); ++f) {
        out += "  facet normal 0 0 0\n    outer loop\n";
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            out += "      vertex";
            append_point(out, s.positions[s.face_indices[j]]);
            out += '\n';
        }
        out += "    endloop\n  endfacet\n";
    }
    out += "endsolid bench\n";
    return out;
}

void append_le(std::string& out, const void* p, std::size_t n) {
    out.append(static_cast<const char*>(p), n);  // the bench runs on little-endian hosts
}

std::string to_stl_binary(const geotex::PolygonSoup& s) {
    std::string out(80, ' ');
    const auto n = static_cast<std::uint32_t>(s.num_polygons());
    append_le(out, &n, 4);
    for (int f = 0; f < s.num_polygons(); ++f) {
        const float zero[3] = {0, 0, 0};
        append_le(out, zero, 12);
        for (int j = s.face_offsets[f]; j < s.face_offsets[f + 1]; ++j) {
            const Eigen::Vector3d& p = s.positions[s.face_indices[j]];
            const float c[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()),
                                static_cast<float>(p.z())};
            append_le(out, c, 12);
        }
        out += std::string(2, '\0');
    }
    return out;
}

// Corners that differ from the reference, compared as floats (the PLY holds floats, the text
// formats their shortest decimal text, read as double); STL renumbers the vertices, so the
// corners are compared by position, not by index.
long count_differences(const geotex::PolygonSoup& ref, const geotex::PolygonSoup& s) {
    if (ref.face_offsets != s.face_offsets) return -1;
    long diff = 0;
    for (std::size_t j = 0; j < ref.face_indices.size(); ++j) {
        const Eigen::Vector3d& a = ref.positions[ref.face_indices[j]];
        const Eigen::Vector3d& b = s.positions[s.face_indices[j]];
        for (int k = 0; k < 3; ++k) {
            if (static_cast<float>(a[k]) != static_cast<float>(b[k])) {
                ++diff;
                break;
            }
        }
    }
    return diff;
}

}  // namespace

const char* const kUsage =
    "usage: geotex_read_bench MESH.ply [--dir DIR] [--repeat N] [--reuse] [--only FORMAT]\n";

int main(int argc, char** argv) {
    std::string input;
    std::string dir = "read_bench";
    int repeat = 3;
    bool reuse = false;
    std::string only;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--dir" && i + 1 < argc) {
            dir = argv[++i];
        } else if (a == "--repeat" && i + 1 < argc) {
            repeat = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--reuse") {
            reuse = true;
        } else if (a == "--only" && i + 1 < argc) {
            only = argv[++i];
        } else if (input.empty() && a[0] != '-') {
            input = a;
        } else {
            std::fprintf(stderr, "%s", kUsage);
            return 1;
        }
    }
    if (input.empty()) {
        std::fprintf(stderr, "%s", kUsage);
        return 1;
    }
    try {
        const geotex::MeshFile ref = geotex::read_mesh_file(input);
        geotex::Mesh mesh;
        mesh.positions = ref.soup.positions;
        for (int f = 0; f < ref.soup.num_polygons(); ++f) {
            const int* c = &ref.soup.face_indices[ref.soup.face_offsets[f]];
            mesh.faces.push_back({c[0], c[1], c[2]});
        }
        std::filesystem::create_directories(dir);
        struct Entry {
            const char* label;
            std::string file;
        };
        const std::vector<Entry> entries = {{"PLY binary", dir + "/mesh.ply"},
                                            {"PLY ASCII", dir + "/mesh_ascii.ply"},
                                            {"OBJ", dir + "/mesh.obj"},
                                            {"OFF", dir + "/mesh.off"},
                                            {"STL ASCII", dir + "/mesh_ascii.stl"},
                                            {"STL binary", dir + "/mesh_binary.stl"}};
        for (const Entry& e : entries) {
            if (reuse && std::filesystem::exists(e.file)) continue;
            std::ofstream out(e.file, std::ios::binary);
            const std::string label = e.label;
            if (label == "PLY binary" || label == "PLY ASCII") {
                geotex::PlyWriteOptions options;
                options.binary = label == "PLY binary";
                geotex::write_ply(out, mesh, {}, options);
                continue;
            }
            const std::string text = label == "OBJ"         ? to_obj(ref.soup)
                                     : label == "OFF"       ? to_off(ref.soup)
                                     : label == "STL ASCII" ? to_stl_ascii(ref.soup)
                                                            : to_stl_binary(ref.soup);
            out.write(text.data(), static_cast<std::streamsize>(text.size()));
        }
        std::printf("| format | file | MB | read (s, best of %d) | MB/s | corners differing |\n",
                    repeat);
        std::printf("|---|---|---|---|---|---|\n");
        for (const Entry& e : entries) {
            if (!only.empty() && only != e.label) continue;
            const double mb = static_cast<double>(std::filesystem::file_size(e.file)) / 1e6;
            double best = 1e30;
            long diff = 0;
            for (int r = 0; r < repeat; ++r) {
                const auto t0 = Clock::now();
                const geotex::MeshFile m = geotex::read_mesh_file(e.file);
                best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
                diff = count_differences(ref.soup, m.soup);
            }
            std::printf("| %s | %s | %.1f | %.3f | %.0f | %ld |\n", e.label,
                        std::filesystem::path(e.file).filename().c_str(), mb, best, mb / best,
                        diff);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geotex_read_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
