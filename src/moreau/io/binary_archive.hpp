#pragma once
// Binary archives of the state for checkpoints: every field of every state struct, recursively,
// as the exact bits in memory (doubles round-trip exactly; a restart must continue bit for bit).
//
// Aggregates (plain structs) are walked field by field with Boost.PFR, which enumerates an
// aggregate's members without a hand-written list: a field added to a state struct is saved
// without anyone remembering to add it here. Containers are a count and their elements; Eigen
// fixed-size matrices and quaternions their coefficients. A type with no rule here (a class with
// private members, a pointer) fails to compile, naming the type; a class then lists its members
// in `archive_members()` (a std::tie of them, const and non-const; see CellGrid), or is left out
// of the state.
//
// Reading checks every count against the bytes left, so a truncated or corrupt file is an error
// (ArchiveError), never a huge allocation or a read past the end.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <array>
#include <boost/pfr.hpp>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace moreau {

/// A checkpoint's bytes do not hold what the reader expects (truncated, corrupt, another layout).
class ArchiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ArchiveWriter {
 public:
  void bytes(const void* data, std::size_t n) {
    if (n > 0) buffer_.append(static_cast<const char*>(data), n);  // an empty vector's data() may be null
  }
  const std::string& buffer() const { return buffer_; }

 private:
  std::string buffer_;
};

class ArchiveReader {
 public:
  ArchiveReader(const char* data, std::size_t size) : data_(data), size_(size) {}
  void bytes(void* out, std::size_t n) {
    if (n > remaining()) throw ArchiveError("the checkpoint ends early (truncated?)");
    if (n == 0) return;  // memcpy into an empty vector's null data() is undefined
    std::memcpy(out, data_ + at_, n);
    at_ += n;
  }
  std::size_t remaining() const { return size_ - at_; }
  /// A count of items of at least `min_bytes` each that the rest of the data can hold.
  std::uint64_t count(std::size_t min_bytes) {
    std::uint64_t n = 0;
    bytes(&n, sizeof n);
    if (min_bytes > 0 && n > remaining() / min_bytes) throw ArchiveError("the checkpoint holds a count larger than its data");
    return n;
  }

 private:
  const char* data_;
  std::size_t size_, at_ = 0;
};

namespace archive_detail {
template <class T> struct is_vector : std::false_type {};
template <class T, class A> struct is_vector<std::vector<T, A>> : std::true_type {};
template <class T> struct is_array : std::false_type {};
template <class T, std::size_t N> struct is_array<std::array<T, N>> : std::true_type {};
template <class T> struct is_tuple_like : std::false_type {};
template <class... T> struct is_tuple_like<std::tuple<T...>> : std::true_type {};
template <class... T> struct is_tuple_like<const std::tuple<T...>> : std::true_type {};
template <class A, class B> struct is_tuple_like<std::pair<A, B>> : std::true_type {};
template <class T> struct is_fixed_eigen : std::false_type {};
template <class S, int R, int C, int O, int MR, int MC>
struct is_fixed_eigen<Eigen::Matrix<S, R, C, O, MR, MC>> : std::bool_constant<R != Eigen::Dynamic && C != Eigen::Dynamic> {};
template <class T> struct is_dynamic_eigen : std::false_type {};
template <class S, int R, int C, int O, int MR, int MC>
struct is_dynamic_eigen<Eigen::Matrix<S, R, C, O, MR, MC>> : std::bool_constant<R == Eigen::Dynamic || C == Eigen::Dynamic> {};
template <class T> struct is_sparse : std::false_type {};
template <class S, int O, class I> struct is_sparse<Eigen::SparseMatrix<S, O, I>> : std::true_type {};
template <class T> struct is_quaternion : std::false_type {};
template <class S, int O> struct is_quaternion<Eigen::Quaternion<S, O>> : std::true_type {};
template <class T> inline constexpr bool no_rule = false;

// A class that lists its members for archives: archive_members() returns a std::tie of them.
template <class T>
concept lists_members = requires(T& v) { v.archive_members(); };
}  // namespace archive_detail

/// Smallest number of bytes one T takes in an archive (guards counts read back).
template <class T>
constexpr std::size_t archived_min_bytes() {
  if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) return sizeof(T);
  else if constexpr (archive_detail::is_fixed_eigen<T>::value) return sizeof(typename T::Scalar) * T::SizeAtCompileTime;
  else return 1;
}

