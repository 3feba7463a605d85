// Deflate blocks of byte planes; see deflate_planes.hpp. Section numbers are RFC 1951's.
#include "io/deflate_planes.hpp"

#include "io/adler32.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <type_traits>

namespace lsi::hdf5 {
namespace {

constexpr int kLiteralLengthSymbols = 286;  // 0-255 literals, 256 end of block, 257-285 lengths
constexpr int kEndOfBlock = 256;
constexpr int kMaxCodeLength = 15;         // literal/length and distance codes (3.2.7)
constexpr int kMaxCodeLengthLength = 7;    // the code of the code lengths
constexpr std::size_t kMaxStored = 65535;  // bytes of a stored block (3.2.4)
constexpr int kMaxMatch = 258;             // the longest match (3.2.5); the shortest is 3 bytes

// Bits written least significant first (3.1.1). Each put() stores eight bytes and advances by the
// whole bytes written, so the output needs eight bytes of room past the stream's end; a put()
// of at most 57 bits, or several whose sum is, goes between two flushes.
class BitWriter {
 public:
  explicit BitWriter(unsigned char* out) : out_(out) {}
  void add(std::uint64_t bits, int n) {
    buffer_ |= bits << count_;
    count_ += n;
  }
  void flush() {
    std::uint64_t bytes = buffer_;  // least significant byte first
    if constexpr (std::endian::native == std::endian::big) bytes = __builtin_bswap64(bytes);
    std::memcpy(out_, &bytes, 8);
    out_ += count_ >> 3;
    buffer_ = count_ >= 64 ? 0 : buffer_ >> (count_ & ~7);
    count_ &= 7;
  }
  void put(std::uint64_t bits, int n) {
    add(bits, n);
    flush();
  }
  // To the next byte boundary (the stored blocks' data and the stream's end).
  void align() {
    if (count_ > 0) {
      out_[0] = static_cast<unsigned char>(buffer_);
      ++out_;
    }
    buffer_ = 0;
    count_ = 0;
  }
  void raw(const unsigned char* bytes, std::size_t n) {
    if (n != 0) std::memcpy(out_, bytes, n);
    out_ += n;
  }
  unsigned char* end() const { return out_; }

