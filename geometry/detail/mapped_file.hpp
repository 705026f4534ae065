#pragma once
// A mesh file mapped into memory for its reader (read_mesh_file). Its pages come from the file
// as the reader reaches them and leave again behind it (release_read), so that reading a scan
// holds its positions and a window of the file rather than a copy of the whole file (sphere-1
// level 11: a 2.0 GB PLY), and a file larger than memory can be read at all.
//
// A mapped file that another program cuts short while it is read would kill the process
// (SIGBUS) at the first page past its new end, where read() gives an error; so would a page the
// disk fails to give. Here that page and the rest of the mapping read as zeros instead; the
// reader goes on to its end or to an error, and read_mesh_file replaces either with an IoError
// saying where the file could not be read (unreadable_from()).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace geotex::detail {

/// The first `size` bytes (more than 0) of the file open as `fd`, mapped read-only: null, with
/// errno set, when they cannot be. No room in the address space (`ulimit -v`) throws
/// std::bad_alloc instead, so that the commands report it as running out of memory (exit 3).
/// For the mesh files here and the scratch files of the repair on disk.
const char* map_read_only(int fd, std::size_t size);

class MappedFile {
  public:
    /// `path` mapped read-only for the reader on this thread, which must not map another file
    /// while this one lives. Throws IoError naming `path` when it cannot be opened, measured
    /// or mapped, and std::bad_alloc when the address space has no room for it.
    explicit MappedFile(const std::string& path);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    /// The file's bytes as they were when it was mapped (empty for an empty file).
    std::string_view bytes() const { return {data_, size_}; }

    /// Where the reader touched a page that could not be read (past the end of a file cut
    /// short since it was mapped, or one the disk failed to give), or where the file now ends
    /// when it was cut short within a page: the bytes from there on were read as zeros, and what
    /// was read is not the file. Empty when every page was read and the file is as long as it
    /// was.
    std::optional<std::size_t> unreadable_from() const;

  private:
    char* data_ = nullptr;
    std::size_t size_ = 0;
    int fd_ = -1;  // open while mapped
};

}  // namespace geotex::detail
