// The compressed chunks of a sweep table (io/compressed_chunks.hpp): HDF5 reads back, bit for bit,
// what lsi compressed itself, for columns of numbers whose byte planes are part random, part of
// few values, part runs (stored, Huffman-coded and run-length coded blocks in one deflate stream,
// io/deflate_planes.hpp), and a compressor reused from call to call gives the bytes of a new one.
#include "io/compressed_chunks.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/hdf5_io.hpp"

namespace {

namespace fs = std::filesystem;
using lsi::hdf5::ChunkCompression;
using lsi::hdf5::ChunkRows;

// Doubles in [1, 2): the sign and exponent bytes the same for all (runs), the mantissa's low six
// bytes random, its top byte half random.
std::vector<double> random_in_one_two(std::size_t n, unsigned seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(1.0, 2.0);
  std::vector<double> v(n);
  for (auto& x : v) x = u(g);
  return v;
}

class CompressedChunks : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lsi_compressed_chunks_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Writes `values` (rows x columns, row-major) as a compressed dataset of `type` in a new file,
// reads it back through HDF5's filters; returns the values read and the bytes stored.
template <class T>
std::vector<T> write_and_read(const std::string& path, hid_t type, const std::vector<T>& values,
                              std::size_t rows, std::size_t columns, hsize_t chunk_rows,
                              hsize_t* stored_bytes) {
  using lsi::hdf5::Handle;
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
              "cannot create " + path);
  const int rank = columns > 1 ? 2 : 1;
  const hsize_t dims[2] = {rows, columns};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "cannot create a dataspace");
  Handle dcpl = lsi::hdf5::compressed_table_properties(rank, dims, sizeof(T), chunk_rows);
  Handle d(H5Dcreate2(file, "values", type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose,
           "cannot create the dataset");
  std::vector<std::vector<T>> column(columns, std::vector<T>(rows));
  std::vector<const void*> data;
  for (std::size_t k = 0; k < columns; ++k) {
    for (std::size_t i = 0; i < rows; ++i) column[k][i] = values[i * columns + k];
    data.push_back(column[k].data());
  }
  EXPECT_TRUE(lsi::hdf5::write_compressed_chunks(d, dcpl, data, rows, sizeof(T)));
  H5Fflush(file, H5F_SCOPE_GLOBAL);
  *stored_bytes = H5Dget_storage_size(d);
  std::vector<T> back(values.size());
  EXPECT_GE(H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, back.data()), 0);
  return back;
}

TEST_F(CompressedChunks, PartRandomDoublesReadBackBitForBitAndStoreTheirRandomBytes) {
  // 10 000 rows in chunks of 4096: two whole chunks and a last, padded one.
  const std::size_t rows = 10000;
  for (const std::size_t columns : {std::size_t{1}, std::size_t{5}}) {
    const std::vector<double> v = random_in_one_two(rows * columns, 7 + unsigned(columns));
    hsize_t stored = 0;
    const auto back = write_and_read((dir_ / "doubles.h5").string(), H5T_NATIVE_DOUBLE, v, rows,
                                     columns, 4096, &stored);
    ASSERT_EQ(back.size(), v.size());
    EXPECT_EQ(std::memcmp(back.data(), v.data(), v.size() * sizeof(double)), 0)
        << columns << " columns: not the same values once inflated";
    // Six random bytes of eight are stored as they are, the sign and exponent byte shrinks to
    // almost nothing and the half-random byte to about half: about 0.81 of the raw size, under
    // 0.84 with the chunks' padding (12 288 rows stored for 10 000), stored blocks' headers and
    // Huffman tables. A random byte left to Huffman coding would not shrink below 7.8 bits.
    const double raw = double(rows * columns * sizeof(double));
    EXPECT_LT(double(stored), 0.84 * raw * 12288.0 / 10000.0) << columns << " columns";
    EXPECT_GT(double(stored), 0.75 * raw) << columns << " columns";
  }
}

