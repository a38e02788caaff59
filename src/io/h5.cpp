#include "src/io/h5.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "src/core/error.hpp"

namespace panoptic::h5 {
namespace {

// zlib's level 4 (h5py's default for gzip): level 9 shrinks the DustPy disk's
// sigma(r, m) by under 1 % more
constexpr unsigned kDeflateLevel = 4;

hid_t ok(hid_t id, const std::string& what) {
  if (id < 0) throw IoError("HDF5: " + what + " failed");
  return id;
}
void ok(herr_t status, const char* what, const std::string& name) {
  if (status < 0) throw IoError(std::string("HDF5: ") + what + " '" + name + "' failed");
}

void describe(hid_t ds, const std::string& units, const std::string& description) {
  set_attr(ds, "units", units);
  set_attr(ds, "description", description);
}

//! An open stack (a dataset of rows): its handle, dataspace, row count and row width.
struct Stack {
  Handle ds, space;
  hsize_t rows = 0, width = 1;
};

Stack open_stack(hid_t parent, const std::string& name) {
  Stack st;
  st.ds =
      Handle(ok(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name),
             H5Dclose);
  st.space = Handle(ok(H5Dget_space(st.ds.get()), "dataspace of " + name), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(st.space.get());
  std::array<hsize_t, 2> dims{0, 0};
  H5Sget_simple_extent_dims(st.space.get(), dims.data(), nullptr);
  st.rows = dims[0];
  st.width = rank == 2 ? dims[1] : 1;
  return st;
}

//! Names of the links (objects) directly under a group or file, in name order.
std::vector<std::string> link_names(hid_t group) {
  H5G_info_t info;
  ok(H5Gget_info(group, &info), "listing", "group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                           nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw IoError("HDF5: listing a group failed");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                       name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(std::move(name));
  }
  return names;
}

//! A whole 1-D dataset `name` of `n` values of `mem_type` at `data`, stored as
//! `file_type` (write_vector, write_u64s).
Handle write_array(hid_t parent, const std::string& name, hid_t file_type, hid_t mem_type,
                   const void* data, hsize_t n) {
  const hsize_t dims[1] = {n};
  Handle space(ok(H5Screate_simple(1, dims, nullptr), "dataspace"), H5Sclose);
  Handle ds(ok(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                          H5P_DEFAULT, H5P_DEFAULT),
               "creating dataset " + name),
            H5Dclose);
  if (n > 0)
    ok(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "writing",
       name);
  return ds;
}

//! Every value of dataset `name` (any rank, flattened) as `mem_type` (read_doubles,
//! read_u64s).
template <class T>
std::vector<T> read_array(hid_t parent, const std::string& name, hid_t mem_type) {
  Handle ds(ok(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name),
            H5Dclose);
  Handle space(ok(H5Dget_space(ds.get()), "dataspace of " + name), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<T> out(static_cast<std::size_t>(n));
  if (n > 0)
    ok(H5Dread(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), "reading",
       name);
  return out;
}

//! Whether the chunk of dataset `ds` that holds row `row` is allocated (written), in
//! `allocated`; a negative status when HDF5 cannot read its index.
//! H5Dget_chunk_info_by_coord walks the whole index in HDF5 1.10 (0.16 ms a call for a
//! dataset of 3 000 chunks: 43 s to copy such an output at a restart), so the chunk is
//! first looked up directly (H5Dget_chunk_storage_size, 0.2 us); that fails for a chunk
//! that is not allocated and for an unreadable index alike, and only then is the index
//! walked to tell the two apart.
herr_t chunk_allocated(hid_t ds, hsize_t row, bool* allocated) {
  std::array<hsize_t, 2> offset{row, 0};
  hsize_t size = 0;
  *allocated = H5Dget_chunk_storage_size(ds, offset.data(), &size) >= 0 && size > 0;
  if (*allocated) return 0;
  unsigned filter_mask = 0;
  haddr_t addr = HADDR_UNDEF;
  const herr_t status =
      H5Dget_chunk_info_by_coord(ds, offset.data(), &filter_mask, &addr, &size);
  *allocated = status >= 0 && addr != HADDR_UNDEF;
  return status;
}

}  // namespace

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    closer_ = o.closer_;
    o.id_ = -1;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

void quiet_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {
// The HDF5 1.10 format as the lowest, for what a file gets: checksummed metadata, SWMR.
Handle latest_format_access(const std::string& path) {
  Handle fapl(ok(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
  ok(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST),
     "setting the format of", path);
  return fapl;
}

Handle create(const std::string& path, bool in_memory) {
  Handle fapl = latest_format_access(path);
  if (in_memory)
    ok(H5Pset_fapl_core(fapl.get(), 64 << 10, true), "setting the core driver of", path);
  // Root attributes in dense storage (the 1.8 format at least): compact storage caps an
  // attribute at 64 KiB, and config_toml (the resolved scene) or a scan's manifest can
  // be longer (an output_times list of 6 000 times: "creating attribute config_toml
  // failed", a stub file left behind).
  Handle fcpl(ok(H5Pcreate(H5P_FILE_CREATE), "property list"), H5Pclose);
  ok(H5Pset_attr_phase_change(fcpl.get(), 0, 0), "setting the attribute storage of",
     path);
  return {ok(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()),
             "creating file " + path),
          H5Fclose};
}
}  // namespace

Handle create_file(const std::string& path) { return create(path, false); }

Handle create_file_in_memory(const std::string& path) { return create(path, true); }

void close_file(Handle& f, const std::string& path) {
  if (!f.valid()) return;
  if (H5Fclose(f.release()) < 0)
    throw IoError("HDF5: closing file " + path + " failed (its data may be incomplete)");
}

Handle open_file(const std::string& path, bool writable) {
  if (writable)
    return {ok(H5Fopen(path.c_str(), H5F_ACC_RDWR, latest_format_access(path).get()),
               "opening file " + path),
            H5Fclose};
  hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  // HDF5 refuses a plain open of a file whose SWMR writer runs or was killed
  if (id < 0) {
    Handle fapl(ok(H5Pcreate(H5P_FILE_ACCESS), "property list"), H5Pclose);
    ok(H5Pset_metadata_read_attempts(fapl.get(), kSwmrReadAttempts),
       "setting the read attempts of", path);
    id = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl.get());
  }
  return {ok(id, "opening file " + path), H5Fclose};
}

bool start_swmr_write(hid_t f) { return H5Fstart_swmr_write(f) >= 0; }

Handle create_group(hid_t parent, const std::string& name) {
  return {ok(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             "creating group " + name),
          H5Gclose};
}

Handle open_group(hid_t parent, const std::string& name) {
  return {ok(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "opening group " + name),
          H5Gclose};
}

bool exists(hid_t parent, const std::string& path) {
  return H5Lexists(parent, path.c_str(), H5P_DEFAULT) > 0;
}

void write_vector(hid_t parent, const std::string& name, std::span<const double> data,
                  const std::string& units, const std::string& description) {
  const Handle ds = write_array(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                                data.data(), data.size());
  describe(ds.get(), units, description);
}

void create_stack(hid_t parent, const std::string& name, hsize_t width,
                  const std::string& units, const std::string& description,
                  bool compressed) {
  const int rank = width > 0 ? 2 : 1;
  const hsize_t dims[2] = {0, width}, maxdims[2] = {H5S_UNLIMITED, width};
  const hsize_t chunk[2] = {1, width > 0 ? width : 1};
  const hsize_t chunk1[1] = {64};
  Handle space(ok(H5Screate_simple(rank, dims, maxdims), "dataspace"), H5Sclose);
  Handle dcpl(ok(H5Pcreate(H5P_DATASET_CREATE), "property list"), H5Pclose);
  ok(H5Pset_chunk(dcpl.get(), rank, rank == 2 ? chunk : chunk1), "chunking", name);
  if (compressed) {
    // the byte shuffle groups the exponent bytes of neighbouring doubles, which deflate
    // then packs (HDF5 User's Guide, "Data Filters")
    ok(H5Pset_shuffle(dcpl.get()), "shuffle filter of", name);
    ok(H5Pset_deflate(dcpl.get(), kDeflateLevel), "deflate filter of", name);
  }
  Handle ds(ok(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                          dcpl.get(), H5P_DEFAULT),
               "creating dataset " + name),
            H5Dclose);
  describe(ds.get(), units, description);
}

