#pragma once
//! Files that survive a crash: fsync of a file or a directory, rename, and the one
//! atomic write of a whole file, each throwing IoError naming the path (checkpoints,
//! the output a restart rebuilds, scan records and summaries, observe outputs).
#include <filesystem>
#include <string>
#include <string_view>

namespace panoptic {

//! fsync of a file, or of a directory (so that a rename in it is on the disk); some file
//! systems cannot fsync a directory (EINVAL), which is accepted: the rename is still
//! atomic.
void fsync_path(const std::filesystem::path& path, bool directory);
//! rename(2): atomic replacement of `to` by `from` on the same file system.
void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to);
//! Writes `text` to `path` atomically: write_temporary, then commit_temporary. At every
//! moment of a crash `path` holds the old text or the new one; a failed write leaves the
//! old file and no temporary one. Throws IoError.
void write_atomically(const std::filesystem::path& path, std::string_view text);
//! The first half of write_atomically, for files that must change together (write each,
//! then commit each): writes `text` to a new temporary file beside `path` (a name no
//! other process holds, mode 0644), fsynced; on failure none is left. Returns its name.
std::filesystem::path write_temporary(const std::filesystem::path& path,
                                      std::string_view text);
//! Puts a finished temporary file in place of `path`: fsync of `tmp`, rename over
//! `path`, fsync of the directory. `tmp` must be in the directory of `path` and closed;
//! it may come from write_temporary or from a library that wrote it (an HDF5 file
//! written to `<path>.tmp` and closed). On failure `tmp` is removed. Throws IoError.
void commit_temporary(const std::filesystem::path& tmp,
                      const std::filesystem::path& path);
//! True when the file begins with the 8-byte HDF5 signature (a file panoptic wrote has
//! no user block, so the signature is at offset 0; a truncated file keeps it).
bool has_hdf5_signature(const std::filesystem::path& path);
//! Throws IoError, naming the fix, when a new output may not be written at `output`:
//! a directory; an existing file without `overwrite`; with it, anything but an earlier
//! output (not a regular file, e.g. a device or a FIFO, or a non-empty file that is not
//! HDF5: a scene, a note or a script given by mistake). Used by run and observe.
void refuse_to_replace(const std::filesystem::path& output, bool overwrite);
//! Throws ConfigError when `output` is the file `input` (by identity: links and other
//! spellings of the path too): --overwrite would replace what the command reads.
//! `what` names it ("the scene the run reads", "the run's checkpoint").
void refuse_output_is_input(const std::filesystem::path& output,
                            const std::filesystem::path& input, const std::string& what);
//! Why writing `path` may have failed, as " (reason); fix" or "": the directory or file
//! not writable (errno's text), `err` (the errno of the failed write) a full quota or
//! disk, or less than 1 MiB free on its file system. For the output and checkpoints.
std::string write_failure_hint(const std::filesystem::path& path, int err);

}  // namespace panoptic
