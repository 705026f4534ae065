#pragma once
// The meshes and thumbnails that `geotex view` serves (view/README.md): both made from one
// reading of an object's segmentation.ply, kept (the meshes most recent first up to a
// budget, the thumbnails all), and made ahead for the first objects of the list as the
// server starts. No HTTP here: cli/cmd_view.cpp answers the requests with it.

#include <atomic>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "geometry/mesh_io.hpp"
#include "pipeline/loaded_collection.hpp"

namespace geotex::cli {

class ViewObjects {
  public:
    /// The two things made from an object's segmentation: its GTXM mesh and its PNG thumbnail.
    enum class Product { Mesh, Thumbnail };

    /// Memory kept for the meshes sent last: about six objects of a million faces.
    static constexpr std::size_t kMeshBudget = std::size_t(256) << 20;

    /// `collection` must outlive this object.
    explicit ViewObjects(const LoadedCollection& collection) : collection_(collection) {}

    /// The product held for object `id`, or nullptr. A mesh asked for becomes the most recent.
    std::shared_ptr<const std::string> held(Product what, const std::string& id);
    /// Keeps a product; a mesh goes first, and the oldest meshes beyond the budget are
    /// dropped (never the one just kept).
    void keep(Product what, const std::string& id, std::shared_ptr<const std::string> bytes);
    /// The lock of an object's reading: one reading of a segmentation at a time, so that the
    /// thumbnail the list asks for and the mesh the 3D view asks for come from one parse.
    std::shared_ptr<std::mutex> reader_of(const std::string& id);

    /// "objects/ID/segmentation.ply" in a batch output, "segmentation.ply" for one object.
    std::string segmentation_path(const LoadedObject& o) const;
    /// The object's segmentation, read anew. Throws Error for a missing or corrupt file.
    std::unique_ptr<MeshFile> read_segmentation(const LoadedObject& o) const;
    /// Makes a product from the object's segmentation. Throws Error when it does not fit the
    /// object's report.
    std::shared_ptr<const std::string> make(Product what, const MeshFile& segmentation,
                                            const LoadedObject& o) const;

    /// The objects whose meshes are held, most recent first.
    std::vector<std::string> held_meshes() const;
    /// True until prepare_first_objects has ended.
    bool preparing() const { return preparing_; }

    /// Makes the meshes and thumbnails of the first objects of the list, in its order, for as
    /// many meshes as the budget keeps: a curator who opens the page and clicks, or follows a
    /// link, finds the object's mesh made instead of waiting for the reading of its PLY
    /// (0.9 s for 1.3 million faces). Meant for its own thread, which it puts at a lower
    /// priority than the requests; stops between two objects when `stop` is set, and leaves
    /// every failure to the request that will report it.
    void prepare_first_objects(const std::atomic<bool>& stop);

  private:
    const LoadedCollection& collection_;
    mutable std::mutex mutex_;
    std::list<std::pair<std::string, std::shared_ptr<const std::string>>> meshes_;
    // Thumbnails are small and slow to draw for a large object: each is drawn once.
    std::map<std::string, std::shared_ptr<const std::string>> thumbnails_;
    std::map<std::string, std::shared_ptr<std::mutex>> readers_;
    std::atomic<bool> preparing_{true};
};

}  // namespace geotex::cli
