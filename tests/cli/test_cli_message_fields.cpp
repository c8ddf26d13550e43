// The fields `imucal echo` and `imucal log2csv` show (cli/message_fields.cpp) are exactly those of the .lcm
// files, in their order, shape and kind, so a field added to a message cannot be silently left out; and
// received bytes are told apart by their fingerprint: each imucal type, a foreign type, a broken message.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <regex>

#include "lcm_sample_messages.hpp"
#include "message_fields.hpp"
#include "message_types.hpp"

namespace imucal::cli {
namespace {

using namespace imucal::testing;

struct Declared {
  std::string kind, name, size;  // size: "" scalar, digits fixed, a field name variable
};

// The field declarations of lcmtypes/<type>.lcm (constants and comments left out).
std::vector<Declared> declaredFields(const std::string& type) {
  std::ifstream in(std::string(IMUCAL_TEST_DATA_DIR) + "/../../lcmtypes/" + type + ".lcm");
  EXPECT_TRUE(in.good()) << type;
  const std::regex field(R"(^\s*(int8_t|int16_t|int32_t|int64_t|double|float|boolean|string|byte)\s+(\w+)\s*(\[\s*(\w+)\s*\])?\s*;)");
  std::vector<Declared> out;
  std::smatch m;
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, m, field)) out.push_back({m[1], m[2], m[4]});
  return out;
}

std::string kindOf(const Field& f) {
  switch (f.values.index()) {
    case 0: return "integer";
    case 1: return "double";
    case 2: return "boolean";
    default: return "string";
  }
}

std::string expectedKind(const std::string& lcm_kind) {
  if (lcm_kind == "double" || lcm_kind == "boolean" || lcm_kind == "string") return lcm_kind;
  return "integer";
}

void expectAsDeclared(const MessageRecord& r) {
  const std::vector<Declared> declared = declaredFields(std::string(r.type));
  ASSERT_EQ(r.fields.size(), declared.size()) << r.type;
  ASSERT_GT(declared.size(), 2u) << r.type;
  for (std::size_t i = 0; i < declared.size(); ++i) {
    const Field& f = r.fields[i];
    const Declared& d = declared[i];
    EXPECT_EQ(f.name, d.name) << r.type << " field " << i;
    EXPECT_EQ(kindOf(f), expectedKind(d.kind)) << r.type << "." << d.name;
    const Shape shape = d.size.empty() ? Shape::Scalar : std::isdigit(static_cast<unsigned char>(d.size[0])) ? Shape::Fixed : Shape::Variable;
    EXPECT_EQ(static_cast<int>(f.shape), static_cast<int>(shape)) << r.type << "." << d.name;
    const std::size_t size = shape == Shape::Fixed ? std::stoul(d.size) : 1;
    if (shape != Shape::Variable) {
      EXPECT_EQ(f.size(), size) << r.type << "." << d.name;
    }
  }
}

TEST(CliMessageFields, EveryTypeListsTheFieldsOfItsLcmFile) {
  expectAsDeclared(describe(sampleImu()));
  expectAsDeclared(describe(sampleStampedBatch()));
  expectAsDeclared(describe(sampleHeading()));
  expectAsDeclared(describe(sampleMagField()));
  expectAsDeclared(describe(sampleCalibration()));
  expectAsDeclared(describe(sampleStatus()));
  expectAsDeclared(describe(sampleProgress()));
  expectAsDeclared(describe(sampleTrigger()));
}

TEST(CliMessageFields, VariableArraysKeepTheirElements) {
  const MessageRecord r = describe(sampleCalibration());
  ASSERT_EQ(r.fields[16].name, "param_names");
  EXPECT_EQ(std::get<std::vector<std::string>>(r.fields[16].values), sampleCalibration().param_names);
  ASSERT_EQ(r.fields[19].name, "converged");
  EXPECT_EQ(std::get<std::vector<bool>>(r.fields[19].values), (std::vector<bool>{true, false}));
  const MessageRecord b = describe(sampleEvenBatch());
  ASSERT_EQ(b.fields[5].name, "sample_utime");
  EXPECT_EQ(b.fields[5].size(), 0u);
  ASSERT_EQ(b.fields[13].name, "status");
  EXPECT_EQ(std::get<std::vector<std::int64_t>>(b.fields[13].values), (std::vector<std::int64_t>{0, 1, 16}));
}

template <class Msg>
void expectIdentified(const Msg& m) {
  const auto bytes = encoded(m);
  const DecodedMessage d = decodeImucalMessage(bytes.data(), bytes.size());
  EXPECT_EQ(static_cast<int>(d.status), static_cast<int>(DecodedMessage::Status::Decoded)) << Msg::getTypeName();
  EXPECT_EQ(d.type, Msg::getTypeName());
  EXPECT_EQ(d.record.type, Msg::getTypeName());
  ASSERT_FALSE(d.record.fields.empty());
  EXPECT_EQ(std::get<std::vector<std::int64_t>>(d.record.fields[0].values).at(0), m.utime) << Msg::getTypeName();
  // One byte short: still named by its fingerprint, but not decoded.
  const DecodedMessage cut = decodeImucalMessage(bytes.data(), bytes.size() - 1);
  EXPECT_EQ(static_cast<int>(cut.status), static_cast<int>(DecodedMessage::Status::Undecodable)) << Msg::getTypeName();
  EXPECT_EQ(cut.type, Msg::getTypeName());
}

TEST(CliMessageTypes, EachTypeIsKnownByItsFingerprint) {
  expectIdentified(sampleImu());
  expectIdentified(sampleEvenBatch());
  expectIdentified(sampleHeading());
  expectIdentified(sampleMagField());
  expectIdentified(sampleCalibration());
  expectIdentified(sampleStatus());
  expectIdentified(sampleProgress());
  expectIdentified(sampleTrigger());
}

TEST(CliMessageTypes, ForeignAndShortBytesAreOfUnknownType) {
  auto bytes = encoded(sampleHeading());
  bytes[7] ^= 0x01;  // another fingerprint, same payload
  const DecodedMessage foreign = decodeImucalMessage(bytes.data(), bytes.size());
  EXPECT_EQ(static_cast<int>(foreign.status), static_cast<int>(DecodedMessage::Status::UnknownType));
  EXPECT_EQ(foreign.type, "");
  const auto whole = encoded(sampleHeading());
  const DecodedMessage shorter = decodeImucalMessage(whole.data(), 7);  // not even a fingerprint
  EXPECT_EQ(static_cast<int>(shorter.status), static_cast<int>(DecodedMessage::Status::UnknownType));
  EXPECT_EQ(static_cast<int>(decodeImucalMessage(nullptr, 0).status), static_cast<int>(DecodedMessage::Status::UnknownType));
}

}  // namespace
}  // namespace imucal::cli