/// Writes `value` (see the file comment for the rules).
template <class T>
void archive(ArchiveWriter& w, const T& value) {
  using namespace archive_detail;
  if constexpr (lists_members<const T>) {
    archive(w, value.archive_members());
  } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    w.bytes(&value, sizeof value);
  } else if constexpr (std::is_same_v<T, std::string>) {
    const std::uint64_t n = value.size();
    w.bytes(&n, sizeof n);
    w.bytes(value.data(), n);
  } else if constexpr (is_vector<T>::value) {
    const std::uint64_t n = value.size();
    w.bytes(&n, sizeof n);
    using E = typename T::value_type;
    if constexpr (std::is_same_v<E, bool>) {
      for (bool b : value) archive(w, static_cast<std::uint8_t>(b));
    } else if constexpr (std::is_arithmetic_v<E> || std::is_enum_v<E>) {
      w.bytes(value.data(), n * sizeof(E));
    } else {
      for (const E& e : value) archive(w, e);
    }
  } else if constexpr (is_array<T>::value) {
    for (const auto& e : value) archive(w, e);
  } else if constexpr (is_tuple_like<T>::value) {
    std::apply([&](const auto&... parts) { (archive(w, parts), ...); }, value);
  } else if constexpr (is_fixed_eigen<T>::value) {
    w.bytes(value.data(), sizeof(typename T::Scalar) * T::SizeAtCompileTime);
  } else if constexpr (is_dynamic_eigen<T>::value) {
    const std::uint64_t rows = value.rows(), cols = value.cols();
    w.bytes(&rows, sizeof rows);
    w.bytes(&cols, sizeof cols);
    w.bytes(value.data(), sizeof(typename T::Scalar) * rows * cols);
  } else if constexpr (is_quaternion<T>::value) {
    w.bytes(value.coeffs().data(), 4 * sizeof(typename T::Scalar));
  } else if constexpr (is_sparse<T>::value) {  // compressed: sizes, outer starts, inner indices, values
    T compressed = value;
    compressed.makeCompressed();
    using I = typename T::StorageIndex;
    const std::uint64_t rows = compressed.rows(), cols = compressed.cols();
    w.bytes(&rows, sizeof rows);
    w.bytes(&cols, sizeof cols);
    archive(w, std::vector<I>(compressed.outerIndexPtr(), compressed.outerIndexPtr() + compressed.outerSize() + 1));
    archive(w, std::vector<I>(compressed.innerIndexPtr(), compressed.innerIndexPtr() + compressed.nonZeros()));
    archive(w, std::vector<typename T::Scalar>(compressed.valuePtr(), compressed.valuePtr() + compressed.nonZeros()));
  } else if constexpr (std::is_aggregate_v<T> && std::is_class_v<T>) {
    boost::pfr::for_each_field(value, [&](const auto& field) { archive(w, field); });
  } else {
    static_assert(no_rule<T>, "no archive rule for this type: give it an archive_fields overload");
  }
}

/// Reads into `value` what archive(writer, value) wrote.
template <class T>
void unarchive(ArchiveReader& r, T& value) {
  using namespace archive_detail;
  if constexpr (lists_members<T>) {
    auto members = value.archive_members();
    unarchive(r, members);
  } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
    r.bytes(&value, sizeof value);
  } else if constexpr (std::is_same_v<T, std::string>) {
    value.resize(r.count(1));
    r.bytes(value.data(), value.size());
  } else if constexpr (is_vector<T>::value) {
    using E = typename T::value_type;
    const std::uint64_t n = r.count(std::is_same_v<E, bool> ? 1 : archived_min_bytes<E>());
    value.resize(n);
    if constexpr (std::is_same_v<E, bool>) {
      for (std::uint64_t i = 0; i < n; ++i) {
        std::uint8_t b = 0;
        unarchive(r, b);
        value[i] = b != 0;
      }
    } else if constexpr (std::is_arithmetic_v<E> || std::is_enum_v<E>) {
      r.bytes(value.data(), n * sizeof(E));
    } else {
      for (E& e : value) unarchive(r, e);
    }
  } else if constexpr (is_array<T>::value) {
    for (auto& e : value) unarchive(r, e);
  } else if constexpr (is_tuple_like<T>::value) {
    std::apply([&](auto&... parts) { (unarchive(r, parts), ...); }, value);
  } else if constexpr (is_fixed_eigen<T>::value) {
    r.bytes(value.data(), sizeof(typename T::Scalar) * T::SizeAtCompileTime);
  } else if constexpr (is_dynamic_eigen<T>::value) {
    std::uint64_t rows = 0, cols = 0;
    r.bytes(&rows, sizeof rows);
    r.bytes(&cols, sizeof cols);
    if (rows != 0 && cols > r.remaining() / sizeof(typename T::Scalar) / rows)
      throw ArchiveError("the checkpoint holds a matrix larger than its data");
    value.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    r.bytes(value.data(), sizeof(typename T::Scalar) * rows * cols);
  } else if constexpr (is_quaternion<T>::value) {
    r.bytes(value.coeffs().data(), 4 * sizeof(typename T::Scalar));
  } else if constexpr (is_sparse<T>::value) {
    using I = typename T::StorageIndex;
    std::uint64_t rows = 0, cols = 0;
    r.bytes(&rows, sizeof rows);
    r.bytes(&cols, sizeof cols);
    std::vector<I> outer, inner;
    std::vector<typename T::Scalar> values;
    unarchive(r, outer);
    unarchive(r, inner);
    unarchive(r, values);
    const std::uint64_t outer_size = (T::IsRowMajor ? rows : cols);
    if (outer.size() != outer_size + 1 || inner.size() != values.size() || outer.front() != 0 ||
        static_cast<std::uint64_t>(outer.back()) != values.size())
      throw ArchiveError("the checkpoint holds an inconsistent sparse matrix");
    for (std::size_t k = 0; k + 1 < outer.size(); ++k)
      if (outer[k] > outer[k + 1]) throw ArchiveError("the checkpoint holds an inconsistent sparse matrix");
    for (I i : inner)
      if (i < 0 || static_cast<std::uint64_t>(i) >= (T::IsRowMajor ? cols : rows))
        throw ArchiveError("the checkpoint holds an inconsistent sparse matrix");
    value = Eigen::Map<const T>(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols),
                                static_cast<Eigen::Index>(values.size()), outer.data(), inner.data(), values.data());
  } else if constexpr (std::is_aggregate_v<T> && std::is_class_v<T>) {
    boost::pfr::for_each_field(value, [&](auto& field) { unarchive(r, field); });
  } else {
    static_assert(no_rule<T>, "no archive rule for this type: give it an archive_fields overload");
  }
}

}  // namespace moreau
