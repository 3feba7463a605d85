// lsi's own deflate blocks of byte planes (io/deflate_planes.hpp): zlib inflates every stream
// back to the planes, bit for bit, for planes of every kind (random, few values, runs of every
// length around the match limits, one byte, none, larger than a stored block), the Huffman codes
// stay within deflate's 15 bits where a minimum-redundancy code would be longer, and each plane
// takes the size its coding should give.
#include "io/deflate_planes.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace {

using lsi::hdf5::PlaneCoding;
using lsi::hdf5::PlaneDeflater;
using Bytes = std::vector<unsigned char>;

// The stream of `planes` planes of equal size, all coded as `coding`.
Bytes deflate_all(const Bytes& bytes, std::size_t planes, PlaneCoding coding) {
  const std::size_t plane_bytes = planes == 0 ? 0 : bytes.size() / planes;
  Bytes out(PlaneDeflater::bound(plane_bytes, planes));
  const std::vector<PlaneCoding> codings(planes, coding);
  PlaneDeflater d;
  out.resize(d.deflate(bytes.data(), plane_bytes, planes, codings.data(), out.data()));
  return out;
}

// zlib's inflate of a stream; fails the test where zlib rejects it or finds other bytes.
void expect_inflates_to(const Bytes& stream, const Bytes& bytes, const std::string& what) {
  Bytes back(bytes.size() + 1);
  uLongf size = static_cast<uLongf>(back.size());
  const int r = uncompress(back.data(), &size, stream.data(), static_cast<uLong>(stream.size()));
  ASSERT_EQ(r, Z_OK) << what << ": zlib rejects the stream";
  back.resize(size);
  EXPECT_TRUE(back == bytes) << what << ": inflated to other bytes";
}

// The size of zlib's deflate of `bytes` with a strategy (level 4, the sweep tables' level).
std::size_t zlib_size(const Bytes& bytes, int strategy) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 4, Z_DEFLATED, 15, 8, strategy), Z_OK);
  Bytes out(deflateBound(&z, static_cast<uLong>(bytes.size())));
  z.next_in = const_cast<unsigned char*>(bytes.data());
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  const std::size_t size = z.total_out;
  deflateEnd(&z);
  return size;
}

// The order-0 entropy of `bytes`, in bytes: what no code of single bytes goes below.
double entropy_bytes(const Bytes& bytes) {
  std::vector<double> count(256, 0.0);
  for (const unsigned char b : bytes) ++count[b];
  double bits = 0.0;
  for (const double c : count)
    if (c > 0) bits -= c * std::log2(c / double(bytes.size()));
  return bits / 8.0;
}

Bytes random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 g(seed);
  Bytes b(n);
  for (auto& x : b) x = static_cast<unsigned char>(g());
  return b;
}

TEST(DeflatePlanes, EveryCodingOfEveryKindOfPlaneInflatesBack) {
  std::mt19937 g(3);
  std::vector<std::pair<std::string, Bytes>> planes;
  planes.push_back({"random", random_bytes(4096, 1)});
  Bytes few(4096);  // four values, no runs to speak of
  for (auto& x : few) x = static_cast<unsigned char>(0x40 + g() % 4);
  planes.push_back({"four values", few});
  planes.push_back({"one value", Bytes(4096, 0x3f)});
  // Runs of every length from 1 to 600 (matches of 3 to 258 bytes, longer runs cut at 258),
  // of alternating values.
  Bytes runs;
  for (int r = 1; runs.size() < 60000; r = r % 600 + 1)
    runs.insert(runs.end(), r, r % 2 ? 0 : 0xc0);
  runs.resize(60000);
  planes.push_back({"runs", runs});
  planes.push_back({"one byte", Bytes{0x7}});
  for (const auto& [name, plane] : planes)
    for (const PlaneCoding c : {PlaneCoding::stored, PlaneCoding::huffman, PlaneCoding::runs})
      expect_inflates_to(deflate_all(plane, 1, c), plane,
                         name + ", coding " + std::to_string(int(c)));
  expect_inflates_to(deflate_all(Bytes{}, 0, PlaneCoding::runs), Bytes{}, "no plane");
}

TEST(DeflatePlanes, PlanesOfMixedCodingsInOneStreamInflateBack) {
  // Eight planes as a shuffled chunk of doubles has them: random, few values, runs, in an order
  // that puts stored planes next to each other and between coded ones.
  const std::size_t n = 4096;
  Bytes bytes;
  std::vector<PlaneCoding> codings;
  std::mt19937 g(5);
  for (int j = 0; j < 8; ++j) {
    Bytes p = j < 5 ? random_bytes(n, 10 + j) : Bytes(n, static_cast<unsigned char>(0x3f + j));
    if (j == 3)
      for (auto& x : p) x = static_cast<unsigned char>(g() % 16);
    bytes.insert(bytes.end(), p.begin(), p.end());
    codings.push_back(j == 3  ? PlaneCoding::huffman
                      : j < 5 ? PlaneCoding::stored
                              : PlaneCoding::runs);
  }
  Bytes out(PlaneDeflater::bound(n, 8));
  PlaneDeflater d;
  out.resize(d.deflate(bytes.data(), n, 8, codings.data(), out.data()));
  expect_inflates_to(out, bytes, "mixed planes");
  // A deflater used before gives the same bytes as a new one.
  Bytes again(out.size() + 64);
  PlaneDeflater fresh;
  again.resize(fresh.deflate(bytes.data(), n, 8, codings.data(), again.data()));
  EXPECT_TRUE(again == out);
}

