// Bitonic sort of (key, value) uint pairs by key, then value, for gpu/cl_sort.cpp. Values are
// unique agent ids, so the order is total and every device produces the same permutation as a
// stable sort by key: ids ascend within a key, the order the CPU reference visits them in.
//
// n is a power of two (the host pads with key 0xffffffff). Work item i handles one pair. Stages
// with a partner distance j below the work-group's span run in local memory, so a sort of
// 2^20 pairs takes about 80 launches instead of 210.

inline bool after(uint ka, uint va, uint kb, uint vb) {
  return ka > kb || (ka == kb && va > vb);
}

// The element index of pair i at distance j: i with a zero inserted at bit log2(j).
inline uint pair_low(uint i, uint j) {
  return ((i & ~(j - 1u)) << 1) | (i & (j - 1u));
}

// One compare-exchange stage (j, k) over the whole array, for j too large for local memory.
__kernel void bitonic_global(__global uint* keys, __global uint* vals, uint j, uint k) {
  uint lo = pair_low(get_global_id(0), j);
  uint hi = lo + j;
  bool ascending = (lo & k) == 0u;
  uint ka = keys[lo], kb = keys[hi], va = vals[lo], vb = vals[hi];
  if (after(ka, va, kb, vb) == ascending) {
    keys[lo] = kb;
    keys[hi] = ka;
    vals[lo] = vb;
    vals[hi] = va;
  }
}

// The stages j = j_start, j_start / 2, ..., 1 of merge level k, inside one work-group's block
// of 2 * local_size elements; with k_first < k it first runs every level from k_first up.
__kernel void bitonic_local(__global uint* keys, __global uint* vals, __local uint* lk,
                            __local uint* lv, uint k_first, uint k_last) {
  uint lid = get_local_id(0);
  uint span = 2u * get_local_size(0);
  uint base = get_group_id(0) * span;
  lk[lid] = keys[base + lid];
  lv[lid] = vals[base + lid];
  lk[lid + span / 2u] = keys[base + lid + span / 2u];
  lv[lid + span / 2u] = vals[base + lid + span / 2u];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint k = k_first; k <= k_last; k <<= 1) {
    for (uint j = min(k, span) >> 1; j > 0u; j >>= 1) {
      uint lo = pair_low(lid, j);
      uint hi = lo + j;
      bool ascending = ((base + lo) & k) == 0u;
      uint ka = lk[lo], kb = lk[hi], va = lv[lo], vb = lv[hi];
      if (after(ka, va, kb, vb) == ascending) {
        lk[lo] = kb;
        lk[hi] = ka;
        lv[lo] = vb;
        lv[hi] = va;
      }
      barrier(CLK_LOCAL_MEM_FENCE);
    }
  }
  keys[base + lid] = lk[lid];
  vals[base + lid] = lv[lid];
  keys[base + lid + span / 2u] = lk[lid + span / 2u];
  vals[base + lid + span / 2u] = lv[lid + span / 2u];
}