void append_row(hid_t parent, const std::string& name, std::span<const double> row) {
  const Stack st = open_stack(parent, name);
  if (row.size() != st.width) throw IoError("HDF5: row of wrong length for " + name);
  const std::array<hsize_t, 2> new_dims{st.rows + 1, st.width};
  ok(H5Dset_extent(st.ds.get(), new_dims.data()), "extending", name);
  Handle fspace(ok(H5Dget_space(st.ds.get()), "dataspace of " + name), H5Sclose);
  const std::array<hsize_t, 2> start{st.rows, 0}, count{1, st.width};
  ok(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr,
                         count.data(), nullptr),
     "selecting", name);
  const hsize_t mdims[1] = {st.width};
  Handle mspace(ok(H5Screate_simple(1, mdims, nullptr), "dataspace"), H5Sclose);
  ok(H5Dwrite(st.ds.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT,
              row.data()),
     "writing", name);
}

hsize_t stack_rows(hid_t parent, const std::string& name) {
  return open_stack(parent, name).rows;
}

void truncate_stack(hid_t parent, const std::string& name, hsize_t rows) {
  const Stack st = open_stack(parent, name);
  if (st.rows == rows) return;
  const std::array<hsize_t, 2> dims{rows, st.width};
  ok(H5Dset_extent(st.ds.get(), dims.data()), "truncating", name);
}

