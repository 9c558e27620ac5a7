// The client protocol schema: what the file identifier and the Verifier guarantee.
#include <gtest/gtest.h>

#include "client_protocol_generated.h"

namespace zonesim::proto {
namespace {

std::vector<std::uint8_t> inputDatagram(std::uint64_t token, std::uint32_t seq) {
  flatbuffers::FlatBufferBuilder b;
  auto input = CreateInput(b, seq, 0.5f, -0.5f);
  FinishDatagramBuffer(b, CreateDatagram(b, token, Message::Input, input.Union()));
  return {b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize()};
}

TEST(ClientProtocol, AVerifiedDatagramReadsBackItsFields) {
  auto bytes = inputDatagram(0xABCDEF, 17);
  flatbuffers::Verifier v(bytes.data(), bytes.size());
  ASSERT_TRUE(VerifyDatagramBuffer(v));
  const Datagram* d = GetDatagram(bytes.data());
  EXPECT_EQ(d->token(), 0xABCDEFu);
  ASSERT_EQ(d->msg_type(), Message::Input);
  EXPECT_EQ(d->msg_as_Input()->seq(), 17u);
  EXPECT_EQ(d->msg_as_Input()->move_z(), -0.5f);
}

TEST(ClientProtocol, EveryTruncationFailsVerification) {
  auto bytes = inputDatagram(1, 2);
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    flatbuffers::Verifier v(bytes.data(), n);
    EXPECT_FALSE(VerifyDatagramBuffer(v)) << "prefix of " << n << " bytes verified";
  }
}

TEST(ClientProtocol, ABufferWithAnotherIdentifierIsRejected) {
  auto bytes = inputDatagram(1, 2);
  bytes[4] = 'X';  // "ZSCP" -> "XSCP"
  flatbuffers::Verifier v(bytes.data(), bytes.size());
  EXPECT_FALSE(VerifyDatagramBuffer(v));
}

}  // namespace
}  // namespace zonesim::proto
