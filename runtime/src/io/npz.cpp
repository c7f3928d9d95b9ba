// NumPy's .npy and .npz formats (npz.hpp).
#include <hubbeam/npz.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <zlib.h>

namespace hubbeam {

namespace {

/// Appends v as n little-endian bytes.
void put(std::string& out, std::uint64_t v, int n)
{
    for (int i = 0; i < n; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

}  // namespace

std::string npy_header(const std::string& descr, const std::string& shape, std::size_t min_size)
{
    std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
    const std::size_t prefix = 10;  // "\x93NUMPY", 1, 0, the dict's length (2 bytes, little-endian)
    std::size_t size = std::max<std::size_t>(min_size, 64);
    while (size < prefix + dict.size() + 1) size += 64;
    dict.append(size - prefix - 1 - dict.size(), ' ');
    dict += '\n';
    std::string h("\x93NUMPY\x01\x00", 8);
    put(h, dict.size(), 2);
    return h + dict;
}

std::string npy_matrix(const Eigen::MatrixXd& m)
{
    std::string out = npy_header("<f8", "(" + std::to_string(m.rows()) + ", " + std::to_string(m.cols()) + ")");
    for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index j = 0; j < m.cols(); ++j) put(out, std::bit_cast<std::uint64_t>(m(i, j)), 8);
    return out;
}

std::string npy_strings(const std::vector<std::string>& items)
{
    std::size_t width = 1;
    for (const std::string& s : items) width = std::max(width, s.size());
    std::string out = npy_header("<U" + std::to_string(width), "(" + std::to_string(items.size()) + ",)");
    for (const std::string& s : items)
        for (std::size_t i = 0; i < width; ++i) put(out, i < s.size() ? static_cast<unsigned char>(s[i]) : 0, 4);
    return out;
}

std::string npz_archive(const std::vector<std::pair<std::string, std::string>>& entries)
{
    // The zip format's local headers, then the central directory and its end record (no zip64: the entries
    // are matrices of a linearized model, far below 4 GiB).
    std::string out, directory;
    for (const auto& [name, data] : entries) {
        const std::string file = name + ".npy";
        if (data.size() >= 0xffffffffu) throw std::length_error("npz: entry " + file + " too large");
        const auto crc = static_cast<std::uint32_t>(
            crc32(0L, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
        const std::uint64_t offset = out.size();
        const auto common = [&](std::string& h) {
            put(h, 20, 2);  // version needed: 2.0
            put(h, 0, 2);   // flags
            put(h, 0, 2);   // stored, not compressed
            put(h, 0, 2);   // time
            put(h, 0x21, 2);  // date: 1980-01-01
            put(h, crc, 4);
            put(h, data.size(), 4);
            put(h, data.size(), 4);
            put(h, file.size(), 2);
            put(h, 0, 2);  // extra field length
        };
        put(out, 0x04034b50, 4);
        common(out);
        out += file;
        out += data;
        put(directory, 0x02014b50, 4);
        put(directory, 20, 2);  // made by: 2.0
        common(directory);
        put(directory, 0, 2);  // comment length
        put(directory, 0, 2);  // disk
        put(directory, 0, 2);  // internal attributes
        put(directory, 0, 4);  // external attributes
        put(directory, offset, 4);
        directory += file;
    }
    const std::uint64_t at = out.size();
    out += directory;
    put(out, 0x06054b50, 4);
    put(out, 0, 2);
    put(out, 0, 2);
    put(out, entries.size(), 2);
    put(out, entries.size(), 2);
    put(out, directory.size(), 4);
    put(out, at, 4);
    put(out, 0, 2);  // comment length
    return out;
}

}  // namespace hubbeam
