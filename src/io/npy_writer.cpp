// io/npy_writer.cpp — NumPy .npy, format version 1.0
// (numpy.lib.format: magic "\x93NUMPY", version 1 0, a little-endian uint16
// header length, then a Python dict literal padded with spaces and ending in
// '\n' so that the data starts at a multiple of 64 bytes).
#include <bit>
#include <cstdint>
#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "polyvol/grid_io.hpp"
#include "core/bit_cast.hpp"

namespace polyvol {

void write_npy(const std::string& path, std::span<const double> data, std::span<const std::size_t> shape) {
    std::size_t count = 1;
    std::string dims;  // "a, b, c", or "a," for one axis (a Python tuple)
    for (std::size_t n : shape) {
        count *= n;
        dims += (dims.empty() ? "" : ", ") + std::to_string(n);
    }
    if (shape.size() == 1) dims += ',';
    if (count != data.size())
        throw std::invalid_argument(path + ": the shape does not match the number of values");
    std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + dims + "), }";
    const std::size_t unpadded = 10 + header.size() + 1;
    header.append((64 - unpadded % 64) % 64, ' ');
    header += '\n';
    if (header.size() > 65535) throw std::invalid_argument(path + ": npy header too long");
    std::string prefix = "\x93NUMPY";
    prefix += '\x01';
    prefix += '\x00';
    prefix += static_cast<char>(header.size() & 0xFF);
    prefix += static_cast<char>(header.size() >> 8);

    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    bool ok = std::fwrite(prefix.data(), 1, prefix.size(), f.get()) == prefix.size() &&
              std::fwrite(header.data(), 1, header.size(), f.get()) == header.size();
    if constexpr (std::endian::native == std::endian::little) {
        ok = ok && std::fwrite(data.data(), sizeof(double), data.size(), f.get()) == data.size();
    } else {
        std::vector<unsigned char> block(8);
        for (std::size_t i = 0; ok && i < data.size(); ++i) {
            const uint64_t bits = core::bit_cast<uint64_t>(data[i]);
            for (int b = 0; b < 8; ++b) block[b] = static_cast<unsigned char>(bits >> (8 * b));
            ok = std::fwrite(block.data(), 1, 8, f.get()) == 8;
        }
    }
    if (!ok || std::fflush(f.get()) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace polyvol
