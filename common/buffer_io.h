#pragma once
// Files parsed from one in-memory buffer, and text written through one: the machinery every
// reader and writer of both meshes shares (Medit, Gmsh, VTU, .sol). A text tokenizer that
// tracks line numbers, a bounds-checked binary cursor on the same buffer, a buffered writer.
//
// Why one buffer: parsing from memory with std::from_chars skips iostream's per-token work,
// Gmsh binary files interleave text lines and binary blocks, and bounding every count read from
// a header by the bytes left in the buffer makes corrupted headers harmless (no huge reserve).

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace hdimesh::io
{

/// The largest magnitude a number read from a file may have. Files hold coordinates and sizes
/// only; beyond this their sixth powers (volumes, quality) or the front's float boxes overflow.
inline constexpr double kMaxMagnitude = 1e30;

/// Reads the whole file. IoError when it cannot be opened or read.
std::string load_file(const std::string& path);

/// Lower-case extension with its dot (".mesh"), or "" when there is none.
std::string lower_extension(const std::string& path);

/// "1e+308 exceeds 1e+30 in magnitude, the largest a coordinate or size may have".
std::string too_large(double value);

/// Whitespace-separated tokens of a text buffer, with the line of the last token read.
/// Every failure throws InputError "path:line: message".
class TextReader
{
public:
    /// comment: a character starting a comment running to the end of the line (0 for none).
    TextReader(const std::string& path, std::string_view text, char comment);

    /// True when only whitespace and comments remain.
    bool at_end();
    /// The next token; `what` names the expected item for the end-of-file message.
    std::string_view token(const char* what);
    long long integer(const char* what);
    /// An integer that must fit in [lo, hi].
    long long integer_in(const char* what, long long lo, long long hi);
    /// A finite double of magnitude <= kMaxMagnitude (others are rejected with the line).
    double real(const char* what);
    /// An item count read from a header, bounded by the bytes left: each item needs at least
    /// min_bytes_per_item characters, so a corrupted count cannot make a reader allocate more
    /// than the file could hold.
    std::size_t count(const char* what, std::size_t min_bytes_per_item);
    /// Skips the rest of the current line (the newline included).
    void skip_line();
    /// Byte offset of the read position (just after the last token).
    std::size_t position() const { return pos_; }
    void set_position(std::size_t pos, int line);
    int line() const { return token_line_; }
    int current_line() const { return line_; }
    const std::string& path() const { return path_; }
    [[noreturn]] void fail(const std::string& message) const;

private:
    void skip_blanks();
    const std::string& path_;
    std::string_view text_;
    char comment_;
    /// Per byte: 0 part of a token, 1 blank, 2 newline, 3 comment start (one table lookup per
    /// character instead of a chain of comparisons: the tokenizer is the hot loop of ASCII reads)
    unsigned char kind_[256];
    std::size_t pos_ = 0;
    int line_ = 1;
    int token_line_ = 1;
};

/// A bounds-checked little/big-endian cursor over a byte buffer. Failures throw InputError
/// "path: byte N: message".
class BinaryReader
{
public:
    BinaryReader(const std::string& path, std::string_view data, std::size_t pos, bool swap)
        : path_(path), data_(data), pos_(pos), swap_(swap)
    {
    }

    template <class T>
    T get(const char* what)
    {
        static_assert(std::is_trivially_copyable_v<T>);
        if (pos_ > data_.size() || data_.size() - pos_ < sizeof(T))
            fail(std::string("unexpected end of file while reading ") + what);
        T value;
        std::memcpy(&value, data_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        if (swap_) value = byte_swapped(value);
        return value;
    }

    /// Reads an integer stored as T and checks it fits in [lo, hi].
    template <class T>
    long long integer_in(const char* what, long long lo, long long hi)
    {
        const T raw = get<T>(what);
        if constexpr (std::is_unsigned_v<T>)
        {
            if (static_cast<unsigned long long>(raw) > static_cast<unsigned long long>(hi))
                fail(std::string(what) + " " + std::to_string(raw) + " out of range [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
            if (static_cast<long long>(raw) < lo)
                fail(std::string(what) + " " + std::to_string(raw) + " out of range");
            return static_cast<long long>(raw);
        }
        else
        {
            const long long v = static_cast<long long>(raw);
            if (v < lo || v > hi)
                fail(std::string(what) + " " + std::to_string(v) + " out of range [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
            return v;
        }
    }

    /// A finite number stored as T (float or double), of magnitude <= kMaxMagnitude.
    template <class T>
    double real(const char* what)
    {
        const double v = static_cast<double>(get<T>(what));
        if (!(v - v == 0.0)) fail(std::string(what) + " is not a finite number");
        if (std::abs(v) > kMaxMagnitude) fail(std::string(what) + " " + too_large(v));
        return v;
    }

    /// Checks that `items` records of `bytes_per_item` bytes fit in what is left.
    void require(unsigned long long items, std::size_t bytes_per_item, const char* what) const;

    std::size_t position() const { return pos_; }
    void seek(std::size_t pos, const char* what);
    std::size_t size() const { return data_.size(); }
    bool swapped() const { return swap_; }
    void set_swap(bool swap) { swap_ = swap; }
    [[noreturn]] void fail(const std::string& message) const;

    template <class T>
    static T byte_swapped(T value)
    {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
            std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }

private:
    const std::string& path_;
    std::string_view data_;
    std::size_t pos_;
    bool swap_;
};

/// Appends text and raw bytes to a buffer flushed to the stream every few megabytes, with
/// numbers printed by std::to_chars (shortest form that reads back to the same double).
class TextWriter
{
public:
    explicit TextWriter(std::ostream& out) : out_(out) { buffer_.reserve(kFlushBytes + 4096); }
    ~TextWriter() = default;
    TextWriter(const TextWriter&) = delete;
    TextWriter& operator=(const TextWriter&) = delete;

    TextWriter& text(std::string_view s)
    {
        buffer_.append(s);
        maybe_flush();
        return *this;
    }
    TextWriter& character(char c)
    {
        buffer_.push_back(c);
        return *this;
    }
    TextWriter& integer(long long v)
    {
        char tmp[24];
        const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
        buffer_.append(tmp, r.ptr);
        maybe_flush();
        return *this;
    }
    /// Shortest round-trip representation: reading it back gives the same bits.
    TextWriter& real(double v)
    {
        char tmp[32];
        const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
        buffer_.append(tmp, r.ptr);
        maybe_flush();
        return *this;
    }
    template <class T>
    TextWriter& raw(const T& value)
    {
        static_assert(std::is_trivially_copyable_v<T>);
        buffer_.append(reinterpret_cast<const char*>(&value), sizeof(T));
        maybe_flush();
        return *this;
    }
    TextWriter& bytes(const void* data, std::size_t n)
    {
        buffer_.append(static_cast<const char*>(data), n);
        maybe_flush();
        return *this;
    }
    /// Bytes written so far (flushed and buffered).
    std::size_t offset() const { return flushed_ + buffer_.size(); }
    void flush();

private:
    static constexpr std::size_t kFlushBytes = std::size_t(4) << 20;
    void maybe_flush()
    {
        if (buffer_.size() >= kFlushBytes) flush();
    }
    std::ostream& out_;
    std::string buffer_;
    std::size_t flushed_ = 0;
};

/// "path:line: message" / "path: message" as an InputError.
[[noreturn]] void throw_input(const std::string& path, const std::string& message);

}  // namespace hdimesh::io
