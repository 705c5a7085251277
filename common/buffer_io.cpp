#include "common/buffer_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <fstream>

#include "common/errors.h"

namespace hdimesh::io
{

std::string load_file(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path + ": cannot open: " + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw IoError(path + ": cannot read (not a regular file?)");
    in.seekg(0, std::ios::beg);
    std::string data(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(data.data(), size)) throw IoError(path + ": read failed");
    return data;
}

std::string lower_extension(const std::string& path)
{
    const auto slash = path.find_last_of("/\\");
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void throw_input(const std::string& path, const std::string& message)
{
    throw InputError(path + ": " + message);
}

// --- TextReader

TextReader::TextReader(const std::string& path, std::string_view text, char comment)
    : path_(path), text_(text), comment_(comment)
{
    std::memset(kind_, 0, sizeof(kind_));
    for (unsigned char c : {' ', '\t', '\r', '\f', '\v'}) kind_[c] = 1;
    kind_[static_cast<unsigned char>('\n')] = 2;
    if (comment_ != 0) kind_[static_cast<unsigned char>(comment_)] = 3;
}

void TextReader::skip_blanks()
{
    const std::size_t n = text_.size();
    const char* text = text_.data();
    while (pos_ < n)
    {
        const unsigned char kind = kind_[static_cast<unsigned char>(text[pos_])];
        if (kind == 0) break;
        if (kind == 2) ++line_;
        if (kind == 3)
            while (pos_ < n && text[pos_] != '\n') ++pos_;
        else
            ++pos_;
    }
}

bool TextReader::at_end()
{
    skip_blanks();
    return pos_ >= text_.size();
}

std::string_view TextReader::token(const char* what)
{
    skip_blanks();
    token_line_ = line_;
    if (pos_ >= text_.size()) fail(std::string("unexpected end of file while reading ") + what);
    const std::size_t start = pos_;
    const std::size_t n = text_.size();
    const char* text = text_.data();
    while (pos_ < n && kind_[static_cast<unsigned char>(text[pos_])] == 0) ++pos_;
    return text_.substr(start, pos_ - start);
}

namespace
{

std::string printable(std::string_view token)
{
    std::string s(token.substr(0, 40));
    for (char& c : s)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return token.size() > 40 ? s + "..." : s;
}

}  // namespace

long long TextReader::integer(const char* what)
{
    std::string_view t = token(what);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    // fast path: up to 18 plain digits cannot overflow (the common case by far)
    if (!t.empty() && t.size() <= 18)
    {
        long long value = 0;
        std::size_t i = t[0] == '-' ? 1 : 0;
        bool digits = i < t.size();
        for (; i < t.size() && digits; ++i)
        {
            const unsigned d = static_cast<unsigned>(t[i] - '0');
            digits = d <= 9;
            value = 10 * value + d;
        }
        if (digits) return t[0] == '-' ? -value : value;
    }
    long long value = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || t.empty())
        fail(std::string("expected an integer (") + what + "), got '" + printable(t) + "'");
    return value;
}

long long TextReader::integer_in(const char* what, long long lo, long long hi)
{
    const long long v = integer(what);
    if (v < lo || v > hi)
        fail(std::string(what) + " " + std::to_string(v) + " out of range [" + std::to_string(lo) +
             ", " + std::to_string(hi) + "]");
    return v;
}

std::string too_large(double value)
{
    const auto text = [](double v) {
        char buffer[32];
        return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
    };
    return text(value) + " exceeds " + text(kMaxMagnitude) +
           " in magnitude, the largest a coordinate or size may have";
}

double TextReader::real(const char* what)
{
    std::string_view t = token(what);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double value = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
    if (r.ec == std::errc::result_out_of_range)
        fail(std::string(what) + " '" + printable(t) + "' is out of the double range");
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || t.empty())
        fail(std::string("expected a number (") + what + "), got '" + printable(t) + "'");
    if (!std::isfinite(value)) fail(std::string(what) + " is not finite: '" + printable(t) + "'");
    if (std::abs(value) > kMaxMagnitude) fail(std::string(what) + " " + too_large(value));
    return value;
}

std::size_t TextReader::count(const char* what, std::size_t min_bytes_per_item)
{
    const long long n = integer(what);
    if (n < 0) fail(std::string("negative count for ") + what + ": " + std::to_string(n));
    const std::size_t left = text_.size() - std::min(pos_, text_.size());
    if (static_cast<unsigned long long>(n) > left / std::max<std::size_t>(min_bytes_per_item, 1))
        fail(std::string("count ") + std::to_string(n) + " for " + what +
             " exceeds what the rest of the file can hold (truncated or corrupted file)");
    return static_cast<std::size_t>(n);
}

void TextReader::skip_line()
{
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size())
    {
        ++pos_;
        ++line_;
    }
}

void TextReader::set_position(std::size_t pos, int line)
{
    pos_ = std::min(pos, text_.size());
    line_ = line;
    token_line_ = line;
}

void TextReader::fail(const std::string& message) const
{
    throw InputError(path_ + ":" + std::to_string(token_line_) + ": " + message);
}

// --- BinaryReader

void BinaryReader::require(unsigned long long items, std::size_t bytes_per_item,
                           const char* what) const
{
    const std::size_t left = pos_ <= data_.size() ? data_.size() - pos_ : 0;
    if (items > left / std::max<std::size_t>(bytes_per_item, 1))
        fail("count " + std::to_string(items) + " for " + what +
             " exceeds what the rest of the file can hold (truncated or corrupted file)");
}

void BinaryReader::seek(std::size_t pos, const char* what)
{
    if (pos > data_.size()) fail(std::string(what) + " points past the end of the file");
    pos_ = pos;
}

void BinaryReader::fail(const std::string& message) const
{
    throw InputError(path_ + ": byte " + std::to_string(pos_) + ": " + message);
}

// --- TextWriter

void TextWriter::flush()
{
    // a failed stream is reported with the file name by write_file_atomically
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    flushed_ += buffer_.size();
    buffer_.clear();
}

}  // namespace hdimesh::io
