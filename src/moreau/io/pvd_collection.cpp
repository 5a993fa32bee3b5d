#include "moreau/io/pvd_collection.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "moreau/errors.hpp"
#include "moreau/io/atomic_file.hpp"

namespace moreau {

namespace {

constexpr const char* kHeader =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n";
constexpr const char* kClosing = "</Collection>\n</VTKFile>\n";

// Writes `text` at byte `offset` of the existing file `path` in one write.
void write_at(const std::string& path, std::uint64_t offset, const std::string& text) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekp(static_cast<std::streamoff>(offset));
  file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.flush();
  if (!file) throw std::runtime_error(fmt::format("{}: cannot extend the collection (is the disk full?)", path));
}

}  // namespace

PvdCollection::PvdCollection(std::string path, const FrameSeries& resume) : path_(std::move(path)) {
  if (resume.frames == 0) {
    write_file_atomically(path_, std::string(kHeader) + kClosing);
    end_ = std::string(kHeader).size();
    return;
  }
  end_ = resume.pvd_bytes;
  std::error_code ec;
  if (std::filesystem::file_size(path_, ec) < end_ || ec)
    throw InputError(fmt::format("{}: shorter than when the checkpoint was written; restart into an empty directory with --out",
                                 path_));
  write_at(path_, end_, kClosing);
  std::filesystem::resize_file(path_, end_ + std::string(kClosing).size());
}

void PvdCollection::add_frame(const std::vector<PvdEntry>& entries) {
  std::string text;
  for (const PvdEntry& e : entries)
    text += fmt::format("<DataSet timestep=\"{:.9g}\" part=\"{}\" file=\"{}\"/>\n", e.time, e.part, e.file);
  write_at(path_, end_, text + kClosing);
  end_ += text.size();
}

}  // namespace moreau