 private:
  unsigned char* out_;
  std::uint64_t buffer_ = 0;
  int count_ = 0;
};

// Each byte with its bits in reverse order.
constexpr std::array<std::uint8_t, 256> make_reversed_bytes() {
  std::array<std::uint8_t, 256> t{};
  for (int b = 0; b < 256; ++b) {
    int r = 0;
    for (int k = 0; k < 8; ++k) r |= ((b >> k) & 1) << (7 - k);
    t[b] = std::uint8_t(r);
  }
  return t;
}
constexpr std::array<std::uint8_t, 256> kReversedByte = make_reversed_bytes();

// A Huffman code: each symbol's length (0: no code) and its code, bit-reversed as the stream
// sends it (3.1.1: Huffman codes go most significant bit first).
template <int N>
struct Code {
  std::array<std::uint8_t, N> length{};
  std::array<std::uint16_t, N> bits{};
};

// The lengths of a minimum-redundancy code for freq[0..n) limited to `limit` bits (0 for the
// unused symbols). At least two symbols get a code, as zlib gives them: some inflaters reject a
// code of one symbol.
template <int N>
void code_lengths(const std::uint32_t* freq, const int n, const int limit, Code<N>& code) {
  std::array<std::uint64_t, N> key;  // frequency above, symbol below (the first `used`)
  int used = 0;
  for (int s = 0; s < n; ++s)
    if (freq[s] != 0) key[used++] = std::uint64_t(freq[s]) << 16 | std::uint64_t(s);
  for (int s = 0; s < n && used < 2; ++s)
    if (freq[s] == 0) key[used++] = std::uint64_t(s);
  std::sort(key.begin(), key.begin() + used);
  // Moffat and Katajainen's in-place computation of the depths from the ascending weights.
  std::array<std::uint64_t, N> a;
  for (int i = 0; i < used; ++i) a[i] = key[i] >> 16;
  a[0] += a[1];
  int root = 0, leaf = 2;
  for (int next = 1; next < used - 1; ++next) {
    if (leaf >= used || a[root] < a[leaf]) {
      a[next] = a[root];
      a[root++] = std::uint64_t(next);
    } else {
      a[next] = a[leaf++];
    }
    if (leaf >= used || (root < next && a[root] < a[leaf])) {
      a[next] += a[root];
      a[root++] = std::uint64_t(next);
    } else {
      a[next] += a[leaf++];
    }
  }
  a[used - 2] = 0;
  for (int next = used - 3; next >= 0; --next) a[next] = a[a[next]] + 1;
  int available = 1, taken = 0, depth = 0, next = used - 1;
  root = used - 2;
  while (available > 0) {
    while (root >= 0 && a[root] == std::uint64_t(depth)) {
      ++taken;
      --root;
    }
    while (available > taken) {
      a[next--] = std::uint64_t(depth);
      --available;
    }
    available = 2 * taken;
    ++depth;
    taken = 0;
  }
  // The number of codes of each length, the longest brought within the limit (the adjustment of
  // the JPEG standard, Annex K.3: a pair of the longest codes moves up a level and a shorter
  // code down one, keeping the code complete).
  std::array<int, N + 1> count{};
  int longest = 0;
  for (int i = 0; i < used; ++i) {
    ++count[a[i]];
    longest = std::max(longest, int(a[i]));
  }
  for (int i = longest; i > limit; --i)
    while (count[i] > 0) {
      int j = i - 2;
      while (count[j] == 0) --j;
      count[i] -= 2;
      count[i - 1] += 1;
      count[j + 1] += 2;
      count[j] -= 1;
    }
  // The longest codes to the rarest symbols.
  code.length.fill(0);
  int i = 0;
  for (int len = std::min(longest, limit); len >= 1; --len)
    for (int c = 0; c < count[len]; ++c) code.length[key[i++] & 0xffff] = std::uint8_t(len);
  // The canonical codes (3.2.2), reversed.
  int per_length[kMaxCodeLength + 1] = {};
  for (int s = 0; s < N; ++s) ++per_length[code.length[s]];
  per_length[0] = 0;
  int next_code[kMaxCodeLength + 1] = {};
  for (int len = 1, c = 0; len <= kMaxCodeLength; ++len) {
    c = (c + per_length[len - 1]) << 1;
    next_code[len] = c;
  }
  for (int s = 0; s < N; ++s) {
    const int len = code.length[s];
    if (len == 0) continue;
    const unsigned c = unsigned(next_code[len]++);
    code.bits[s] =
        std::uint16_t((kReversedByte[c & 0xff] << 8 | kReversedByte[c >> 8]) >> (16 - len));
  }
}

// The match lengths' symbols and extra bits (3.2.5), for lengths 3 to 258.
struct LengthSymbol {
  std::uint16_t symbol;
  std::uint8_t extra_bits;
  std::uint8_t extra;
};
constexpr std::array<LengthSymbol, kMaxMatch + 1> make_length_symbols() {
  std::array<LengthSymbol, kMaxMatch + 1> t{};
  int base = 3;
  for (int symbol = 257; symbol < 285; ++symbol) {
    const int extra_bits = symbol < 265 ? 0 : (symbol - 261) / 4;
    for (int e = 0; e < (1 << extra_bits) && base + e < kMaxMatch; ++e)
      t[base + e] = {std::uint16_t(symbol), std::uint8_t(extra_bits), std::uint8_t(e)};
    base += 1 << extra_bits;
  }
  t[kMaxMatch] = {285, 0, 0};
  return t;
}
constexpr std::array<LengthSymbol, kMaxMatch + 1> kLengthSymbols = make_length_symbols();

// The distance code of the runs and Huffman blocks: distance codes 0 and 1 of one bit each
// (distance 1 is code 0, without extra bits). A block of literals alone sends it unused.
constexpr int kDistanceCodes = 2;

// A dynamic block's header (3.2.7): the code lengths of both codes, run-length coded with the
// symbols 16-18 and sent with a code of their own.
class DynamicHeader {
 public:
  DynamicHeader() = default;
  explicit DynamicHeader(const Code<kLiteralLengthSymbols>& literal) {
    literal_count_ = kLiteralLengthSymbols;
    while (literal_count_ > 257 && literal.length[literal_count_ - 1] == 0) --literal_count_;
    std::array<std::uint8_t, kLiteralLengthSymbols + kDistanceCodes> lengths{};
    const int n = literal_count_ + kDistanceCodes;
    for (int s = 0; s < literal_count_; ++s) lengths[s] = literal.length[s];
    for (int d = 0; d < kDistanceCodes; ++d) lengths[literal_count_ + d] = 1;
    std::uint32_t freq[19] = {};
    auto emit = [&](int symbol, int extra) {
      items_[items_count_++] = {std::uint8_t(symbol), std::uint8_t(extra)};
      ++freq[symbol];
    };
    for (int i = 0; i < n;) {
      const int v = lengths[i];
      int run = 1;
      while (i + run < n && lengths[i + run] == v) ++run;
      i += run;
      if (v == 0) {
        for (; run >= 11; run -= std::min(run, 138)) emit(18, std::min(run, 138) - 11);
        if (run >= 3) {
          emit(17, run - 3);
          run = 0;
        }
        for (; run > 0; --run) emit(0, 0);
      } else {
        emit(v, 0);
        --run;
        for (; run >= 3; run -= std::min(run, 6)) emit(16, std::min(run, 6) - 3);
        for (; run > 0; --run) emit(v, 0);
      }
    }
    code_lengths<19>(freq, 19, kMaxCodeLengthLength, lengths_code_);
    length_count_ = 19;
    while (length_count_ > 4 && lengths_code_.length[kOrder[length_count_ - 1]] == 0)
      --length_count_;
    bits_ = 3 + 5 + 5 + 4 + 3 * length_count_;
    for (int k = 0; k < items_count_; ++k)
      bits_ += lengths_code_.length[items_[k].symbol] + extra_bits(items_[k].symbol);
  }
  // The header's bits, the block's first three included.
  std::uint64_t bits() const { return bits_; }
  void write(BitWriter& w, const bool last) const {
    w.put((last ? 1u : 0u) | (2u << 1), 3);
    w.put(unsigned(literal_count_ - 257) | unsigned(kDistanceCodes - 1) << 5 |
              unsigned(length_count_ - 4) << 10,
          14);
    for (int k = 0; k < length_count_; ++k) w.put(lengths_code_.length[kOrder[k]], 3);
    for (int k = 0; k < items_count_; ++k) {
      const Item& it = items_[k];
      w.add(lengths_code_.bits[it.symbol], lengths_code_.length[it.symbol]);
      w.put(it.extra, extra_bits(it.symbol));
    }
  }

