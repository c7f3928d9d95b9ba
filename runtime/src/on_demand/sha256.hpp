// SHA-256 (FIPS 180-4), for the checksums of on-demand objects: no library this project links provides it, and a
// checksum must be computed before an object is loaded.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace hubbeam {

/// An incremental SHA-256: add() the bytes in any pieces, then hex() once.
class Sha256 {
public:
    Sha256();
    void add(const void* data, std::size_t size);
    void add(std::string_view s) { add(s.data(), s.size()); }
    /// The digest as 64 lower-case hexadecimal digits; the object is spent afterwards.
    std::string hex();

private:
    void block(const unsigned char* p);
    std::array<std::uint32_t, 8> h_;
    std::array<unsigned char, 64> buffer_{};
    std::size_t buffered_ = 0;
    std::uint64_t length_ = 0;  // bytes added
};

}  // namespace hubbeam
