// SHA-256 against FIPS 180-4's examples (and NIST's long-message vector), plus messages around
// the padding boundaries checked with Python's hashlib, and streaming in uneven pieces.
#include "auth/sha256.h"

#include <gtest/gtest.h>

#include "hex.h"

namespace zonesim::auth {
namespace {

using test::bytesOf;
using test::hex;

TEST(Sha256, FipsExamples) {
  EXPECT_EQ(hex(sha256(bytesOf("abc"))),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(hex(sha256(bytesOf(""))),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(hex(sha256(bytesOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"))),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(hex(sha256(bytesOf("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                               "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"))),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, OneMillionA) {
  std::vector<std::uint8_t> a(1'000'000, 'a');
  EXPECT_EQ(hex(sha256(a)), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// 55 and 56 bytes: the length still fits the last block, or needs one more; 63-65 straddle a
// block; 119-120 the same one block later.
TEST(Sha256, PaddingBoundaries) {
  const std::pair<std::size_t, const char*> cases[] = {
      {55, "463eb28e72f82e0a96c0a4cc53690c571281131f672aa229e0d45ae59b598b59"},
      {56, "da2ae4d6b36748f2a318f23e7ab1dfdf45acdc9d049bd80e59de82a60895f562"},
      {63, "29af2686fd53374a36b0846694cc342177e428d1647515f078784d69cdb9e488"},
      {64, "fdeab9acf3710362bd2658cdc9a29e8f9c757fcf9811603a8c447cd1d9151108"},
      {65, "4bfd2c8b6f1eec7a2afeb48b934ee4b2694182027e6d0fc075074f2fabb31781"},
      {119, "da18797ed7c3a777f0847f429724a2d8cd5138e6ed2895c3fa1a6d39d18f7ec6"},
      {120, "f52b23db1fbb6ded89ef42a23ce0c8922c45f25c50b568a93bf1c075420bbb7c"},
  };
  for (auto [n, expected] : cases) {
    std::vector<std::uint8_t> m(n);
    for (std::size_t i = 0; i < n; ++i) m[i] = std::uint8_t(i % 251);
    EXPECT_EQ(hex(sha256(m)), expected) << n << " bytes";
  }
}

TEST(Sha256, StreamingInPiecesEqualsOneShot) {
  std::vector<std::uint8_t> m(1000);
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = std::uint8_t(i * 7 + 3);
  Digest whole = sha256(m);
  for (std::size_t piece : {1u, 3u, 63u, 64u, 65u, 200u}) {
    Sha256 h;
    for (std::size_t i = 0; i < m.size(); i += piece)
      h.update(std::span(m).subspan(i, std::min(piece, m.size() - i)));
    EXPECT_EQ(h.finish(), whole) << "pieces of " << piece;
  }
}

}  // namespace
}  // namespace zonesim::auth