 private:
  static constexpr int kOrder[19] = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                     11, 4,  12, 3, 13, 2, 14, 1, 15};
  static int extra_bits(int symbol) {
    return symbol == 16 ? 2 : symbol == 17 ? 3 : symbol == 18 ? 7 : 0;
  }
  struct Item {
    std::uint8_t symbol, extra;
  };
  std::array<Item, kLiteralLengthSymbols + kDistanceCodes> items_{};
  int items_count_ = 0, literal_count_ = 0, length_count_ = 0;
  Code<19> lengths_code_;
  std::uint64_t bits_ = 0;
};

// The bits of `n` bytes in stored blocks, at most: each block's 3 header bits and 4 length bytes,
// the first block up to 7 bits of padding more (the blocks after it start on a byte boundary).
std::uint64_t stored_bits(std::size_t n) {
  const std::size_t blocks = std::max<std::size_t>(1, (n + kMaxStored - 1) / kMaxStored);
  return 8 * (std::uint64_t(n) + 5 * blocks) + 7;
}

void write_stored(BitWriter& w, const unsigned char* bytes, std::size_t n, const bool last) {
  do {
    const std::size_t k = std::min(n, kMaxStored);
    const bool final_block = last && k == n;
    w.put(final_block ? 1u : 0u, 3);
    w.align();
    const unsigned char header[4] = {std::uint8_t(k), std::uint8_t(k >> 8), std::uint8_t(~k),
                                     std::uint8_t(~k >> 8)};
    w.raw(header, 4);
    w.raw(bytes, k);
    bytes += k;
    n -= k;
  } while (n > 0);
}

// The byte histogram of a plane (four tallies, so that equal bytes in a row do not wait on each
// other's increments).
void histogram(const unsigned char* p, const std::size_t n, std::uint32_t freq[256]) {
  std::uint32_t t[4][256] = {};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    ++t[0][p[i]];
    ++t[1][p[i + 1]];
    ++t[2][p[i + 2]];
    ++t[3][p[i + 3]];
  }
  for (; i < n; ++i) ++t[0][p[i]];
  for (int b = 0; b < 256; ++b) freq[b] = t[0][b] + t[1][b] + t[2][b] + t[3][b];
}