std::vector<std::pair<hsize_t, hsize_t>> unallocated_rows(hid_t parent,
                                                          const std::string& name,
                                                          hsize_t rows) {
  Handle ds(ok(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "opening dataset " + name),
            H5Dclose);
  Handle dcpl(ok(H5Dget_create_plist(ds.get()), "creation properties of " + name),
              H5Pclose);
  std::vector<std::pair<hsize_t, hsize_t>> lost;
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return lost;
  std::array<hsize_t, 2> chunk{1, 1};
  const int rank = H5Pget_chunk(dcpl.get(), 2, chunk.data());
  if (rank < 1 || chunk[0] == 0) return lost;
  for (hsize_t first = 0; first < rows; first += chunk[0]) {
    bool allocated = false;
    ok(chunk_allocated(ds.get(), first, &allocated), "chunk index of", name);
    if (allocated) continue;
    const hsize_t last = std::min(first + chunk[0], rows);
    if (!lost.empty() && lost.back().second == first)
      lost.back().second = last;
    else
      lost.emplace_back(first, last);
  }
  return lost;
}

void fill_rows_nan(hid_t parent, const std::string& name, hsize_t first, hsize_t last) {
  const Stack st = open_stack(parent, name);
  const std::array<hsize_t, 2> start{first, 0}, count{last - first, st.width};
  ok(H5Sselect_hyperslab(st.space.get(), H5S_SELECT_SET, start.data(), nullptr,
                         count.data(), nullptr),
     "selecting", name);
  const std::vector<double> nan((last - first) * st.width,
                                std::numeric_limits<double>::quiet_NaN());
  const hsize_t n[1] = {nan.size()};
  Handle mspace(ok(H5Screate_simple(1, n, nullptr), "dataspace"), H5Sclose);
  ok(H5Dwrite(st.ds.get(), H5T_NATIVE_DOUBLE, mspace.get(), st.space.get(), H5P_DEFAULT,
              nan.data()),
     "writing", name);
}

std::vector<std::string> dataset_names(hid_t group) {
  std::vector<std::string> names;
  for (std::string& name : link_names(group)) {
    // H5Oopen + H5Iget_type: the same call in every HDF5 API version.
    const hid_t obj = H5Oopen(group, name.c_str(), H5P_DEFAULT);
    if (obj < 0) continue;
    if (H5Iget_type(obj) == H5I_DATASET) names.push_back(std::move(name));
    H5Oclose(obj);
  }
  return names;
}

std::vector<double> read_doubles(hid_t parent, const std::string& name) {
  return read_array<double>(parent, name, H5T_NATIVE_DOUBLE);
}

std::vector<double> read_rows(hid_t parent, const std::string& name, hsize_t first,
                              hsize_t last) {
  const Stack st = open_stack(parent, name);
  if (last > st.rows || first > last)
    throw IoError("HDF5: rows " + std::to_string(first) + ".." + std::to_string(last) +
                  " of " + name + " out of range (" + std::to_string(st.rows) + " rows)");
  std::vector<double> out((last - first) * st.width);
  if (out.empty()) return out;
  // (a 1-D stack's selection reads only the first entry of start and count)
  const std::array<hsize_t, 2> start{first, 0}, count{last - first, st.width};
  ok(H5Sselect_hyperslab(st.space.get(), H5S_SELECT_SET, start.data(), nullptr,
                         count.data(), nullptr),
     "selecting", name);
  const hsize_t n[1] = {out.size()};
  Handle mspace(ok(H5Screate_simple(1, n, nullptr), "dataspace"), H5Sclose);
  ok(H5Dread(st.ds.get(), H5T_NATIVE_DOUBLE, mspace.get(), st.space.get(), H5P_DEFAULT,
             out.data()),
     "reading", name);
  return out;
}

hsize_t stack_width(hid_t parent, const std::string& name) {
  return open_stack(parent, name).width;
}

void write_u64s(hid_t parent, const std::string& name,
                std::span<const std::uint64_t> data) {
  write_array(parent, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, data.data(), data.size());
}

