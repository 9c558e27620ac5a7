#pragma once
// Graph colouring of contact constraints for the wide solver (Box2D v3's constraint graph):
// constraints of one colour share no movable body, so a block of them can be solved in SIMD
// lanes at once, each lane reading and writing its own bodies. Immovable bodies (static,
// kinematic, held) are only read, so any number of lanes may share one. The same blocks can
// instead be packed in constraint order (buildInOrder), which solves as one constraint at a
// time.
//
// The layout is fixed at kBlockLanes lanes whatever width solves it: a 4-wide solve takes each
// block as two halves, a scalar one lane by lane, and since the lanes of a block touch
// disjoint bodies every width gives the same result bit for bit.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace zonesim::physics {

/// Lanes of one block: the widest SIMD width (8 floats, AVX2).
constexpr int kBlockLanes = 8;
/// Colours before a constraint overflows: one bit each in a body's 64-bit mask.
constexpr int kMaxColours = 64;
/// A lane that holds no constraint.
constexpr std::uint32_t kEmptyLane = 0xffffffffu;

/// The two bodies of a constraint and whether impulses move each.
struct ConstraintBodies {
  std::uint32_t a = 0, b = 0;
  bool a_moves = false, b_moves = false;
};

/// Constraints coloured and packed into blocks of kBlockLanes lanes, colour after colour.
class ConstraintColouring {
 public:
  /// Greedy colouring in constraint order: each constraint takes the lowest colour that neither
  /// of its movable bodies has yet. A constraint that finds none of the kMaxColours free (a body
  /// touching more than 64 others) overflows into a block of its own, solved alone after the
  /// coloured blocks.
  void build(std::span<const ConstraintBodies> constraints, std::size_t body_count);
  /// Packs instead of colouring, keeping the order: each constraint goes to the first block
  /// with a free lane after the last block holding either of its movable bodies. Constraints
  /// that share no body commute, so solving the blocks in order is solving the constraints one
  /// by one in their own order, bit for bit, with every lane of a block in use where the
  /// constraints allow it. No colours (colourCount() is 0) and no overflow.
  void buildInOrder(std::span<const ConstraintBodies> constraints, std::size_t body_count);
  /// The constraint index of every lane, block after block (kEmptyLane pads a colour's last
  /// block).
  std::span<const std::uint32_t> lanes() const { return lanes_; }
  /// Number of blocks.
  std::size_t blockCount() const { return lanes_.size() / kBlockLanes; }
  /// Number of colours used (overflow blocks not counted).
  std::size_t colourCount() const {
    return colour_first_block_.empty() ? 0 : colour_first_block_.size() - 1;
  }
  /// First block of each colour, then the first overflow block.
  std::span<const std::uint32_t> colourFirstBlock() const { return colour_first_block_; }
  /// Constraints that found no colour.
  std::size_t overflowCount() const { return overflow_; }

 private:
  std::vector<std::uint64_t> body_colours_;  // bit c: the body has a constraint of colour c
  std::vector<std::uint8_t> colour_of_;      // kMaxColours: overflow
  std::vector<std::uint32_t> lanes_, colour_first_block_, next_lane_;
  std::vector<std::uint32_t> last_block_, free_after_;  // buildInOrder
  std::vector<std::uint8_t> used_lanes_;
  std::size_t overflow_ = 0;
};

}  // namespace zonesim::physics