TEST_F(CompressedChunks, EachColumnOfATableIsChunkedAndCompressedOnItsOwn) {
  // A random column in [1, 2) beside a discrete one (4 to 8: six zero bytes, two of few values).
  // A chunk holds one column, so the discrete column's planes are runs and a few Huffman-coded
  // values, and its chunks shrink to almost nothing. Chunks across both columns would shuffle
  // into planes half random and half zeros (about 5 bits a byte, order-0 entropy): the table
  // would take at least 0.54 of its raw size, against about 0.42 here.
  const std::size_t rows = 3 * 4096;
  const std::vector<double> random = random_in_one_two(rows, 3);
  std::vector<double> v(2 * rows);
  for (std::size_t i = 0; i < rows; ++i) {
    v[2 * i] = random[i];
    v[2 * i + 1] = double(4 + i * 7919 % 5);
  }
  hsize_t stored = 0;
  const auto back =
      write_and_read((dir_ / "mixed.h5").string(), H5T_NATIVE_DOUBLE, v, rows, 2, 4096, &stored);
  ASSERT_EQ(back.size(), v.size());
  EXPECT_EQ(std::memcmp(back.data(), v.data(), v.size() * sizeof(double)), 0)
      << "not the same values once inflated";
  // The random column about 0.81 of its size (as above), the discrete one about 0.04: 0.42 of
  // the table's, under 0.45 with the blocks' headers and code tables.
  EXPECT_LT(double(stored), 0.45 * double(v.size() * sizeof(double)));
  using lsi::hdf5::Handle;
  Handle file(H5Fopen((dir_ / "mixed.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose,
              "cannot open mixed.h5");
  Handle d(H5Dopen2(file, "values", H5P_DEFAULT), H5Dclose, "cannot open the dataset");
  Handle dcpl(H5Dget_create_plist(d), H5Pclose, "cannot get the creation properties");
  hsize_t chunk[2] = {0, 0};
  ASSERT_EQ(H5Pget_chunk(dcpl, 2, chunk), 2);
  EXPECT_EQ(chunk[0], 4096u);
  EXPECT_EQ(chunk[1], 1u);
}

TEST_F(CompressedChunks, DoublesOfSeveralExponentsMixStoredHuffmanAndRunLengthPlanes) {
  // Doubles uniform in [1, 16): the six low mantissa bytes random (stored), the byte of the
  // exponent's low bits and the mantissa's top four about 5.6 bits (Huffman codes alone), the
  // sign and exponent byte 0x40 but for the values below 2 (run-length coded). Three whole
  // chunks, so that no padding is stored.
  const std::size_t rows = 3 * 4096;
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(1.0, 16.0);
  std::vector<double> v(rows);
  for (auto& x : v) x = u(g);
  hsize_t stored = 0;
  const auto back = write_and_read((dir_ / "exponents.h5").string(), H5T_NATIVE_DOUBLE, v, rows, 1,
                                   4096, &stored);
  ASSERT_EQ(back.size(), v.size());
  EXPECT_EQ(std::memcmp(back.data(), v.data(), v.size() * sizeof(double)), 0)
      << "not the same values once inflated";
  // Six stored planes are 0.75 of the raw size, the Huffman-coded one about 5.7 / 64 = 0.089,
  // the run-length coded one about 0.01: 0.85, with the blocks' headers and code tables a little
  // more. The middle plane stored instead would make 0.885.
  const double raw = double(rows * sizeof(double));
  EXPECT_LT(double(stored), 0.87 * raw);
  EXPECT_GT(double(stored), 0.75 * raw);
}

TEST_F(CompressedChunks, IntegersAndConstantsReadBackBitForBitAndShrink) {
  const std::size_t rows = 10000;
  std::vector<std::uint64_t> index(rows);
  for (std::size_t i = 0; i < rows; ++i) index[i] = 1000000 + i;
  hsize_t stored = 0;
  const auto back = write_and_read((dir_ / "index.h5").string(), H5T_NATIVE_UINT64, index, rows, 1,
                                   4096, &stored);
  EXPECT_EQ(back, index);
  // Consecutive integers: each chunk's low byte repeats every 256 rows and the others come in
  // runs; a tenth of the raw size is far more than deflate needs.
  EXPECT_LT(double(stored), 0.1 * double(rows * sizeof(std::uint64_t)));
  const std::vector<double> constant(rows, 2.5);
  const auto back_constant = write_and_read((dir_ / "constant.h5").string(), H5T_NATIVE_DOUBLE,
                                            constant, rows, 1, 4096, &stored);
  EXPECT_EQ(back_constant, constant);
  EXPECT_LT(double(stored), 0.01 * double(rows * sizeof(double)));
}

TEST(ChunkCompression, ReusedGivesTheBytesOfANewOne) {
  // Chunks of both kinds, floating ones with stored and run-length coded planes, so that every
  // zlib stream ends a call in some state; a second call on the same object must not depend on it.
  const std::size_t count = 4096;
  const std::vector<double> a = random_in_one_two(count, 1), b(count, 3.0);
  std::vector<std::uint64_t> index(count);
  for (std::size_t i = 0; i < count; ++i) index[i] = i;
  const std::size_t bytes = count * 8;
  const std::vector<ChunkRows> chunks = {{a.data(), bytes, bytes, 8, true},
                                         {index.data(), bytes, bytes, 8, false},
                                         {b.data(), bytes / 2, bytes, 8, true},
                                         {a.data(), bytes, bytes, 8, true}};
  ChunkCompression reused(1);
  const auto first = reused.compress(chunks);
  std::vector<ChunkRows> reversed(chunks.rbegin(), chunks.rend());
  (void)reused.compress(reversed);
  const auto again = reused.compress(chunks);
  ChunkCompression fresh(1);
  const auto& expected = fresh.compress(chunks);
  ASSERT_EQ(first.size(), chunks.size());
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    EXPECT_EQ(first[c], expected[c]) << "chunk " << c;
    EXPECT_EQ(again[c], expected[c]) << "chunk " << c;
  }
  EXPECT_EQ(expected[0], expected[3]);  // the same rows, the same bytes
}

// 40 chunks of 4096 values in [1, 2), column k drawn with seed `seed` + k.
struct ManyChunks {
  std::vector<std::vector<double>> columns;
  std::vector<ChunkRows> chunks;  // into `columns`
};
ManyChunks forty_chunks(unsigned seed) {
  const std::size_t count = 4096, bytes = count * 8;
  ManyChunks m;
  for (unsigned k = 0; k < 40; ++k) m.columns.push_back(random_in_one_two(count, seed + k));
  for (const auto& c : m.columns) m.chunks.push_back({c.data(), bytes, bytes, 8, true});
  return m;
}

TEST(ChunkCompression, EachChunkHandedOverInOrderAndAFailureStopsTheCall) {
  // 40 chunks on the threads (OMP_NUM_THREADS or the hardware's): handed over in order, with the
  // bytes compress() gives.
  const ManyChunks many = forty_chunks(100);
  const std::vector<ChunkRows>& chunks = many.chunks;
  ChunkCompression compression(1);
  const auto expected = compression.compress(chunks);
  std::vector<std::size_t> order;
  compression.compress_each(chunks, [&](std::size_t c, const unsigned char* b, std::size_t size) {
    order.push_back(c);
    EXPECT_EQ(std::vector<unsigned char>(b, b + size), expected[c]) << "chunk " << c;
  });
  ASSERT_EQ(order.size(), chunks.size());
  for (std::size_t c = 0; c < order.size(); ++c) EXPECT_EQ(order[c], c);
  // A writer that fails at chunk 5: the call ends with its exception, after chunks 0-5 only,
  // and the object compresses again afterwards.
  std::size_t handed = 0;
  EXPECT_THROW(compression.compress_each(chunks,
                                         [&](std::size_t c, const unsigned char*, std::size_t) {
                                           ++handed;
                                           if (c == 5) throw std::runtime_error("disk full");
                                         }),
               std::runtime_error);
  EXPECT_EQ(handed, 6u);
  EXPECT_EQ(compression.compress(chunks)[39], expected[39]);
}

TEST(ChunkCompression, AFailedCompressionEndsTheCallWithItsError) {
  // Chunk 20 cannot be compressed (a chunk larger than any buffer can be: its buffer's resize
  // throws std::length_error). The call ends with that error, having handed over at most the
  // chunks before it, in order, whatever the threads were doing (some waiting for a slot of the
  // ring); repeated, since where a thread stands when the error comes is a matter of timing.
  const ManyChunks many = forty_chunks(200);
  const std::vector<ChunkRows>& chunks = many.chunks;
  std::vector<ChunkRows> failing = chunks;
  failing[20].chunk_bytes = std::numeric_limits<std::size_t>::max() - 7;
  ChunkCompression compression(1);
  const auto expected = compression.compress(chunks);
  for (int round = 0; round < 50; ++round) {
    std::vector<std::size_t> order;
    EXPECT_THROW(compression.compress_each(failing, [&](std::size_t c, const unsigned char*,
                                                        std::size_t) { order.push_back(c); }),
                 std::length_error);
    ASSERT_LE(order.size(), 20u);
    for (std::size_t c = 0; c < order.size(); ++c) ASSERT_EQ(order[c], c);
  }
  EXPECT_EQ(compression.compress(chunks)[39], expected[39]);
}

}  // namespace