std::vector<std::uint64_t> read_u64s(hid_t parent, const std::string& name) {
  return read_array<std::uint64_t>(parent, name, H5T_NATIVE_UINT64);
}

namespace {

//! Every attribute of `src` onto `dst`: raw bytes with their own type and dataspace
//! (panoptic writes fixed-length strings and numbers).
void copy_attributes(hid_t src, hid_t dst) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*,
                          void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  ok(H5Aiterate2(src, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names),
     "listing the attributes of", "an object");
  for (const std::string& name : names) {
    Handle a(ok(H5Aopen(src, name.c_str(), H5P_DEFAULT), "opening attribute " + name),
             H5Aclose);
    Handle type(ok(H5Aget_type(a.get()), "type of attribute " + name), H5Tclose);
    Handle space(ok(H5Aget_space(a.get()), "dataspace of attribute " + name), H5Sclose);
    if (H5Tis_variable_str(type.get()) > 0)
      throw IoError("HDF5: attribute " + name +
                    " is a variable-length string, which panoptic does not write");
    const hssize_t n = H5Sget_simple_extent_npoints(space.get());
    std::vector<char> bytes(static_cast<std::size_t>(n) * H5Tget_size(type.get()) + 1);
    ok(H5Aread(a.get(), type.get(), bytes.data()), "reading attribute", name);
    Handle b(ok(H5Acreate2(dst, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                           H5P_DEFAULT),
                "creating attribute " + name),
             H5Aclose);
    ok(H5Awrite(b.get(), type.get(), bytes.data()), "writing attribute", name);
  }
}

//! Dataset `name` of group `src` into group `dst`: same type, shape, maximum shape and
//! creation properties (chunking), a new chunk index. A chunked dataset is copied one
//! chunk row at a time; a chunk the source has lost, or that HDF5 cannot read back, is
//! left unallocated in the copy (it reads as the fill value there, where the restart
//! finds it: mark_lost_rows).
void copy_dataset(hid_t src, hid_t dst, const std::string& name) {
  Handle ds(ok(H5Dopen2(src, name.c_str(), H5P_DEFAULT), "opening dataset " + name),
            H5Dclose);
  Handle type(ok(H5Dget_type(ds.get()), "type of " + name), H5Tclose);
  Handle space(ok(H5Dget_space(ds.get()), "dataspace of " + name), H5Sclose);
  Handle dcpl(ok(H5Dget_create_plist(ds.get()), "creation properties of " + name),
              H5Pclose);
  Handle out(ok(H5Dcreate2(dst, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                           dcpl.get(), H5P_DEFAULT),
                "creating dataset " + name),
             H5Dclose);
  copy_attributes(ds.get(), out.get());
  const std::size_t tsize = H5Tget_size(type.get());
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED || rank < 1 || rank > 2) {
    const hssize_t n = H5Sget_simple_extent_npoints(space.get());
    std::vector<char> bytes(static_cast<std::size_t>(n) * tsize + 1);
    if (n > 0) {
      ok(H5Dread(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()),
         "reading", name);
      ok(H5Dwrite(out.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()),
         "writing", name);
    }
    return;
  }
  std::array<hsize_t, 2> dims{0, 1}, chunk{1, 1};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  H5Pget_chunk(dcpl.get(), 2, chunk.data());
  const hsize_t width = rank == 2 ? dims[1] : 1, step = chunk[0] > 0 ? chunk[0] : 1;
  Handle fspace(ok(H5Dget_space(out.get()), "dataspace of " + name), H5Sclose);
  for (hsize_t first = 0; first < dims[0]; first += step) {
    const hsize_t last = std::min(first + step, dims[0]);
    bool allocated = false;
    if (chunk_allocated(ds.get(), first, &allocated) < 0 || !allocated) continue;
    const std::array<hsize_t, 2> start{first, 0}, count{last - first, width};
    ok(H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr,
                           count.data(), nullptr),
       "selecting", name);
    ok(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr,
                           count.data(), nullptr),
       "selecting", name);
    const hsize_t n[1] = {(last - first) * width};
    Handle mspace(ok(H5Screate_simple(1, n, nullptr), "dataspace"), H5Sclose);
    std::vector<char> bytes(n[0] * tsize);
    if (H5Dread(ds.get(), type.get(), mspace.get(), space.get(), H5P_DEFAULT,
                bytes.data()) < 0)
      continue;  // unreadable: left unallocated in the copy
    ok(H5Dwrite(out.get(), type.get(), mspace.get(), fspace.get(), H5P_DEFAULT,
                bytes.data()),
       "writing", name);
  }
}