// A block of literals alone: its code, from the plane's histogram, and its size.
struct LiteralBlock {
  Code<kLiteralLengthSymbols> code;
  DynamicHeader header;
  std::uint64_t bits = 0;
};
void plan_literals(const std::uint32_t byte_freq[256], LiteralBlock& b) {
  std::uint32_t freq[kLiteralLengthSymbols] = {};
  std::copy(byte_freq, byte_freq + 256, freq);
  freq[kEndOfBlock] = 1;
  code_lengths<kLiteralLengthSymbols>(freq, kLiteralLengthSymbols, kMaxCodeLength, b.code);
  std::uint64_t bits = b.code.length[kEndOfBlock];
  for (int s = 0; s < 256; ++s) bits += std::uint64_t(byte_freq[s]) * b.code.length[s];
  b.header = DynamicHeader(b.code);
  b.bits = bits + b.header.bits();
}

// The code's table for the literals: each byte's code bits below, its length from bit 16.
void literal_table(const Code<kLiteralLengthSymbols>& code, std::uint32_t table[256]) {
  for (int s = 0; s < 256; ++s) table[s] = code.bits[s] | std::uint32_t(code.length[s]) << 16;
}

// The literals p[0, n) by `table`, K codes between two flushes (K codes of the longest length
// within the 57 bits put() allows).
template <int K>
void put_literals(BitWriter& w, const unsigned char* p, const std::size_t n,
                  const std::uint32_t table[256]) {
  std::size_t i = 0;
  for (; i + K <= n; i += K) {
    for (int k = 0; k < K; ++k) {
      const std::uint32_t e = table[p[i + k]];
      w.add(e & 0xffff, int(e >> 16));
    }
    w.flush();
  }
  for (; i < n; ++i) w.add(table[p[i]] & 0xffff, int(table[p[i]] >> 16));
  w.flush();
}

// f(std::integral_constant<int, K>()) with K the most codes of `longest` bits between two
// flushes (at most 8): the fewer flushes, the shorter the chain of shifts each byte waits on.
template <class F>
void with_codes_per_flush(const int longest, F&& f) {
  switch (std::min(8, 57 / std::max(longest, 1))) {
    case 8:
      return f(std::integral_constant<int, 8>());
    case 7:
      return f(std::integral_constant<int, 7>());
    case 6:
      return f(std::integral_constant<int, 6>());
    case 5:
      return f(std::integral_constant<int, 5>());
    case 4:
      return f(std::integral_constant<int, 4>());
    default:
      return f(std::integral_constant<int, 3>());
  }
}

// The longest code among the literals.
int longest_literal(const Code<kLiteralLengthSymbols>& code) {
  return *std::max_element(code.length.begin(), code.length.begin() + 256);
}

