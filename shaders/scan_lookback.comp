#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_memory_scope_semantics : require
// Ordered inclusive scan in one pass: decoupled look-back (Merrill and Garland 2016). Each
// workgroup takes tiles of kLookbackTile elements in the order it starts them (an atomic
// counter), publishes its tile's sum, walks back over its predecessors' states for the sum
// before the tile, and publishes the sum up to and including it.
//
// Vulkan guarantees no forward progress between workgroups, so a workgroup never waits
// unboundedly on a predecessor: after p.polls reads of a state that is not ready it reduces that
// tile itself and goes on looking back (decoupled fallback, Smith, Levien and Owens 2025).
//
// A tile's state is one uint64 in p.block_sums: a 2-bit flag above a 62-bit value (the host
// asks for this scan only when its bound on the total is below 2^62, and runs a frame whose
// total exceeds the bound again). Flags order as the states progress, so every publication is
// an atomicMax and none undoes a later one; a tile's sum is the same whoever reduces it. The
// values travel in the state words themselves; the atomics use the Vulkan memory model at
// queue-family scope (release on publication, acquire on reading).
#include "workgroup.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { ScanPush p; };

const uint64_t kValueMask = (1ul << 62) - 1ul;
const uint64_t kAggregate = 1ul << 62;  // the value is the tile's own sum
const uint64_t kInclusive = 2ul << 62;  // the value is the sum up to and including the tile

// Invocation 0's tile index and look-back reads, shared with the workgroup.
shared uint64_t shared_tile;
shared uint64_t shared_state;

Uint64s tile_counter() { return uint64_at(p.block_sums, 0ul); }
Uint64s tile_state(uint64_t tile) { return uint64_at(p.block_sums, tile + 1ul); }

void publish(uint64_t tile, uint64_t state) {
  atomicMax(tile_state(tile).v[0], state, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer, gl_SemanticsRelease);
}

// Tile `tile`'s state, read up to p.polls times while it is not ready (0).
uint64_t poll(uint64_t tile) {
  uint64_t state = 0ul;
  for (uint k = 0u; k < p.polls && state == 0ul; ++k)
    state = atomicLoad(tile_state(tile).v[0], gl_ScopeQueueFamily, gl_StorageSemanticsBuffer, gl_SemanticsAcquire);
  return state;
}

// The sum of this invocation's elements of tile `tile`, each element written to `items`.
uint64_t load_items(uint64_t tile, out uint64_t items[kLookbackItems]) {
  uint64_t first = tile * kLookbackTile + uint64_t(gl_LocalInvocationIndex) * kLookbackItems;
  uint64_t sum = 0ul;
  for (uint k = 0u; k < kLookbackItems; ++k) {
    items[k] = first + k < p.count ? uint64_at(p.source, first + k).v[0] : 0ul;
    sum += items[k];
  }
  return sum;
}

// Sum of the workgroup's values before this invocation's, and the workgroup's total.
uint64_t workgroup_exclusive_add(uint64_t value, out uint64_t total) {
  uint64_t before = subgroupExclusiveAdd(value);
  gather_subgroups(subgroupAdd(value));
  total = 0ul;
  for (uint s = 0u; s < gl_NumSubgroups; ++s) {
    if (s < gl_SubgroupID) before += subgroup_values[s];
    total += subgroup_values[s];
  }
  return before;
}

// The sum of the elements before tile `tile`, at invocation 0. Invocation 0 reads each
// predecessor's state; the workgroup follows it through shared memory, so the loop and the
// fallback's reduction (which holds barriers) are workgroup-uniform.
uint64_t exclusive_prefix(uint64_t tile) {
  uint64_t prefix = 0ul;
  for (uint64_t predecessor = tile; predecessor > 0ul;) {
    --predecessor;
    if (gl_LocalInvocationIndex == 0u) shared_state = poll(predecessor);
    barrier();
    uint64_t state = shared_state;
    barrier();  // every read is done before the next iteration's write
    if (state == 0ul) {
      uint64_t items[kLookbackItems];
      uint64_t sum = workgroup_add(load_items(predecessor, items));
      if (gl_LocalInvocationIndex == 0u) publish(predecessor, kAggregate | sum);
      prefix += sum;
    } else {
      prefix += state & kValueMask;
      if (state >= kInclusive) break;
    }
  }
  return prefix;
}

void main() {
  uint64_t tiles = (p.count + kLookbackTile - 1ul) / kLookbackTile;
  for (;;) {
    // Tiles are numbered as workgroups take them: a tile waits only on tiles already started.
    if (gl_LocalInvocationIndex == 0u)
      shared_tile = atomicAdd(tile_counter().v[0], 1ul, gl_ScopeQueueFamily, gl_StorageSemanticsBuffer,
                              gl_SemanticsRelaxed);
    barrier();
    uint64_t tile = shared_tile;
    barrier();  // every read is done before the next tile's write
    if (tile >= tiles) break;
    uint64_t items[kLookbackItems];
    uint64_t tile_sum;
    uint64_t before = workgroup_exclusive_add(load_items(tile, items), tile_sum);
    if (gl_LocalInvocationIndex == 0u) publish(tile, (tile == 0ul ? kInclusive : kAggregate) | tile_sum);
    uint64_t prefix = exclusive_prefix(tile);
    if (gl_LocalInvocationIndex == 0u) {
      if (tile > 0ul) publish(tile, kInclusive | (prefix + tile_sum));
      shared_state = prefix;
    }
    barrier();
    uint64_t sum = shared_state + before;
    uint64_t first = tile * kLookbackTile + uint64_t(gl_LocalInvocationIndex) * kLookbackItems;
    for (uint k = 0u; k < kLookbackItems; ++k) {
      sum += items[k];
      if (first + k < p.count) uint64_at(p.result, first + k).v[0] = sum;
    }
  }
}
