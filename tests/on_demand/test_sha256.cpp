// SHA-256 (runtime/src/sha256.hpp) against the test vectors of FIPS 180-4's examples (NIST CSRC "SHA256.pdf",
// "SHA2_Additional.pdf"): the checksums of on-demand objects are only as good as this.
#include <catch2/catch.hpp>
#include <string>

#include "on_demand/sha256.hpp"

using hubbeam::Sha256;

namespace {

std::string sha256(const std::string& s)
{
    Sha256 h;
    h.add(s);
    return h.hex();
}

}  // namespace

TEST_CASE("SHA-256 gives the published digests", "[sha256]")
{
    CHECK(sha256("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    CHECK(sha256("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    // 448 bits: the padding needs a second block.
    CHECK(sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    CHECK(sha256(std::string(1000000, 'a')) == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    // 55 and 56 bytes, the last length whose padding fits in one block and the first that does not (digests from
    // coreutils' sha256sum).
    CHECK(sha256(std::string(55, 'a')) == "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
    CHECK(sha256(std::string(56, 'a')) == "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
}

TEST_CASE("SHA-256 of pieces is the SHA-256 of the whole", "[sha256]")
{
    std::string text;
    for (int i = 0; i < 1000; ++i) text += static_cast<char>(i * 37 % 251);
    for (std::size_t piece : {1u, 7u, 63u, 64u, 65u, 500u}) {
        Sha256 h;
        for (std::size_t at = 0; at < text.size(); at += piece) h.add(text.substr(at, piece));
        CHECK(h.hex() == sha256(text));
    }
}
