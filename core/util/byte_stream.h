#pragma once
/// Little-endian byte buffers for handing results between processes (the ranks of an MPI job,
/// app/mpi/ranks.h): a part of a dataset or of a training run is written into one std::string on one
/// rank and read back on another. Numbers keep their exact bits (doubles are copied, never printed),
/// so what is read equals what was written. The format is private to one build talking to itself:
/// it has no version and is never stored in a file.

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace rrf {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "byte streams are little-endian");

/// Appends values to a byte string.
class ByteWriter {
public:
    void u64(uint64_t v) { raw(&v, sizeof v); }
    void i64(int64_t v) { raw(&v, sizeof v); }
    void f64(double v) { raw(&v, sizeof v); }
    /// A length (u64) followed by the bytes.
    void string(const std::string& s) {
        u64(s.size());
        bytes_.append(s);
    }
    /// A count (u64) followed by the floats.
    void floats(const std::vector<float>& v) {
        u64(v.size());
        raw(v.data(), v.size() * sizeof(float));
    }
    const std::string& bytes() const { return bytes_; }
    std::string take() { return std::move(bytes_); }

private:
    void raw(const void* p, size_t n) { bytes_.append(static_cast<const char*>(p), n); }
    std::string bytes_;
};

/// Reads what a ByteWriter wrote, in the same order. Reading past the end or a length larger than
/// what is left throws std::runtime_error naming `source` (a truncated or mismatched transfer).
class ByteReader {
public:
    ByteReader(const std::string& bytes, std::string source) : bytes_(bytes), source_(std::move(source)) {}
    uint64_t u64() { return pod<uint64_t>(); }
    int64_t i64() { return pod<int64_t>(); }
    double f64() { return pod<double>(); }
    std::string string() {
        const uint64_t n = u64();
        need(n);
        std::string s = bytes_.substr(at_, size_t(n));
        at_ += size_t(n);
        return s;
    }
    std::vector<float> floats() {
        const uint64_t n = u64();
        if (n > (bytes_.size() - at_) / sizeof(float)) fail();
        std::vector<float> v(static_cast<size_t>(n));
        std::memcpy(v.data(), bytes_.data() + at_, size_t(n) * sizeof(float));
        at_ += size_t(n) * sizeof(float);
        return v;
    }
    /// True when every byte was read.
    bool atEnd() const { return at_ == bytes_.size(); }

private:
    template <class T>
    T pod() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    void need(uint64_t n) const {
        if (n > bytes_.size() - at_) fail();
    }
    [[noreturn]] void fail() const;

    const std::string& bytes_;
    std::string source_;
    size_t at_ = 0;
};

}  // namespace rrf
