// Contacts: the persistent arbiters between pairs of bodies (the appendix's arbiters).
//
// Each step the world turns candidate pairs into manifolds (narrowphase.hpp) and keeps them
// in one list sorted by (body id index a, b, sub-shape), a < b. A manifold's accumulated
// impulses survive to the next step when the same pair reports the same feature ids, so the
// solver starts from last step's answer (warm starting). Pairs whose bodies both rest
// (asleep, or asleep against static geometry) are not recomputed: their records are carried
// over unchanged, which keeps sleeping islands connected. Everything is ordered by ids, so
// the list depends only on the bodies, never on slots, threads or SIMD width.
#pragma once

#include "dynamics/body_store.hpp"
#include "dynamics/broadphase.hpp"
#include "dynamics/manifold.hpp"

#include <cstdint>
#include <vector>

namespace gyro::detail {

struct ContactRecord {
  uint64_t key = 0;   ///< (id index of a) << 32 | id index of b, a < b
  uint32_t sub = 0;   ///< triangle index against a mesh body, else 0
  uint32_t gen_a = 0, gen_b = 0;  ///< id generations, so a reused index never matches
  uint32_t slot_a = 0, slot_b = 0;  ///< dense slots this step
  float friction = 0.0f, restitution = 0.0f;
  Manifold manifold;  ///< normal from a to b
  float normal_impulse[kMaxManifoldPoints] = {};
  /// Patch friction of the manifold (at the points' centre): along tangent 1, tangent 2 and
  /// about the normal (the tangents are a function of the normal, so they carry over).
  float friction_impulse[3] = {};
  ContactAnchors anchors;  ///< incremental convex manifolds only

  uint32_t index_a() const { return uint32_t(key >> 32); }
  uint32_t index_b() const { return uint32_t(key); }
  /// At least one point with separation <= 0 (speculative points do not touch).
  bool touching() const;
};

struct ContactSettings {
  float speculative_distance = 0.02f;  ///< margin kept for every pair
  bool continuous = true;              ///< widen the margin by the motion of the step
  bool incremental_convex = false;     ///< capsule/hull pairs: the arbiter approach, not clipping
  float dt = 0.0f;
};

/// One candidate pair, slots in key order.
struct CandidatePair {
  uint32_t a, b;
};

class ContactSet {
 public:
  /// Recomputes the records of the candidate pairs (sorted by key, at least one body active)
  /// and carries over the old records whose bodies are both inactive (`active[slot]`).
  /// Warm-start impulses move from the old records to matching new points. Fills the
  /// begin/end touch events.
  void update(const BodyStore& bodies, const std::vector<CandidatePair>& pairs, const uint8_t* active,
              const ContactSettings& settings);

  std::vector<ContactRecord>& records() { return records_; }
  const std::vector<ContactRecord>& records() const { return records_; }
  const std::vector<ContactEvent>& begin_events() const { return begin_; }
  const std::vector<ContactEvent>& end_events() const { return end_; }
  void clear();

  /// Replaces the records (a snapshot being restored); last step's touching pairs, which the
  /// next step's events are measured against, follow from them. The events are cleared.
  void set_records(std::vector<ContactRecord>&& records);

  /// Drops every record naming the body (it is being destroyed).
  void remove_body(uint32_t id_index);

  /// A body moved from slot `from` to slot `to` (a destroy swapped it into the hole).
  void remap_slot(uint32_t from, uint32_t to);

  void hash_into(StateHasher& h) const;

 private:
  std::vector<ContactRecord> records_, old_;
  std::vector<uint32_t> pair_first_;  ///< per candidate pair: first record in scratch_
  std::vector<uint32_t> pair_count_;
  std::vector<ContactRecord> scratch_;
  std::vector<ContactEvent> begin_, end_;
  struct TouchKey {
    uint64_t key;
    ContactEvent event;
  };
  std::vector<TouchKey> touch_old_, touch_new_;
  static void touching_pairs(const std::vector<ContactRecord>& list, std::vector<TouchKey>& keys);
};

}  // namespace gyro::detail
