// FaceIndices: a face's vertex indices, stored inline up to four (a triangle or a quad, what
// every face is after loading) and on the heap beyond. 24 bytes per face with no allocation,
// where std::vector<int> took 24 bytes plus a 32-byte heap block: at 10 million triangles the
// faces alone went from 560 MB to 240 MB. Keeps the std::vector<int> calls the code uses.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <ostream>
#include <utility>
#include <vector>

namespace radkit {

class FaceIndices {
 public:
  using value_type = int;
  using size_type = std::size_t;
  using difference_type = std::ptrdiff_t;
  using reference = int&;
  using const_reference = const int&;
  using pointer = int*;
  using const_pointer = const int*;
  using iterator = int*;
  using const_iterator = const int*;

  static constexpr std::uint32_t kInline = 4;

  FaceIndices() = default;
  FaceIndices(std::initializer_list<int> values) { assign(values.begin(), values.end()); }
  FaceIndices(const std::vector<int>& values) {  // NOLINT: implicit, as Face{v} was written
    assign(values.data(), values.data() + values.size());
  }
  template <class It, class = decltype(*std::declval<It>())>
  FaceIndices(It first, It last) {
    for (; first != last; ++first) push_back(int(*first));
  }
  FaceIndices(const FaceIndices& other) { assign(other.begin(), other.end()); }
  FaceIndices(FaceIndices&& other) noexcept { take(other); }
  FaceIndices& operator=(const FaceIndices& other) {
    if (this != &other) assign(other.begin(), other.end());
    return *this;
  }
  FaceIndices& operator=(FaceIndices&& other) noexcept {
    if (this != &other) {
      release();
      take(other);
    }
    return *this;
  }
  FaceIndices& operator=(std::initializer_list<int> values) {
    assign(values.begin(), values.end());
    return *this;
  }
  FaceIndices& operator=(const std::vector<int>& values) {
    assign(values.data(), values.data() + values.size());
    return *this;
  }
  ~FaceIndices() { release(); }

  /// A copy as a std::vector (for code that keeps or edits a face's list as one).
  operator std::vector<int>() const { return std::vector<int>(begin(), end()); }

  std::size_t size() const { return m_size; }
  bool empty() const { return m_size == 0; }
  std::size_t capacity() const { return m_capacity; }
  int* data() { return onHeap() ? m_heap : m_inline; }
  const int* data() const { return onHeap() ? m_heap : m_inline; }
  int* begin() { return data(); }
  int* end() { return data() + m_size; }
  const int* begin() const { return data(); }
  const int* end() const { return data() + m_size; }
  const int* cbegin() const { return begin(); }
  const int* cend() const { return end(); }
  int& operator[](std::size_t k) { return data()[k]; }
  const int& operator[](std::size_t k) const { return data()[k]; }
  int& at(std::size_t k) { return data()[k]; }
  const int& at(std::size_t k) const { return data()[k]; }
  int& front() { return data()[0]; }
  const int& front() const { return data()[0]; }
  int& back() { return data()[m_size - 1]; }
  const int& back() const { return data()[m_size - 1]; }

  void reserve(std::size_t n) {
    if (n <= m_capacity) return;
    int* heap = new int[n];
    std::memcpy(heap, data(), m_size * sizeof(int));
    if (onHeap()) delete[] m_heap;
    m_heap = heap;
    m_capacity = std::uint32_t(n);
  }
  void push_back(int v) {
    if (m_size == m_capacity) reserve(std::size_t(m_capacity) * 2);
    data()[m_size++] = v;
  }
  void emplace_back(int v) { push_back(v); }
  void pop_back() { --m_size; }
  void clear() { m_size = 0; }
  void resize(std::size_t n, int value = 0) {
    reserve(n);
    for (std::size_t k = m_size; k < n; ++k) data()[k] = value;
    m_size = std::uint32_t(n);
  }
  template <class It>
  void assign(It first, It last) {
    clear();
    reserve(std::size_t(std::distance(first, last)));
    for (; first != last; ++first) data()[m_size++] = int(*first);
  }
  int* erase(const int* at) {
    int* p = begin() + (at - begin());
    std::copy(p + 1, end(), p);
    --m_size;
    return p;
  }
  int* insert(const int* at, int v) {
    const std::ptrdiff_t k = at - begin();
    push_back(v);
    std::rotate(begin() + k, end() - 1, end());
    return begin() + k;
  }

  friend bool operator==(const FaceIndices& a, const FaceIndices& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator!=(const FaceIndices& a, const FaceIndices& b) { return !(a == b); }
  friend bool operator<(const FaceIndices& a, const FaceIndices& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
  }
  friend bool operator==(const FaceIndices& a, const std::vector<int>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator==(const std::vector<int>& a, const FaceIndices& b) { return b == a; }
  friend bool operator!=(const FaceIndices& a, const std::vector<int>& b) { return !(a == b); }
  friend bool operator!=(const std::vector<int>& a, const FaceIndices& b) { return !(b == a); }
  friend std::ostream& operator<<(std::ostream& out, const FaceIndices& f) {
    out << '{';
    for (std::size_t k = 0; k < f.size(); ++k) out << (k ? ", " : "") << f[k];
    return out << '}';
  }

 private:
  bool onHeap() const { return m_capacity > kInline; }
  void release() {
    if (onHeap()) delete[] m_heap;
    m_capacity = kInline;
    m_size = 0;
  }
  void take(FaceIndices& other) {
    m_size = other.m_size;
    m_capacity = other.m_capacity;
    if (other.onHeap())
      m_heap = other.m_heap;
    else
      std::memcpy(m_inline, other.m_inline, sizeof m_inline);
    other.m_capacity = kInline;
    other.m_size = 0;
  }

  union {
    int m_inline[kInline] = {0, 0, 0, 0};
    int* m_heap;
  };
  std::uint32_t m_size = 0;
  std::uint32_t m_capacity = kInline;
};

static_assert(sizeof(FaceIndices) == 24, "a face's indices fit in 24 bytes");

}  // namespace radkit
