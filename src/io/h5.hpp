#pragma once
//! Thin RAII over the HDF5 C API (serial): handles close themselves, every failure throws
//! IoError naming the file and object. Only what panoptic writes: groups, fixed and
//! extendible (time-stacked) double datasets, string/number attributes.
#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace panoptic::h5 {

//! Owns one hid_t and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();
  //! Gives up ownership: the caller closes the id.
  hid_t release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

//! Creates (truncating) an HDF5 file in the HDF5 1.10 format: its metadata carries
//! checksums, so that a damaged file is reported as such instead of read as garbage
//! (checkpoints), and it can be written in SWMR mode (start_swmr_write; run outputs).
Handle create_file(const std::string& path);
//! The same, built in memory and written to `path` only when flushed and closed (the
//! core driver with a backing store): a write that fails there (disk full, quota) is an
//! error of the flush, and does not leave HDF5 with a half-written file that it fails
//! to close and crashes on at exit (seen with sec2 and HDF5 1.10.8). For files that
//! fit in memory (a scan's summary).
Handle create_file_in_memory(const std::string& path);
//! Opens an HDF5 file, read-write with the 1.10 format for what it adds (so that
//! start_swmr_write can follow). Read-only, a file that HDF5 marks as open by a SWMR
//! writer (a run's output while it runs, or after the run was killed) is opened for
//! SWMR reading: what the writer last flushed, consistent.
Handle open_file(const std::string& path, bool writable);
//! How often a SWMR reader reads a metadata entry whose checksum fails before it gives
//! up. HDF5 1.10's default, 100, with a back-off that doubles at each attempt, waits
//! for ever on an entry that a SIGKILL tore (the kernel can stop a write at a page
//! boundary: a restart's copy hung for 12 min on /snapshots/St of a killed output of
//! regression.test_restart_killed). 24 attempts give up after ~0.07 s, still long
//! enough for a live writer to finish an entry (a flush takes microseconds).
inline constexpr unsigned kSwmrReadAttempts = 24;
//! Switches file `f` (opened read-write or created by this process) to SWMR writing
//! (HDF5's single-writer/multiple-reader mode): from here on HDF5 writes its metadata in
//! an order that keeps the file on disk consistent at every write, so a process killed
//! at any moment, in the middle of a flush included, leaves a file that opens, holding
//! every row flushed before (regression.test_kill_during_flush). False when HDF5
//! refuses (a file in the 1.8 format, which HDF5 cannot write in that mode).
bool start_swmr_write(hid_t f);
//! Closes file `f` and throws IoError naming `path` when HDF5 fails to (its metadata,
//! cached until the close, could not be written: the file is incomplete). ~Handle
//! ignores that failure; a file that must be whole (a checkpoint) is closed with this.
void close_file(Handle& f, const std::string& path);
Handle create_group(hid_t parent, const std::string& name);
Handle open_group(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& path);

//! Fixed-size 1-D double dataset.
void write_vector(hid_t parent, const std::string& name, std::span<const double> data,
                  const std::string& units, const std::string& description);
//! Extendible dataset of shape (0, width) (width 0: shape (0,)), chunked along time.
//! `compressed`: each chunk (row) is shuffled and deflated (the HDF5 filters h5py
//! and every HDF5 reader decode), for rows of many values such as a distribution.
void create_stack(hid_t parent, const std::string& name, hsize_t width,
                  const std::string& units, const std::string& description,
                  bool compressed = false);
//! Appends one row to a stack created by create_stack.
void append_row(hid_t parent, const std::string& name, std::span<const double> row);
//! Number of rows of a stack.
hsize_t stack_rows(hid_t parent, const std::string& name);
//! Cuts a stack to its first `rows` rows (H5Dset_extent), e.g. to drop the snapshots a
//! restart will write again.
void truncate_stack(hid_t parent, const std::string& name, hsize_t rows);
//! The rows [first, last) among the first `rows` of the chunked stack `name` whose chunk
//! is not allocated (so they read back as the fill value), as ranges. A writer killed
//! while HDF5 flushed its (unjournaled) chunk index can lose the entries of rows it had
//! flushed before.
std::vector<std::pair<hsize_t, hsize_t>> unallocated_rows(hid_t parent,
                                                          const std::string& name,
                                                          hsize_t rows);
//! Writes NaN into rows [first, last) of the stack `name`.
void fill_rows_nan(hid_t parent, const std::string& name, hsize_t first, hsize_t last);
//! Names of the datasets directly in a group, in name order.
std::vector<std::string> dataset_names(hid_t group);
//! Reads a whole double dataset (any rank, flattened).
std::vector<double> read_doubles(hid_t parent, const std::string& name);
//! Rows [first, last) of a stack, flattened (width values per row; 1 for a 1-D stack).
std::vector<double> read_rows(hid_t parent, const std::string& name, hsize_t first,
                              hsize_t last);
//! Width of a stack's rows (1 for a 1-D stack).
hsize_t stack_width(hid_t parent, const std::string& name);
//! Fixed-size 1-D dataset of unsigned 64-bit integers (digests), and its reader.
void write_u64s(hid_t parent, const std::string& name,
                std::span<const std::uint64_t> data);
std::vector<std::uint64_t> read_u64s(hid_t parent, const std::string& name);

void set_attr(hid_t obj, const std::string& name, const std::string& value);
void set_attr(hid_t obj, const std::string& name, double value);
void set_attr(hid_t obj, const std::string& name, long value);
std::string get_attr_string(hid_t obj, const std::string& name);
double get_attr_double(hid_t obj, const std::string& name);
long get_attr_long(hid_t obj, const std::string& name);
bool has_attr(hid_t obj, const std::string& name);

//! Writes a new file `to` (replacing one there) with every group and dataset of `from`
//! and every attribute, each dataset with a new chunk index, copied chunk row by chunk
//! row from the chunks the old index reaches: a file whose index a killed writer left
//! inconsistent is copied into a consistent one. Rows the old index had lost, or that
//! HDF5 cannot read back, stay unallocated in the copy.
void copy_file(const std::string& from, const std::string& to);

//! Silences HDF5's own error stack printing (we throw IoError with our own message).
void quiet_errors();

}  // namespace panoptic::h5
