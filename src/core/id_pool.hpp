// IdPool: stable ids {index, generation} over dense slots.
//
// Objects live in dense SoA slots 0..size()-1. An id names an object for its whole life:
// index picks an entry in the id table, generation tells a live id from a stale one (a
// destroyed object's entry gets a new generation, so a kept id is detected, never
// followed). Destroying moves the last dense slot into the hole (the owner does the same
// to its columns). Freed indices are reused last-freed-first. Everything depends only on
// the sequence of calls, so two worlds fed the same calls hand out the same ids.
// All-zero is the null id: generations start at 1 and skip 0 when they wrap.
#pragma once

#include "core/byte_stream.hpp"

#include <cstdint>
#include <vector>

namespace gyro::detail {

struct Id {
  uint32_t index = 0;
  uint32_t generation = 0;
  friend bool operator==(Id a, Id b) { return a.index == b.index && a.generation == b.generation; }
  bool is_null() const { return index == 0 && generation == 0; }
};

class IdPool {
 public:
  static constexpr uint32_t kNoSlot = 0xFFFFFFFFu;

  struct Removal {
    uint32_t slot;        // the slot that was freed
    uint32_t moved_from;  // the slot whose object moved into it (== slot when it was the last)
  };

  uint32_t size() const { return static_cast<uint32_t>(dense_.size()); }

  Id create() {
    uint32_t index;
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
    } else {
      index = static_cast<uint32_t>(entries_.size());
      entries_.push_back({1, kNoSlot});
    }
    Entry& e = entries_[index];
    e.slot = static_cast<uint32_t>(dense_.size());
    dense_.push_back(index);
    return {index, e.generation};
  }

  /// The index the next create() will hand out.
  uint32_t next_index() const { return free_.empty() ? static_cast<uint32_t>(entries_.size()) : free_.back(); }

  bool valid(Id id) const {
    return id.index < entries_.size() && entries_[id.index].generation == id.generation &&
           entries_[id.index].slot != kNoSlot;
  }

  /// Dense slot of a live id, kNoSlot for a stale or null one.
  uint32_t slot(Id id) const { return valid(id) ? entries_[id.index].slot : kNoSlot; }

  /// The id living in a dense slot.
  Id id_at(uint32_t slot) const { return {dense_[slot], entries_[dense_[slot]].generation}; }

  /// Precondition: valid(id).
  Removal destroy(Id id) {
    Entry& e = entries_[id.index];
    const uint32_t hole = e.slot;
    const uint32_t last = static_cast<uint32_t>(dense_.size() - 1);
    if (hole != last) {
      dense_[hole] = dense_[last];
      entries_[dense_[hole]].slot = hole;
    }
    dense_.pop_back();
    e.slot = kNoSlot;
    e.generation = e.generation + 1 == 0 ? 1 : e.generation + 1;
    free_.push_back(id.index);
    return {hole, last};
  }

  /// Feeds the whole allocator state to a hasher (generations, slots, free order).
  template <class Hasher> void hash_into(Hasher& h) const {
    h.add_u64(entries_.size());
    for (const Entry& e : entries_) h.add_u64((uint64_t{e.generation} << 32) | e.slot);
    h.add_u64(free_.size());
    for (uint32_t f : free_) h.add_u64(f);
  }

  /// The whole allocator as snapshot bytes (entries, dense order, free order).
  void write(ByteWriter& w) const {
    w.u64(entries_.size());
    for (const Entry& e : entries_) w.u32(e.generation), w.u32(e.slot);
    w.array(dense_);
    w.array(free_);
  }
  /// Reads an allocator and checks it whole: every entry is live (its slot names a dense
  /// position that names it back) or free (listed once), generations are never 0. On failure
  /// the reader is marked failed and this pool is unspecified (read into a fresh one).
  void read(ByteReader& r) {
    std::size_t n = 0;
    r.count(n, r.remaining() / 8);
    if (!r.ok()) return;
    try {
      entries_.assign(n, Entry{1, kNoSlot});
    } catch (const std::bad_alloc&) {
      r.fail();
      return;
    }
    for (Entry& e : entries_) r.u32(e.generation), r.u32(e.slot);
    r.array(dense_);
    r.array(free_);
    if (!r.ok()) return;
    r.require(n < kNoSlot && dense_.size() + free_.size() == n);
    std::vector<uint8_t> seen(r.ok() ? n : 0, 0);
    for (std::size_t i = 0; r.ok() && i < dense_.size(); ++i) {
      const uint32_t index = dense_[i];
      r.require(index < n && entries_[index].slot == i && entries_[index].generation != 0 && !seen[index]);
      if (r.ok()) seen[index] = 1;
    }
    for (std::size_t i = 0; r.ok() && i < free_.size(); ++i) {
      const uint32_t index = free_[i];
      r.require(index < n && entries_[index].slot == kNoSlot && entries_[index].generation != 0 && !seen[index]);
      if (r.ok()) seen[index] = 1;
    }
  }

 private:
  struct Entry {
    uint32_t generation;
    uint32_t slot;
  };
  std::vector<Entry> entries_;
  std::vector<uint32_t> dense_;
  std::vector<uint32_t> free_;
};

}  // namespace gyro::detail