// How many of the first `most` bytes at p equal v: eight bytes at a time (the first byte that
// differs is the lowest nonzero byte of their difference, on a little-endian host).
std::size_t run_length(const unsigned char* p, const std::size_t most, const unsigned char v) {
  std::size_t r = 0;
  if constexpr (std::endian::native == std::endian::little) {
    const std::uint64_t pattern = 0x0101010101010101ull * v;
    for (; r + 8 <= most; r += 8) {
      std::uint64_t w;
      std::memcpy(&w, p + r, 8);
      if (const std::uint64_t d = w ^ pattern; d != 0)
        return r + static_cast<std::size_t>(std::countr_zero(d) >> 3);
    }
  }
  while (r < most && p[r] == v) ++r;
  return r;
}

// Where the next match may start at or after i (1 <= i): the first j >= i with p[j - 1] = p[j] =
// p[j + 1] = p[j + 2] and j + 2 < n, or n where there is none. Eight positions at a time: the
// bytes of the three words of neighbours' differences that are zero in all three (the exact
// zero-byte test: the high bit of ~((x & 0x7f..) + 0x7f.. | x | 0x7f..)).
std::size_t next_match(const unsigned char* p, std::size_t i, const std::size_t n) {
  if constexpr (std::endian::native == std::endian::little) {
    constexpr std::uint64_t low7 = 0x7f7f7f7f7f7f7f7full;
    auto word = [p](std::size_t k) {
      std::uint64_t v;
      std::memcpy(&v, p + k, 8);
      return v;
    };
    for (; i + 10 <= n; i += 8) {  // the words read p[i - 1, i + 10)
      const std::uint64_t a = word(i - 1), b = word(i), c = word(i + 1), d = word(i + 2);
      const std::uint64_t x = (a ^ b) | (b ^ c) | (c ^ d);
      const std::uint64_t zero = ~(((x & low7) + low7) | x | low7);
      if (zero != 0) return i + static_cast<std::size_t>(std::countr_zero(zero) >> 3);
    }
  }
  for (; i + 2 < n; ++i)
    if (p[i - 1] == p[i] && p[i] == p[i + 1] && p[i + 1] == p[i + 2]) return i;
  return n;
}

using Match = PlaneDeflater::Match;

// A runs block: the plane as literals and matches at distance one (the greedy parse of zlib's
// run-length strategy: a repeat of the previous byte three times or more is a match, at most
// 258 bytes long); its matches, code, size and number of symbols. The literals' counts are the
// plane's byte counts less the bytes the matches cover.
struct RunsBlock {
  Code<kLiteralLengthSymbols> code;
  DynamicHeader header;
  std::uint64_t bits = 0;
  std::size_t symbols = 0;
};
void plan_runs(const unsigned char* p, const std::size_t n, const std::uint32_t byte_freq[256],
               std::vector<Match>& matches, RunsBlock& b) {
  matches.clear();
  std::uint32_t freq[kLiteralLengthSymbols] = {};
  std::copy(byte_freq, byte_freq + 256, freq);
  std::uint64_t extra = 0, covered = 0;
  for (std::size_t i = n == 0 ? 0 : next_match(p, 1, n); i < n; i = next_match(p, i, n)) {
    const unsigned char v = p[i - 1];
    const std::size_t r = run_length(p + i, std::min<std::size_t>(kMaxMatch, n - i), v);
    matches.push_back({std::uint32_t(i), std::uint16_t(r)});
    const LengthSymbol& ls = kLengthSymbols[r];
    ++freq[ls.symbol];
    freq[v] -= std::uint32_t(r);
    extra += ls.extra_bits + 1;  // the distance code's bit
    covered += r;
    i += r;
  }
  freq[kEndOfBlock] = 1;
  b.symbols = n - covered + matches.size();
  code_lengths<kLiteralLengthSymbols>(freq, kLiteralLengthSymbols, kMaxCodeLength, b.code);
  std::uint64_t bits = extra;
  for (int s = 0; s < kLiteralLengthSymbols; ++s) bits += std::uint64_t(freq[s]) * b.code.length[s];
  b.header = DynamicHeader(b.code);
  b.bits = bits + b.header.bits();
}