TEST(DeflatePlanes, LargerThanAStoredBlockInflatesBack) {
  // A stored block holds at most 65535 bytes: 200 000 random bytes take four.
  const Bytes b = random_bytes(200000, 9);
  const Bytes out = deflate_all(b, 1, PlaneCoding::stored);
  expect_inflates_to(out, b, "200 000 random bytes");
  // zlib's header and checksum (6 bytes) and four block headers of 5 bytes (and 3 bits).
  EXPECT_LE(out.size(), b.size() + 6 + 4 * 5 + 1);
}

TEST(DeflatePlanes, CodesLongerThanFifteenBitsAreLimited) {
  // Byte k appears Fibonacci(k + 1) times (1, 1, 2, 3, 5, ...) for k < 24: a minimum-redundancy
  // code gives the rarest bytes 23 bits, which deflate cannot send; the stream must still inflate,
  // and its size stay that of a near-optimal code within the limit (zlib's, which limits its
  // codes similarly: within 1 %, for the blocks' headers).
  Bytes b;
  std::uint64_t f0 = 1, f1 = 1;
  for (int k = 0; k < 24; ++k) {
    b.insert(b.end(), f0, static_cast<unsigned char>(k));
    const std::uint64_t f2 = f0 + f1;
    f0 = f1;
    f1 = f2;
  }
  std::shuffle(b.begin(), b.end(), std::mt19937(2));  // no runs to speak of
  for (const PlaneCoding c : {PlaneCoding::huffman, PlaneCoding::runs}) {
    const Bytes out = deflate_all(b, 1, c);
    expect_inflates_to(out, b, "Fibonacci frequencies, coding " + std::to_string(int(c)));
    EXPECT_GT(double(out.size()), entropy_bytes(b)) << int(c);
    EXPECT_LT(double(out.size()), 1.01 * double(zlib_size(b, Z_HUFFMAN_ONLY))) << int(c);
  }
}

TEST(DeflatePlanes, EachPlaneTakesTheSizeOfItsCoding) {
  const std::size_t n = 16384;
  // Bytes of probabilities 1/2, 1/4, 1/8, 1/8: no block beats their entropy, 1.75 bits a byte;
  // the Huffman block is an optimal code, as zlib's Huffman-only strategy's (within 1 %, for the
  // headers).
  Bytes dyadic(n);
  std::mt19937 g(8);
  for (auto& x : dyadic) {
    const unsigned u = g() % 8;
    x = static_cast<unsigned char>(u < 4 ? 'a' : u < 6 ? 'b' : u < 7 ? 'c' : 'd');
  }
  const Bytes coded = deflate_all(dyadic, 1, PlaneCoding::huffman);
  EXPECT_GT(double(coded.size()), entropy_bytes(dyadic));
  EXPECT_LT(double(coded.size()), 1.01 * double(zlib_size(dyadic, Z_HUFFMAN_ONLY)));
  // The same plane allowed no more than storing: its bytes, plus 11 bytes of headers.
  EXPECT_EQ(deflate_all(dyadic, 1, PlaneCoding::stored).size(), n + 6 + 5);
  // Random bytes allowed a Huffman code are stored all the same: a code saves nothing on them.
  const Bytes r = random_bytes(n, 4);
  EXPECT_EQ(deflate_all(r, 1, PlaneCoding::huffman).size(), n + 6 + 5);
  // Runs of two values, of random lengths from 1 to 40: the runs block is the greedy parse of
  // zlib's run-length strategy with an optimal code (within 1 %).
  Bytes runs;
  while (runs.size() < n) runs.insert(runs.end(), 1 + g() % 40, g() % 2 ? 0x3f : 0x40);
  runs.resize(n);
  const Bytes runs_coded = deflate_all(runs, 1, PlaneCoding::runs);
  EXPECT_LT(double(runs_coded.size()), 1.01 * double(zlib_size(runs, Z_RLE)));
  // One value repeated: a literal and 63 matches of 258 bytes and one shorter, a few dozen bytes
  // with the header; as a block of literals alone it is at least a bit a byte.
  const Bytes constant(n, 0x40);
  EXPECT_LT(deflate_all(constant, 1, PlaneCoding::runs).size(), 100u);
  EXPECT_GE(deflate_all(constant, 1, PlaneCoding::huffman).size(), n / 8);
}

}  // namespace
