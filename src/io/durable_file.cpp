#include "src/io/durable_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "src/core/error.hpp"

namespace panoptic {
namespace fs = std::filesystem;

void fsync_path(const std::filesystem::path& path, bool directory) {
  const int fd =
      ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (directory ? O_DIRECTORY : 0));
  if (fd < 0)
    throw IoError(path.string() + ": cannot open for fsync (" + std::strerror(errno) +
                  ")");
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0 && !(directory && err == EINVAL))
    throw IoError(path.string() + ": fsync failed (" + std::strerror(err) +
                  "); is the disk full?");
}

void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (::rename(from.c_str(), to.c_str()) != 0)
    throw IoError("cannot rename " + from.string() + " to " + to.string() + " (" +
                  std::strerror(errno) + ")");
}

void write_atomically(const fs::path& path, std::string_view text) {
  commit_temporary(write_temporary(path, text), path);
}

fs::path write_temporary(const fs::path& path, std::string_view text) {
  // A name no other process can hold: processes of one scan on different nodes of a
  // shared file system (MPI ranks, array tasks) may have the same PID, and ".tmpPID"
  // would then be one file written by both. mkstemp creates it exclusively (O_EXCL).
  std::string name = path.string() + ".tmpXXXXXX";
  const int fd = mkostemp(name.data(), O_CLOEXEC);
  const fs::path tmp = name;
  if (fd < 0)
    throw IoError(tmp.string() + ": cannot write (" + std::strerror(errno) + ")");
  fchmod(fd, 0644);  // mkstemp's 0600 would hide the records from the user's group
  // a failed write (disk full, quota: some file systems report it only at fsync or
  // close) leaves the old file and no temporary one, which would fill the disk further
  const auto fail = [&](const std::string& what, int e) {
    unlink(tmp.c_str());
    throw IoError(tmp.string() + ": " + what + " (" + std::strerror(e) + ")");
  };
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : EIO;
      close(fd);
      fail("write failed", e);
    }
    done += static_cast<std::size_t>(n);
  }
  if (fsync(fd) != 0) {
    const int e = errno;
    close(fd);
    fail("fsync failed", e);
  }
  if (close(fd) != 0) fail("close failed", errno);
  return tmp;
}

void commit_temporary(const fs::path& tmp, const fs::path& path) {
  try {
    fsync_path(tmp, false);
  } catch (const IoError&) {
    unlink(tmp.c_str());
    throw;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    unlink(tmp.c_str());
    throw IoError(path.string() + ": cannot rename " + tmp.string() + " (" +
                  std::strerror(e) + ")");
  }
  fsync_path(path.has_parent_path() ? path.parent_path() : fs::path("."), true);
}

bool has_hdf5_signature(const std::filesystem::path& path) {
  static constexpr char kSignature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  char head[8] = {};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  const std::size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  return n == sizeof head && std::memcmp(head, kSignature, sizeof head) == 0;
}

void refuse_to_replace(const std::filesystem::path& output, bool overwrite) {
  std::error_code ec;
  const auto st = std::filesystem::status(output, ec);
  if (!std::filesystem::exists(st)) return;
  if (std::filesystem::is_directory(st))
    throw IoError(output.string() +
                  ": is a directory; give the output file's name with -o");
  if (!overwrite)
    throw IoError(output.string() +
                  ": output file exists; pass --overwrite to replace it, or choose "
                  "another file with -o");
  if (!std::filesystem::is_regular_file(st))  // a device, a FIFO, a socket
    throw IoError(output.string() +
                  ": exists and is not a regular file; --overwrite replaces only an "
                  "earlier output: choose an output file with -o");
  if (std::filesystem::file_size(output, ec) == 0 || ec) return;
  if (!has_hdf5_signature(output))
    throw IoError(
        output.string() +
        ": exists and is not an HDF5 file; --overwrite replaces only an earlier "
        "output: move the file or choose another with -o");
}

void refuse_output_is_input(const std::filesystem::path& output,
                            const std::filesystem::path& input, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::equivalent(output, input, ec) && !ec)
    throw ConfigError("-o " + output.string() + ": this is " + what + " (" +
                      input.string() +
                      "); --overwrite would replace it: choose another output file with "
                      "-o");
}

std::string write_failure_hint(const std::filesystem::path& path, int err) {
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (::access(dir.c_str(), W_OK) != 0)
    return " (" + dir.string() + ": " + std::strerror(errno) +
           "); write the output elsewhere with -o";
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && ::access(path.c_str(), W_OK) != 0)
    return " (" + std::string(std::strerror(errno)) +
           "); write the output elsewhere with -o";
  if (err == EDQUOT)
    return " (" + std::string(std::strerror(err)) +
           ": the disk quota is full); make room or write elsewhere with -o";
  const auto space = std::filesystem::space(dir, ec);
  if (err == ENOSPC || (!ec && space.available < (std::uintmax_t{1} << 20)))
    return " (the file system of " + dir.string() + " has " +
           (ec ? std::string("no space") : std::to_string(space.available) + " bytes") +
           " free: the disk is full); make room or write elsewhere with -o";
  return "";
}

}  // namespace panoptic
