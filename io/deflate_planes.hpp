// A zlib stream (RFC 1950) of deflate blocks (RFC 1951) written by lsi itself, one block per byte
// plane of a shuffled chunk of floating-point numbers, each plane in the smallest of the codings
// its kind allows:
//  - stored: the bytes as they are (the low mantissa bytes, which look random);
//  - Huffman: a block of literals alone, with a code made for the plane (planes of few values
//    but no runs);
//  - runs: literals and repeats of the previous byte (matches at distance one), with a code made
//    for the plane (the sign and exponent bytes of a column of numbers, which come in runs).
// These are the blocks zlib writes with its stored, Huffman-only and run-length strategies; zlib
// spends most of a sweep table's writing time in its general block machinery for them (a symbol
// buffer, its tallies and a tree per block of 16 k symbols), which a coder that knows the block's
// content does not need. The stream is standard: any inflater (HDF5's deflate filter, zlib,
// h5py) reads it. The bytes of a plane and its coding decide the stream's bytes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lsi::hdf5 {

// How a byte plane may be coded: stored only; the smaller of a Huffman block and a stored one;
// the smallest of a runs block, a Huffman block and a stored one.
enum class PlaneCoding : char { stored, huffman, runs };

class PlaneDeflater {
 public:
  // The most bytes deflate() writes for `planes` planes of `plane_bytes` bytes (every plane at
  // most stored), room for the bit writer's last word included.
  static std::size_t bound(std::size_t plane_bytes, std::size_t planes);

  // Writes the zlib stream of `planes` consecutive planes of `plane_bytes` bytes at `bytes`, plane
  // j coded as coding[j] allows, into `out` (at least bound() bytes). Returns its size.
  std::size_t deflate(const unsigned char* bytes, std::size_t plane_bytes, std::size_t planes,
                      const PlaneCoding* coding, unsigned char* out);

  // A match of a runs block: `length` (3 to 258) bytes from `at`, each equal to the byte
  // before them.
  struct Match {
    std::uint32_t at;
    std::uint16_t length;
  };

 private:
  std::vector<Match> matches_;  // a runs plane's matches, kept from plane to plane
};

}  // namespace lsi::hdf5
