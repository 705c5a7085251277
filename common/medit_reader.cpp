#include "common/medit_reader.h"

#include <climits>
#include <cstdint>
#include <string>

namespace hdimesh::medit
{

int read_ascii_keywords(io::TextReader& in, EndKeyword end, const char* file_kind,
                        const std::function<bool(std::string_view keyword)>& read_section)
{
    bool seen_end = false;
    int keywords = 0;
    while (!in.at_end())
    {
        const std::string_view keyword = in.token("keyword");
        if (keyword == "End")
        {
            seen_end = true;
            break;
        }
        if (keyword == "MeshVersionFormatted")
            in.integer_in("MeshVersionFormatted", 1, 4);
        else if (keyword == "Dimension")
        {
            if (in.integer("Dimension") != 3) in.fail("only Dimension 3 is supported");
        }
        else if (!read_section(keyword))
        {
            in.fail("unknown keyword '" + std::string(keyword.substr(0, 60)) + "'" +
                    (file_kind ? std::string(" in a ") + file_kind : std::string()));
        }
        ++keywords;
    }
    if (end == EndKeyword::Required && !seen_end)
    {
        if (keywords == 0) in.fail("no Medit keyword found (not a Medit file?)");
        in.set_position(in.position(), in.current_line());
        in.fail("missing End keyword (truncated file?)");
    }
    return keywords;
}

BinaryFile::BinaryFile(io::BinaryReader& in) : in_(in)
{
    const std::int32_t magic = in_.get<std::int32_t>("magic number");
    if (magic != 1)
    {
        if (io::BinaryReader::byte_swapped(magic) != 1)
            in_.fail("not a Medit binary file (magic number " + std::to_string(magic) +
                     ", expected 1)");
        in_.set_swap(true);
    }
    version_ = static_cast<int>(in_.integer_in<std::int32_t>("version", 1, 4));
    int_bytes_ = version_ == 4 ? 8 : 4;
    real_bytes_ = version_ == 1 ? 4 : 8;
    position_bytes_ = version_ >= 3 ? 8 : 4;
}

BinaryFile::Keyword BinaryFile::keyword()
{
    if (in_.position() >= in_.size()) in_.fail("missing End keyword (truncated file?)");
    const int code = in_.get<std::int32_t>("keyword code");
    // End carries a (zero) position too, as libMeshb and meshio write it: requiring it catches
    // files cut inside the last keyword
    const long long next = position_bytes_ == 8
                               ? in_.integer_in<std::int64_t>("next keyword position", 0, LLONG_MAX)
                               : in_.integer_in<std::int32_t>("next keyword position", 0, INT_MAX);
    return {code, next};
}

long long BinaryFile::count(const char* what, std::size_t bytes_per_item)
{
    const long long n = integer(what, 0, INT_MAX);
    in_.require(static_cast<unsigned long long>(n), bytes_per_item, what);
    return n;
}

long long BinaryFile::integer(const char* what, long long lo, long long hi)
{
    return int_bytes_ == 8 ? in_.integer_in<std::int64_t>(what, lo, hi)
                           : in_.integer_in<std::int32_t>(what, lo, hi);
}

double BinaryFile::real(const char* what)
{
    return real_bytes_ == 4 ? in_.real<float>(what) : in_.real<double>(what);
}

void BinaryFile::dimension()
{
    if (in_.get<std::int32_t>("dimension") != 3) in_.fail("only dimension 3 is supported");
}

}  // namespace hdimesh::medit
