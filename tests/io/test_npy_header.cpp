// The .npy header as NEP 1 (numpy's format 1.0) asks: magic, version, the dict's length, the dict padded with spaces
// and a newline so that the whole header is a multiple of 64 bytes, for every shape, dtype and size a file can have.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <hubbeam/npz.hpp>

using namespace hubbeam;

namespace {

/// The header's length as the file states it: 10 bytes of magic, version and length, then the dict.
std::size_t stated_length(const std::string& npy)
{
    REQUIRE(npy.size() >= 10);
    REQUIRE(npy.compare(0, 8, std::string("\x93NUMPY\x01\x00", 8)) == 0);
    return 10 + (static_cast<unsigned char>(npy[8]) | static_cast<std::size_t>(static_cast<unsigned char>(npy[9])) << 8);
}

}  // namespace

TEST_CASE("every .npy header is a multiple of 64 bytes and ends its dict with a newline", "[output]")
{
    std::vector<std::string> shapes = {"(0,)", "(3,)", "(0, 0)", "(1, 1)", "(3001, 10)", "(123456789012, 99)"};
    std::string wide = "(";  // a dict longer than 64 and than 128 bytes
    for (int i = 0; i < 30; ++i) wide += "7, ";
    shapes.push_back(wide + "7)");
    for (const std::string& shape : shapes) {
        for (const char* descr : {"<f8", "<U12", "<U400"}) {
            for (const std::size_t min_size : {std::size_t{0}, std::size_t{64}, std::size_t{128}}) {
                const std::string h = npy_header(descr, shape, min_size);
                INFO(descr << " " << shape << " at least " << min_size << ": " << h.size() << " bytes");
                CHECK(h.size() % 64 == 0);
                CHECK(h.size() >= min_size);
                CHECK(stated_length(h) == h.size());
                CHECK(h.back() == '\n');
                CHECK(h.find(shape) != std::string::npos);
            }
        }
    }
}

TEST_CASE("an array's .npy bytes: an aligned header, then the values in C order", "[output]")
{
    Eigen::MatrixXd m(3, 2);
    m << 1.0, -2.5, 1e-300, 3.0, 0.0, -0.0;
    const std::string npy = npy_matrix(m);
    const std::size_t at = stated_length(npy);
    CHECK(at % 64 == 0);
    REQUIRE(npy.size() == at + 6 * 8);
    for (Eigen::Index i = 0; i < 3; ++i)
        for (Eigen::Index j = 0; j < 2; ++j) {
            std::uint64_t bits = 0;
            for (int b = 0; b < 8; ++b)
                bits |= static_cast<std::uint64_t>(static_cast<unsigned char>(npy[at + 8 * (2 * i + j) + b])) << (8 * b);
            CHECK(std::bit_cast<std::uint64_t>(m(i, j)) == bits);
        }
    const std::string names = npy_strings({"tip_uy", "theta", "a name longer than the others"});
    CHECK(stated_length(names) % 64 == 0);
    CHECK(names.size() == stated_length(names) + 3 * 29 * 4);  // UTF-32, the longest name's width
}
