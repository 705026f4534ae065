#pragma once
// Small meshes built in code for the tests: analytic shapes with known answers.

#include <filesystem>
#include <functional>
#include <string>

#include "geometry/mesh.hpp"

namespace geotex::test {

/// Square grid in the xy plane, [-size/2, size/2]^2, n x n cells of two triangles each,
/// faces counter-clockwise seen from +z; z = height(x, y) when given.
Mesh make_grid(int n, double size, const std::function<double(double, double)>& height = {});

/// Open cylinder of the z axis, `around` vertices per ring, `rings` rings over `length`,
/// faces outward.
Mesh make_cylinder(double radius, double length, int around, int rings);

/// Icosphere of the given radius and level, centred at `center`.
Mesh make_sphere(double radius, int level, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Triangulated flat disc of radius 1 in the xy plane (rings of vertices), faces up.
Mesh make_disc(int rings);

/// The mesh with every coordinate multiplied by k.
Mesh scaled(Mesh mesh, double k);

/// Two meshes as one (the second's indices shifted).
Mesh combined(const Mesh& a, const Mesh& b);

/// The squared distance from q to the proper triangle abc by the textbook rule: to its plane
/// where the foot falls inside, else to the nearest of its edges. A reference for the
/// distance searches, independent of CGAL's projection.
double triangle_squared_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Signed volume enclosed (positive when faces point outward).
double signed_volume(const Mesh& mesh);

/// All face indices [0, #F).
std::vector<int> all_faces(const Mesh& mesh);

/// Sphere-1 (geotex synth) at icosphere `level` with half of its shapes engraved, so that both
/// orientations and the rim removal have work to do.
Mesh half_engraved_sphere(int level);

/// a and b have the same bits: 0.0 and -0.0 differ, a NaN equals a NaN of the same bits.
bool same_bits(double a, double b);

/// Writes `bytes` to `path`, creating its directory first.
void write_file(const std::filesystem::path& path, const std::string& bytes);

/// A fresh, empty directory under the system's temporary directory, removed with the object.
/// `name` and the process id (ctest runs test processes in parallel) make its name, with a
/// count for the directories of one process.
class TempDir {
  public:
    explicit TempDir(const std::string& name);
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    bool empty() const { return std::filesystem::is_empty(path_); }

  private:
    std::filesystem::path path_;
};

/// Where the arrays of one of a tiled run's binary files (a prepared mesh, a tile's mesh) start:
/// after the magic line, the header's length (8 bytes, little-endian) and the header.
std::size_t binary_arrays_start(const std::string& bytes);

}  // namespace geotex::test