// A dynamic block of the plane p[0, n) as literals and the given matches (none for a block of
// literals alone), with its code and header.
void write_dynamic(BitWriter& w, const unsigned char* p, const std::size_t n, const Match* matches,
                   const std::size_t match_count, const Code<kLiteralLengthSymbols>& code,
                   const DynamicHeader& header, const bool last) {
  header.write(w, last);
  std::uint32_t table[256];
  literal_table(code, table);
  with_codes_per_flush(longest_literal(code), [&](auto k) {
    BitWriter v = w;  // a local copy, whose state the compiler keeps in registers
    std::size_t i = 0;
    for (std::size_t j = 0; j < match_count; ++j) {
      const Match& m = matches[j];
      put_literals<k()>(v, p + i, m.at - i, table);
      const LengthSymbol& ls = kLengthSymbols[m.length];
      v.add(code.bits[ls.symbol], code.length[ls.symbol]);
      v.add(ls.extra, ls.extra_bits);
      v.put(0, 1);  // distance code 0: distance 1
      i = m.at + m.length;
    }
    put_literals<k()>(v, p + i, n - i, table);
    w = v;
  });
  w.put(code.bits[kEndOfBlock], code.length[kEndOfBlock]);
}

}  // namespace

std::size_t PlaneDeflater::bound(const std::size_t plane_bytes, const std::size_t planes) {
  return 2 + planes * ((stored_bits(plane_bytes) + 7) / 8 + 1) + 4 + 8;
}

std::size_t PlaneDeflater::deflate(const unsigned char* bytes, const std::size_t plane_bytes,
                                   const std::size_t planes, const PlaneCoding* coding,
                                   unsigned char* out) {
  // zlib's header: deflate with a 32 KiB window, no dictionary, "fastest" level (the level is
  // informative only); 0x7801 is a multiple of 31 (RFC 1950, 2.2).
  out[0] = 0x78;
  out[1] = 0x01;
  BitWriter w(out + 2);
  if (planes == 0) write_stored(w, bytes, 0, true);
  for (std::size_t j = 0; j < planes;) {
    const unsigned char* p = bytes + j * plane_bytes;
    if (coding[j] == PlaneCoding::stored) {  // with the stored planes that follow it
      std::size_t end = j + 1;
      while (end < planes && coding[end] == PlaneCoding::stored) ++end;
      write_stored(w, p, (end - j) * plane_bytes, end == planes);
      j = end;
      continue;
    }
    const bool last = j + 1 == planes;
    const std::uint64_t stored = stored_bits(plane_bytes);
    // A runs plane whose matches leave fewer symbols than half its bytes is taken as a runs block
    // without planning a block of literals too (a second code for a plane that is mostly runs;
    // the choice decides the file's size, never its values).
    std::uint32_t freq[256];
    histogram(p, plane_bytes, freq);
    RunsBlock runs;
    // (A match's position is 32 bits: a plane of 4 GiB or more is coded without matches.)
    const bool try_runs = coding[j] == PlaneCoding::runs && plane_bytes <= UINT32_MAX;
    if (try_runs) plan_runs(p, plane_bytes, freq, matches_, runs);
    LiteralBlock literals;
    const bool try_literals = !try_runs || 2 * runs.symbols > plane_bytes;
    if (try_literals) plan_literals(freq, literals);
    if (try_runs && (!try_literals || runs.bits <= literals.bits) && runs.bits < stored)
      write_dynamic(w, p, plane_bytes, matches_.data(), matches_.size(), runs.code, runs.header,
                    last);
    else if (try_literals && literals.bits < stored)
      write_dynamic(w, p, plane_bytes, nullptr, 0, literals.code, literals.header, last);
    else
      write_stored(w, p, plane_bytes, last);
    ++j;
  }
  w.align();
  unsigned char* end = w.end();
  const std::uint32_t adler = adler32(1, bytes, plane_bytes * planes);
  for (int k = 0; k < 4; ++k) end[k] = static_cast<unsigned char>(adler >> (24 - 8 * k));
  return static_cast<std::size_t>(end + 4 - out);
}

}  // namespace lsi::hdf5
