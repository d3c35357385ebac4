#include "raw_cdr_type.hpp"

#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>
#include <dds/ddsi/q_radmin.h>

#include <cstdlib>
#include <cstring>
#include <functional>
#include <new>
#include <string>

namespace mote::ros::detail {
namespace {

// The serdata: Cyclone's header first (the generic code reads and writes its fields), then the
// bytes. Allocated with new, freed by the ops' free.
struct RawSample : ddsi_serdata {
  std::string bytes;
};

struct RawType : ddsi_sertype {};

const RawSample& as_raw(const ddsi_serdata* d) { return *static_cast<const RawSample*>(d); }

RawSample* new_sample(const ddsi_sertype* type, ddsi_serdata_kind kind, std::size_t size) {
  auto* d = new (std::nothrow) RawSample();
  if (d == nullptr) return nullptr;
  ddsi_serdata_init(d, type, kind);
  // Keyless: every sample is the one instance, so all hash alike (rmw_cyclonedds does the same).
  d->hash = type->serdata_basehash;
  if (kind == SDK_DATA) d->bytes.resize(size);
  return d;
}

uint32_t sample_size(const ddsi_serdata* d) {
  return static_cast<uint32_t>(as_raw(d).bytes.size());
}

void sample_free(ddsi_serdata* d) { delete static_cast<RawSample*>(d); }

// A received sample arrives as a chain of fragments, each holding bytes [min, maxp1) of the
// sample; later fragments may overlap earlier ones, so each copies only what it adds.
ddsi_serdata* sample_from_ser(const ddsi_sertype* type, ddsi_serdata_kind kind,
                              const nn_rdata* fragment, std::size_t size) {
  RawSample* d = new_sample(type, kind, size);
  if (d == nullptr || kind != SDK_DATA) return d;
  std::size_t off = 0;
  for (; fragment != nullptr; fragment = fragment->nextfrag) {
    if (fragment->maxp1 <= off || fragment->min > off) continue;
    const unsigned char* payload =
        NN_RMSG_PAYLOADOFF(fragment->rmsg, NN_RDATA_PAYLOAD_OFF(fragment));
    const std::size_t end = std::min<std::size_t>(fragment->maxp1, size);
    std::memcpy(d->bytes.data() + off, payload + (off - fragment->min), end - off);
    off = end;
  }
  return d;
}

ddsi_serdata* sample_from_ser_iov(const ddsi_sertype* type, ddsi_serdata_kind kind,
                                  ddsrt_msg_iovlen_t niov, const ddsrt_iovec_t* iov,
                                  std::size_t size) {
  RawSample* d = new_sample(type, kind, size);
  if (d == nullptr || kind != SDK_DATA) return d;
  std::size_t off = 0;
  for (ddsrt_msg_iovlen_t k = 0; k < niov && off < size; ++k) {
    const std::size_t n = std::min<std::size_t>(iov[k].iov_len, size - off);
    std::memcpy(d->bytes.data() + off, iov[k].iov_base, n);
    off += n;
  }
  return d;
}

ddsi_serdata* sample_from_keyhash(const ddsi_sertype* type, const ddsi_keyhash*) {
  return new_sample(type, SDK_KEY, 0);
}

// Samples of this type are the bytes: from_sample takes a std::string_view.
ddsi_serdata* sample_from_sample(const ddsi_sertype* type, ddsi_serdata_kind kind,
                                 const void* sample) {
  const auto& view = *static_cast<const std::string_view*>(sample);
  RawSample* d = new_sample(type, kind, view.size());
  if (d != nullptr && kind == SDK_DATA) std::memcpy(d->bytes.data(), view.data(), view.size());
  return d;
}

void sample_to_ser(const ddsi_serdata* d, std::size_t off, std::size_t size, void* buf) {
  std::memcpy(buf, as_raw(d).bytes.data() + off, size);
}

ddsi_serdata* sample_to_ser_ref(const ddsi_serdata* d, std::size_t off, std::size_t size,
                                ddsrt_iovec_t* ref) {
  ref->iov_base = const_cast<char*>(as_raw(d).bytes.data() + off);
  ref->iov_len = static_cast<ddsrt_iov_len_t>(size);
  return ddsi_serdata_ref(d);
}

void sample_to_ser_unref(ddsi_serdata* d, const ddsrt_iovec_t*) { ddsi_serdata_unref(d); }

// Reading into a typed sample: a std::string.
bool sample_to_sample(const ddsi_serdata* d, void* sample, void**, void*) {
  *static_cast<std::string*>(sample) = as_raw(d).bytes;
  return true;
}

ddsi_serdata* sample_to_untyped(const ddsi_serdata* d) {
  ddsi_serdata* key = new_sample(d->type, SDK_KEY, 0);
  if (key != nullptr) key->type = nullptr;
  return key;
}

bool untyped_to_sample(const ddsi_sertype*, const ddsi_serdata*, void*, void**, void*) {
  return true;
}

bool sample_eqkey(const ddsi_serdata*, const ddsi_serdata*) { return true; }

std::size_t sample_print(const ddsi_sertype*, const ddsi_serdata* d, char* buf, std::size_t size) {
  const int n = std::snprintf(buf, size, "(%zu bytes of CDR)", as_raw(d).bytes.size());
  return n < 0 ? 0 : static_cast<std::size_t>(n);
}

void sample_keyhash(const ddsi_serdata*, ddsi_keyhash* buf, bool) {
  std::memset(buf, 0, sizeof(*buf));
}

const ddsi_serdata_ops kSampleOps = {
    .eqkey = sample_eqkey,
    .get_size = sample_size,
    .from_ser = sample_from_ser,
    .from_ser_iov = sample_from_ser_iov,
    .from_keyhash = sample_from_keyhash,
    .from_sample = sample_from_sample,
    .to_ser = sample_to_ser,
    .to_ser_ref = sample_to_ser_ref,
    .to_ser_unref = sample_to_ser_unref,
    .to_sample = sample_to_sample,
    .to_untyped = sample_to_untyped,
    .untyped_to_sample = untyped_to_sample,
    .free = sample_free,
    .print = sample_print,
    .get_keyhash = sample_keyhash,
#ifdef DDS_HAS_SHM  // Debian's Cyclone is built with iceoryx support; mote does not use it
    .get_sample_size = nullptr,
    .from_iox_buffer = nullptr,
#endif
};

void type_free(ddsi_sertype* t) {
  ddsi_sertype_fini(t);
  delete static_cast<RawType*>(t);
}

// Typed samples are std::string (sample_to_sample); Cyclone allocates them only for the typed
// read and take calls, which mote does not use, but the ops must exist.
void type_zero_samples(const ddsi_sertype*, void* samples, std::size_t count) {
  auto* s = static_cast<std::string*>(samples);
  for (std::size_t k = 0; k < count; ++k) s[k].clear();
}

void type_realloc_samples(void** ptrs, const ddsi_sertype*, void* old, std::size_t old_count,
                          std::size_t count) {
  auto* fresh = new std::string[count];
  auto* previous = static_cast<std::string*>(old);
  for (std::size_t k = 0; k < std::min(old_count, count); ++k) fresh[k] = std::move(previous[k]);
  delete[] previous;
  for (std::size_t k = 0; k < count; ++k) ptrs[k] = &fresh[k];
}

void type_free_samples(const ddsi_sertype*, void** ptrs, std::size_t count, dds_free_op_t op) {
  if (count == 0) return;
  auto* first = static_cast<std::string*>(ptrs[0]);
  if ((op & DDS_FREE_ALL_BIT) != 0) {
    delete[] first;
  } else {
    for (std::size_t k = 0; k < count; ++k) static_cast<std::string*>(ptrs[k])->clear();
  }
}

bool type_equal(const ddsi_sertype* a, const ddsi_sertype* b) {
  return std::strcmp(a->type_name, b->type_name) == 0;
}

uint32_t type_hash(const ddsi_sertype* t) {
  return static_cast<uint32_t>(std::hash<std::string_view>{}(t->type_name));
}

std::size_t type_serialized_size(const ddsi_sertype*, const void* sample) {
  return static_cast<const std::string_view*>(sample)->size();
}

bool type_serialize_into(const ddsi_sertype*, const void* sample, void* buffer, std::size_t size) {
  const auto& view = *static_cast<const std::string_view*>(sample);
  if (size < view.size()) return false;
  std::memcpy(buffer, view.data(), view.size());
  return true;
}

const ddsi_sertype_ops kTypeOps = {
    .version = ddsi_sertype_v0,
    .arg = nullptr,
    .free = type_free,
    .zero_samples = type_zero_samples,
    .realloc_samples = type_realloc_samples,
    .free_samples = type_free_samples,
    .equal = type_equal,
    .hash = type_hash,
    .type_id = nullptr,
    .type_map = nullptr,
    .type_info = nullptr,
    .derive_sertype = nullptr,
    .get_serialized_size = type_serialized_size,
    .serialize_into = type_serialize_into,
};

}  // namespace

ddsi_sertype* make_raw_cdr_type(const std::string& dds_type) {
  auto* t = new RawType();
  ddsi_sertype_init_flags(t, dds_type.c_str(), &kTypeOps, &kSampleOps,
                          DDSI_SERTYPE_FLAG_TOPICKIND_NO_KEY);
  // ROS 2 speaks plain CDR only: a reader or writer offering XCDR2 would not match it.
  t->allowed_data_representation = DDS_DATA_REPRESENTATION_FLAG_XCDR1;
  return t;
}

ddsi_serdata* make_raw_sample(const ddsi_sertype* type, std::string_view cdr) {
  return sample_from_sample(type, SDK_DATA, &cdr);
}

std::string_view raw_sample_bytes(const ddsi_serdata* sample) { return as_raw(sample).bytes; }

}  // namespace mote::ros::detail
