#include "cli/view_objects.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include "common/errors.hpp"
#include "view/api_json.hpp"
#include "view/mesh_payload.hpp"
#include "view/thumbnail.hpp"

namespace geotex::cli {

std::shared_ptr<const std::string> ViewObjects::held(Product what, const std::string& id) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (what == Product::Thumbnail) {
        const auto it = thumbnails_.find(id);
        return it == thumbnails_.end() ? nullptr : it->second;
    }
    for (auto it = meshes_.begin(); it != meshes_.end(); ++it)
        if (it->first == id) {
            meshes_.splice(meshes_.begin(), meshes_, it);
            return it->second;
        }
    return nullptr;
}

void ViewObjects::keep(Product what, const std::string& id,
                       std::shared_ptr<const std::string> bytes) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (what == Product::Thumbnail) {
        thumbnails_[id] = std::move(bytes);
        return;
    }
    meshes_.remove_if([&](const auto& entry) { return entry.first == id; });
    meshes_.emplace_front(id, std::move(bytes));
    std::size_t total = 0;
    for (auto it = meshes_.begin(); it != meshes_.end(); ++it) {
        total += it->second->size();
        if (total > kMeshBudget && it != meshes_.begin()) {
            meshes_.erase(it, meshes_.end());
            break;
        }
    }
}

std::shared_ptr<std::mutex> ViewObjects::reader_of(const std::string& id) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto& reader = readers_[id];
    if (!reader) reader = std::make_shared<std::mutex>();
    return reader;
}

std::string ViewObjects::segmentation_path(const LoadedObject& o) const {
    return collection_.batch ? "objects/" + o.id + "/segmentation.ply"
                             : std::string("segmentation.ply");
}

std::unique_ptr<MeshFile> ViewObjects::read_segmentation(const LoadedObject& o) const {
    const std::string bytes = read_object_file(collection_.objects_root, o.id, "segmentation.ply");
    return std::make_unique<MeshFile>(read_mesh_memory(bytes, segmentation_path(o)));
}

std::shared_ptr<const std::string> ViewObjects::make(Product what, const MeshFile& segmentation,
                                                     const LoadedObject& o) const {
    const std::string where = o.id + "/segmentation.ply";
    return std::make_shared<const std::string>(
        what == Product::Mesh
            ? view::make_mesh_payload(segmentation, view::texel_depths(o.report), where)
            : view::make_thumbnail(segmentation, where));
}

std::vector<std::string> ViewObjects::held_meshes() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> ids;
    for (const auto& entry : meshes_) ids.push_back(entry.first);
    return ids;
}

void ViewObjects::prepare_first_objects(const std::atomic<bool>& stop) {
    struct Done {
        std::atomic<bool>& preparing;
        ~Done() { preparing = false; }
    } done{preparing_};
    // Linux gives each thread its own nice value.
    ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
    std::size_t bytes = 0;
    for (const LoadedObject& o : collection_.objects) {
        if (stop || bytes >= kMeshBudget) return;
        if (!o.error.empty()) continue;
        const std::lock_guard<std::mutex> reading(*reader_of(o.id));
        std::shared_ptr<const std::string> mesh = held(Product::Mesh, o.id);
        const bool has_png = held(Product::Thumbnail, o.id) != nullptr;
        try {
            if (mesh == nullptr || !has_png) {
                const std::unique_ptr<MeshFile> file = read_segmentation(o);
                if (mesh == nullptr) {
                    mesh = make(Product::Mesh, *file, o);
                    // Kept only while it fits beside those made before, which it must not evict.
                    if (bytes + mesh->size() <= kMeshBudget) keep(Product::Mesh, o.id, mesh);
                }
                if (!has_png) keep(Product::Thumbnail, o.id, make(Product::Thumbnail, *file, o));
            }
        } catch (const Error&) {
            continue;
        }
        bytes += mesh->size();
    }
}

}  // namespace geotex::cli