//! Every group and dataset under `src` into `dst`, with their attributes. An object
//! HDF5 cannot open (its header torn by a SIGKILL in the middle of its write: the
//! kernel can stop a write at a page boundary) is left out: the restart that copies
//! the file recreates a snapshot field it lost, its rows NaN (RunOutput::add_field).
void copy_group(hid_t src, hid_t dst) {
  copy_attributes(src, dst);
  for (const std::string& name : link_names(src)) {
    const hid_t id = H5Oopen(src, name.c_str(), H5P_DEFAULT);
    if (id < 0) continue;
    Handle obj(id, H5Oclose);
    const H5I_type_t kind = H5Iget_type(obj.get());
    if (kind == H5I_GROUP) {
      Handle g = create_group(dst, name);
      copy_group(obj.get(), g.get());
    } else if (kind == H5I_DATASET) {
      copy_dataset(src, dst, name);
    }
  }
}

}  // namespace

void copy_file(const std::string& from, const std::string& to) {
  Handle src = open_file(from, false);
  Handle dst = create_file(to);
  copy_group(src.get(), dst.get());
  ok(H5Fflush(dst.get(), H5F_SCOPE_GLOBAL), "flushing", to);
}

void set_attr(hid_t obj, const std::string& name, const std::string& value) {
  // An existing attribute is replaced only once the new one is written (under a
  // temporary name, then renamed): a failure leaves the old value, not none (a restart
  // whose longer config_toml could not be written lost the file's config_toml).
  const bool replace = H5Aexists(obj, name.c_str()) > 0;
  const std::string target = replace ? name + ".__new" : name;
  if (replace && H5Aexists(obj, target.c_str()) > 0) H5Adelete(obj, target.c_str());
  {
    Handle type(ok(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
    H5Tset_size(type.get(), value.empty() ? 1 : value.size());
    H5Tset_cset(type.get(), H5T_CSET_UTF8);
    Handle space(ok(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
    Handle attr(ok(H5Acreate2(obj, target.c_str(), type.get(), space.get(), H5P_DEFAULT,
                              H5P_DEFAULT),
                   "creating attribute " + name),
                H5Aclose);
    const std::string v = value.empty() ? std::string(1, '\0') : value;
    ok(H5Awrite(attr.get(), type.get(), v.data()), "writing attribute", name);
  }
  if (replace) {
    ok(H5Adelete(obj, name.c_str()), "replacing attribute", name);
    ok(H5Arename(obj, target.c_str(), name.c_str()), "replacing attribute", name);
  }
}

namespace {

// A scalar attribute of file type `file_type`, written from `value` in `memory_type`
// (replacing one of that name).
void set_scalar_attr(hid_t obj, const std::string& name, hid_t file_type,
                     hid_t memory_type, const void* value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle space(ok(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  Handle attr(
      ok(H5Acreate2(obj, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
         "creating attribute " + name),
      H5Aclose);
  ok(H5Awrite(attr.get(), memory_type, value), "writing attribute", name);
}

// A scalar attribute read into `value` as `memory_type`.
void get_scalar_attr(hid_t obj, const std::string& name, hid_t memory_type, void* value) {
  Handle attr(ok(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "opening attribute " + name),
              H5Aclose);
  ok(H5Aread(attr.get(), memory_type, value), "reading attribute", name);
}

}  // namespace

void set_attr(hid_t obj, const std::string& name, double value) {
  set_scalar_attr(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void set_attr(hid_t obj, const std::string& name, long value) {
  set_scalar_attr(obj, name, H5T_STD_I64LE, H5T_NATIVE_LONG, &value);
}

std::string get_attr_string(hid_t obj, const std::string& name) {
  Handle attr(ok(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "opening attribute " + name),
              H5Aclose);
  Handle type(ok(H5Aget_type(attr.get()), "attribute type"), H5Tclose);
  const std::size_t size = H5Tget_size(type.get());
  std::string s(size, '\0');
  ok(H5Aread(attr.get(), type.get(), s.data()), "reading attribute", name);
  if (const auto nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
  return s;
}

double get_attr_double(hid_t obj, const std::string& name) {
  double v = 0.0;
  get_scalar_attr(obj, name, H5T_NATIVE_DOUBLE, &v);
  return v;
}

long get_attr_long(hid_t obj, const std::string& name) {
  long v = 0;
  get_scalar_attr(obj, name, H5T_NATIVE_LONG, &v);
  return v;
}

bool has_attr(hid_t obj, const std::string& name) {
  return H5Aexists(obj, name.c_str()) > 0;
}

}  // namespace panoptic::h5
