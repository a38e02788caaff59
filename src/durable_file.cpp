#include "src/durable_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "src/error.hpp"

namespace panoptic {

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

void refuse_output_is_input(const std::filesystem::path& output,
                            const std::filesystem::path& input, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::equivalent(output, input, ec) && !ec)
    throw ConfigError("-o " + output.string() + ": this is " + what + " (" +
                      input.string() +
                      "); --overwrite would replace it: choose another output file with "
                      "-o");
}

}  // namespace panoptic
