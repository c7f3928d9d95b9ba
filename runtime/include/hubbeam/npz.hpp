// NumPy's file formats written without numpy: an array as .npy bytes, and a .npz archive of named arrays (a zip
// of .npy entries, stored uncompressed), which numpy.load reads as a dict.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <utility>
#include <vector>

namespace hubbeam {

/// A .npy header (format 1.0) for an array of dtype descr ("<f8", "<U12") and shape text ("(3, 4)", "(5,)"),
/// padded with spaces to a multiple of 64 bytes (numpy's alignment of the data), at least min_size.
std::string npy_header(const std::string& descr, const std::string& shape, std::size_t min_size = 64);
/// The .npy bytes of a matrix of little-endian doubles in C order.
std::string npy_matrix(const Eigen::MatrixXd& m);
/// The .npy bytes of a 1-D array of strings (numpy's fixed-width unicode, UTF-32; the strings are ASCII names).
std::string npy_strings(const std::vector<std::string>& items);
/// The bytes of a .npz: a zip archive holding NAME.npy for each (NAME, .npy bytes), uncompressed, each with its
/// CRC-32, as numpy.savez writes them.
std::string npz_archive(const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace hubbeam
